// core/nearest_integer.hpp against the C library: nearest_integer is std::nearbyint in the
// default rounding mode (to nearest, ties to even) and floor_integer is std::floor, bit for bit,
// on ties, near-ties, negative values, signed zeros and magnitudes up to 2^51 (the stated range).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/nearest_integer.hpp"

namespace fluidem {
namespace {

std::vector<double> samples() {
  std::vector<double> v = {0.0,
                           -0.0,
                           0.5,
                           -0.5,
                           1.5,
                           -1.5,
                           2.5,
                           -2.5,
                           0.49999999999999994,
                           -0.49999999999999994,
                           1.0,
                           -1.0,
                           3.0,
                           1e-300,
                           -1e-300,
                           std::ldexp(1.0, 51) - 0.5,
                           -(std::ldexp(1.0, 51) - 0.5),
                           std::ldexp(1.0, 50) + 0.5,
                           4503599627370495.5 / 2};
  for (double x = -3.0; x <= 3.0; x += 0.125) v.push_back(x); // ties and exact quarters
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  for (int k = 0; k < 100000; ++k) v.push_back(u(rng));
  for (int e = -20; e <= 50; ++e) {
    v.push_back(std::ldexp(1.0, e) + 0.5), v.push_back(-std::ldexp(1.0, e) - 0.5);
    v.push_back(std::nextafter(std::ldexp(1.0, e) + 0.5, 0.0));
  }
  return v;
}

// Compared as values (nearbyint(-0.3) is -0.0, the inline rounding gives +0.0: both are the
// integer 0, and the minimum image and the wrap only multiply and subtract it).
TEST(NearestInteger, IsNearbyintInTheDefaultRoundingMode) {
  for (const double q : samples()) ASSERT_EQ(nearest_integer(q), std::nearbyint(q)) << q;
}

TEST(NearestInteger, FloorIntegerIsFloor) {
  for (const double q : samples()) ASSERT_EQ(floor_integer(q), std::floor(q)) << q;
}

// wrapped() is the periodic wrap c - l floor((c - lo) / l) of the integrators, bit for bit.
TEST(NearestInteger, WrappedIsTheFloorWrap) {
  const double lo = -0.013, l = 0.15;
  for (const double q : samples()) {
    const double c = lo + q * l;
    ASSERT_EQ(wrapped(c, lo, l), c - l * std::floor((c - lo) / l)) << c;
  }
}

} // namespace
} // namespace fluidem
