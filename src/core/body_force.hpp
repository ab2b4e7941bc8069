#pragma once
// A spatially varying body force on the particles (`[body_force]`, docs/case-file.md): an
// acceleration a(x) in m/s^2 that every particle feels in addition to `simulation.gravity`,
// per unit of its own mass (F_i = m_i a(x_i)). The fluid of a coupled run does not feel it (no
// buoyancy: a(x) is not a gradient, see below, so a fluid driven by it would not stay at rest).
//
// "sinusoidal_cube": the three-dimensional sinusoidal "gravitational" field of the [Chang08]
// binary-collision test problem (Chang, Lin & Liu, "Applicability limit of binary collision
// model in dense particle flow", AIP Conf. Proc. 2008, eq. 1). The paper's equation is lost in
// the extracted text except its shape, A (cos cos e_x + cos cos e_y + cos cos e_z), and its
// description (collision centres CC at (L/4, L/4, L/4) and (3L/4, 3L/4, 3L/4), a nonzero mean
// velocity at the geometric centre GC). ASSUMPTION (our reconstruction, docs: cases/chang08/
// README.md), with k = 2 pi / wavelength and (x, y, z) measured from `origin`:
//
//   a_x = A cos(k y) cos(k z),   a_y = A cos(k z) cos(k x),   a_z = A cos(k x) cos(k y).
//
// Each component does not depend on its own coordinate, so div a = 0, and a = 0 at both CC
// (every cosine vanishes at L/4 and 3L/4) while a = (A, A, A) at GC and at the corners: the flow
// passes through GC. Near a CC, a = A k^2 (eta zeta, zeta xi, xi eta) (xi = x - x_CC, ...),
// the gradient of A k^2 xi eta zeta: streams from orthogonal directions meet there. Other fits:
// the cyclic products (cos kx cos ky, cos ky cos kz, cos kz cos kx) and (cos kx cos kz, ...) also
// vanish at CC and are (A, A, A) at GC, and cos-sin products make CC true sinks. A parcel-tracking
// check (linear drag, tau = 0.3 and 1 s, no collisions, 20 s) put the particles at both CC in
// all of them, but only this field keeps GC denser than the mean (3.5 times the mean number
// density within 0.1 L at tau = 1 s, CC 17 times); the others empty GC (< 0.1 times). [Chang08]
// Table 1 has void fractions CC < GC < whole domain in all three cases, so this field was picked.
// Its negative (-A) is the same flow mirrored and fits equally.
#include <array>
#include <cmath>
#include <numbers>

namespace fluidem {

enum class BodyForceType { SinusoidalCube };

struct BodyForceSpec {
  BodyForceType type = BodyForceType::SinusoidalCube;
  double amplitude = 0.0;                ///< A, m/s^2 (any sign)
  double wavelength = 0.0;               ///< m, > 0; on a periodic axis it divides the box length
  std::array<double, 3> origin{0, 0, 0}; ///< m, where every cosine is 1
};

inline const char* to_string(BodyForceType) {
  return "sinusoidal_cube";
}

/// The acceleration (m/s^2) of the body force at the point (x, y, z).
inline std::array<double, 3> body_acceleration(const BodyForceSpec& b, double x, double y,
                                               double z) {
  const double k = 2.0 * std::numbers::pi / b.wavelength;
  const double cx = std::cos(k * (x - b.origin[0]));
  const double cy = std::cos(k * (y - b.origin[1]));
  const double cz = std::cos(k * (z - b.origin[2]));
  return {b.amplitude * cy * cz, b.amplitude * cz * cx, b.amplitude * cx * cy};
}

} // namespace fluidem
