// The time at which a sphere in free flight under gravity meets a fixed sphere
// (hardsphere/fixed_partner_time.hpp: the first root of the quartic |r + v t + g t^2/2|^2 =
// sigma^2, docs/fixed_particles.md), against independent references:
//  - a head-on fall from rest through a height h: t = sqrt(2 h / g) (free fall);
//  - a throw straight up from a height h above contact: t = (u + sqrt(u^2 + 2 g h)) / g;
//  - without gravity: the straight-line root of [Deen07 eq. 45],
//    t = (-b - sqrt(b^2 - |v|^2 c)) / |v|^2 with b = r.v, c = |r|^2 - sigma^2;
//  - a sphere resting on top (touching, at rest, pushed in by g): the minimal flight, as at a
//    wall; touching and approaching: 0; touching and moving off upwards at u, pulled back: the
//    flight time 2 u / g of the vertical throw;
//  - 6000 random flights (positions within 2 diameters, speeds up to 1 m/s, gravity none, down,
//    or in a random direction): a brute-force scan of the distance |r(t)| at 10^4 points of [0, T],
//    its first crossing of sigma refined by bisection on the distance itself. The two must
//    agree to 1e-9 T wherever the scan finds a crossing; where the search finds a contact the
//    scan missed (a graze shorter than the scan's spacing) the distance there must be sigma to
//    1e-9 of it; where the search finds none the scan must find none.
// Tolerances: the search bisects to adjacent doubles; the references are closed forms evaluated
// in double (1e-12 relative) or the scan's own bisection (1e-12 T).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "hardsphere/fixed_partner_time.hpp"

namespace fluidem {
namespace {

using hardsphere::time_to_fixed_contact;
constexpr double kNever = std::numeric_limits<double>::infinity();
constexpr double kG = 9.81;
constexpr double kSigma = 0.004; // two spheres of 4 mm diameter: R_a + R_b
constexpr double kMinFlight = 1e-9;

TEST(FixedPartnerTime, HeadOnFallFromRest) {
  for (const double h : {1e-6, 1e-3, 0.01, 0.2}) {
    const double t =
        time_to_fixed_contact({0, 0, kSigma + h}, {0, 0, 0}, {0, 0, -kG}, kSigma, 1.0, kMinFlight);
    EXPECT_NEAR(t / std::sqrt(2.0 * h / kG), 1.0, 1e-12) << "h = " << h;
  }
  // Beyond the horizon: none.
  EXPECT_EQ(
      time_to_fixed_contact({0, 0, kSigma + 0.2}, {0, 0, 0}, {0, 0, -kG}, kSigma, 0.1, kMinFlight),
      kNever);
}

TEST(FixedPartnerTime, ThrownUpThenFallingBack) {
  const double h = 0.01, u = 0.7;
  const double t =
      time_to_fixed_contact({0, 0, kSigma + h}, {0, 0, u}, {0, 0, -kG}, kSigma, 1.0, kMinFlight);
  EXPECT_NEAR(t / ((u + std::sqrt(u * u + 2.0 * kG * h)) / kG), 1.0, 1e-12);
}

TEST(FixedPartnerTime, StraightLineWithoutGravity) {
  const Vec3 r{0.003, 0.001, -0.0042}, v{-0.4, -0.1, 0.5};
  const double b = dot(r, v), c = norm2(r) - kSigma * kSigma, vv = norm2(v);
  const double ref = (-b - std::sqrt(b * b - vv * c)) / vv;
  const double t = time_to_fixed_contact(r, v, {0, 0, 0}, kSigma, 1.0, kMinFlight);
  EXPECT_NEAR(t / ref, 1.0, 1e-12);
  // Moving apart: never.
  EXPECT_EQ(time_to_fixed_contact(r, v * -1.0, {0, 0, 0}, kSigma, 1.0, kMinFlight), kNever);
}

TEST(FixedPartnerTime, TouchingStates) {
  const Vec3 top{0, 0, kSigma}, g{0, 0, -kG};
  // At rest on top, pushed in by gravity: the minimal flight.
  EXPECT_EQ(time_to_fixed_contact(top, {0, 0, 0}, g, kSigma, 1.0, kMinFlight), kMinFlight);
  // Touching and approaching: now.
  EXPECT_EQ(time_to_fixed_contact(top, {0.1, 0, -0.2}, g, kSigma, 1.0, kMinFlight), 0.0);
  // Touching, moving off upwards at u: back after the vertical throw's flight 2 u / g.
  const double u = 0.3;
  const double t = time_to_fixed_contact(top, {0, 0, u}, g, kSigma, 1.0, kMinFlight);
  EXPECT_NEAR(t / (2.0 * u / kG), 1.0, 1e-9);
  // Touching below the fixed sphere, gravity pulling it away: never.
  EXPECT_EQ(time_to_fixed_contact({0, 0, -kSigma}, {0, 0, 0}, g, kSigma, 1.0, kMinFlight), kNever);
}

/// |r + v t + g t^2/2|
double distance(const Vec3& r, const Vec3& v, const Vec3& g, double t) {
  return std::sqrt(norm2(r + v * t + g * (0.5 * t * t)));
}

/// The first time the distance falls to sigma, by a scan of m points and bisection; infinity if
/// the scan sees none.
double scanned(const Vec3& r, const Vec3& v, const Vec3& g, double horizon, int m) {
  double prev = 0.0;
  for (int k = 1; k <= m; ++k) {
    const double t = horizon * k / m;
    if (distance(r, v, g, t) <= kSigma) {
      double lo = prev, hi = t;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (distance(r, v, g, mid) > kSigma ? lo : hi) = mid;
      }
      return lo;
    }
    prev = t;
  }
  return kNever;
}

TEST(FixedPartnerTime, RandomFlightsAgainstAScan) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int found = 0, agreed = 0, grazes = 0;
  for (int c = 0; c < 6000; ++c) {
    Vec3 dir{u(rng), u(rng), u(rng)};
    if (norm2(dir) < 1e-6) continue;
    dir = dir / std::sqrt(norm2(dir));
    const Vec3 r = dir * (kSigma * (1.0 + 1e-6 + std::abs(u(rng))));
    const Vec3 v{u(rng), u(rng), u(rng)};
    Vec3 g{0, 0, 0}; // none, downwards, or in a random direction
    if (c % 3 == 1) g = Vec3{0, 0, -kG};
    if (c % 3 == 2) g = Vec3{u(rng), u(rng), u(rng)} * kG;
    const double horizon = 0.01 * (1.0 + std::abs(u(rng)));
    const double t = time_to_fixed_contact(r, v, g, kSigma, horizon, kMinFlight);
    const double s = scanned(r, v, g, horizon, 10000);
    if (s < kNever) {
      ASSERT_LT(t, kNever) << "case " << c << ": the scan found a contact at " << s;
      if (std::abs(t - s) <= 1e-9 * horizon) {
        ++agreed;
      } else {
        // Only an earlier graze the scan stepped over may differ.
        ASSERT_LT(t, s) << "case " << c;
        EXPECT_NEAR(distance(r, v, g, t) / kSigma, 1.0, 1e-9) << "case " << c;
        ++grazes;
      }
      ++found;
    } else if (t < kNever) {
      EXPECT_NEAR(distance(r, v, g, t) / kSigma, 1.0, 1e-9) << "case " << c;
      ++grazes;
    }
  }
  std::printf("random flights: %d contacts found by the scan, %d agreeing to 1e-9 T, %d grazes "
              "between the scan's points\n",
              found, agreed, grazes);
  EXPECT_GT(found, 600);
}

} // namespace
} // namespace fluidem
