// The fluid torque on a sphere spinning relative to the fluid [Zhu07 §2.3 (the particle's
// rotation in Table 3's Magnus force); Crowe, Sommerfeld & Tsuji 1998 §4.7]:
//
//   Stokes (Re_r -> 0):  T = pi mu d^3 (Omega/2 - omega_p)  (= 8 pi mu a^3 Omega_rel, a = d/2)
//   Dennis, Singh & Ingham (1980, J. Fluid Mech. 101:257), finite Re_r:
//     T = rho_f/2 (d/2)^5 C_R |Omega_rel| Omega_rel,   Re_r = rho_f d^2 |Omega_rel|/mu
//     C_R = 64 pi/Re_r                          (Re_r <= 32)
//     C_R = 12.9/sqrt(Re_r) + 128.4/Re_r        (32 < Re_r < 1000)
// Stokes limit, exactly: rho_f/2 d^5/32 (64 pi mu/(rho_f d^2 |Omega_rel|)) |Omega_rel| Omega_rel
// = pi mu d^3 Omega_rel, so the first branch is the Stokes torque (and is computed as such: no
// 0/0 at Omega_rel = 0, where T = 0). C_R jumps by 0.15% at Re_r = 32 (6.2832 -> 6.2930), as
// published (the constants as quoted by Crowe, Sommerfeld & Tsuji; the original paper was not
// at hand to check them). Validity: Dennis et al.'s computations reach Re_r = 1000 (steady
// axisymmetric flow); a translating sphere's wake is not in it (Re_p << 1 assumed for the
// rotation). Spin-down of a sphere (I = m d^2/10) in a fluid at rest: I d(omega)/dt = -pi mu d^3
// omega, time constant I/(pi mu d^3) = rho_p d^2/(60 mu) (Stokes; tested).
#pragma once
#include <cmath>
#include <numbers>

#include "core/vec3.hpp"

namespace fluidem::coupling::forces {

/// Stokes: pi mu d^3 (Omega/2 - omega_p), N m.
inline Vec3 fluid_torque_stokes(const Vec3& vorticity, const Vec3& omega_p, double d, double mu) {
  return (std::numbers::pi * mu * d * d * d) * (0.5 * vorticity - omega_p);
}

/// C_R(Re_r) [Dennis, Singh & Ingham 1980], Re_r > 0.
inline double rotational_drag_coefficient(double re_r) {
  if (re_r <= 32.0) return 64.0 * std::numbers::pi / re_r;
  return 12.9 / std::sqrt(re_r) + 128.4 / re_r;
}

/// rho_f/2 (d/2)^5 C_R |Omega_rel| Omega_rel, N m.
inline Vec3 fluid_torque_dennis(const Vec3& vorticity, const Vec3& omega_p, double d, double rho_f,
                                double mu) {
  const Vec3 om = 0.5 * vorticity - omega_p;
  const double om_mag = norm(om);
  const double re_r = rho_f * d * d * om_mag / mu;
  if (re_r <= 32.0) return (std::numbers::pi * mu * d * d * d) * om;
  const double r = 0.5 * d;
  const double r5 = r * r * r * r * r;
  return (0.5 * rho_f * r5 * rotational_drag_coefficient(re_r) * om_mag) * om;
}

} // namespace fluidem::coupling::forces
