// The [body_force] field "sinusoidal_cube" (core/body_force.hpp): values at chosen points against
// hand-evaluated cosines of the formula a = A (cos ky cos kz, cos kz cos kx, cos kx cos ky),
// k = 2 pi / wavelength (our reconstruction of [Chang08] eq. 1), and the properties the
// reconstruction was chosen for: zero at both collision centres (L/4, L/4, L/4) and
// (3L/4, 3L/4, 3L/4), (A, A, A) at the geometric centre, zero divergence, period L. Tolerance
// 1e-15 m/s2 (round-off of cos; exact values from cos(pi/4) = sqrt(2)/2, cos(2 pi/3) = -1/2).
#include <gtest/gtest.h>

#include <cmath>

#include "core/body_force.hpp"

namespace fluidem {
namespace {

constexpr double L = 0.1, A = 0.1, tol = 1e-15;

BodyForceSpec field() {
  BodyForceSpec b;
  b.amplitude = A;
  b.wavelength = L;
  return b;
}

TEST(BodyForce, ValuesAtChosenPoints) {
  const BodyForceSpec b = field();
  // (0, L/8, L/3): cos kx = 1, cos ky = sqrt(2)/2, cos kz = -1/2.
  const auto a = body_acceleration(b, 0.0, L / 8, L / 3);
  const double h = std::sqrt(2.0) / 2.0;
  EXPECT_NEAR(a[0], A * h * -0.5, tol);
  EXPECT_NEAR(a[1], A * -0.5 * 1.0, tol);
  EXPECT_NEAR(a[2], A * 1.0 * h, tol);
  // Geometric centre: all cosines -1: (A, A, A); corner: all +1.
  for (const auto& q : {body_acceleration(b, L / 2, L / 2, L / 2), body_acceleration(b, 0, 0, 0)})
    for (double c : q) EXPECT_NEAR(c, A, tol);
  // Collision centres: every cosine 0.
  for (double s : {L / 4, 3 * L / 4})
    for (double c : body_acceleration(b, s, s, s)) EXPECT_NEAR(c, 0.0, tol);
  // The origin shifts the field: origin (L/4, 0, 0) puts cos kx = 0 at x = L/2.
  BodyForceSpec o = b;
  o.origin = {L / 4, 0.0, 0.0};
  const auto s =
      body_acceleration(o, L / 2, 0.0, 0.0); // cos kx = cos(pi/2) = 0, cos ky = cos kz = 1
  EXPECT_NEAR(s[0], A, tol);
  EXPECT_NEAR(s[1], 0.0, tol);
  EXPECT_NEAR(s[2], 0.0, tol);
}

TEST(BodyForce, PeriodicAndDivergenceFree) {
  const BodyForceSpec b = field();
  const double pts[][3] = {{0.013, 0.031, 0.047}, {0.071, 0.002, 0.099}, {0.05, 0.025, 0.0833}};
  for (const auto& p : pts) {
    const auto a = body_acceleration(b, p[0], p[1], p[2]);
    const auto w = body_acceleration(b, p[0] + L, p[1] - L, p[2] + 2 * L);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(a[d], w[d], 1e-14);
    // Central differences, step 1e-6 m: error (k h)^2 / 6 |a| ~ 1e-10 relative.
    const double h = 1e-6;
    double div = 0.0;
    for (int d = 0; d < 3; ++d) {
      double q[3] = {p[0], p[1], p[2]}, r[3] = {p[0], p[1], p[2]};
      q[d] += h, r[d] -= h;
      div +=
          (body_acceleration(b, q[0], q[1], q[2])[d] - body_acceleration(b, r[0], r[1], r[2])[d]) /
          (2 * h);
    }
    EXPECT_NEAR(div, 0.0, 1e-9); // |grad a| ~ A k = 6.3 s^-2
  }
}

} // namespace
} // namespace fluidem
