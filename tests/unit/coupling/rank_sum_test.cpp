// Fixed-point sums (coupling/rank_sum.hpp), one process (the identities for the reductions):
//  - the sum does not depend on the order of the parts, bit for bit, where the double sum does;
//  - N parts of the largest allowed size in one entry do not overflow and sum to N max to the
//    resolution (N units at most);
//  - the resolution is the largest power of two below N max 2^-62 times 2 (the scale's rule);
//  - a NaN or infinite bound stops with InstabilityError.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.hpp"
#include "coupling/rank_sum.hpp"

namespace fluidem::coupling {
namespace {

RankSum alone() {
  return {[](double v) { return v; }, [](std::int64_t v) { return v; },
          [](std::span<std::int64_t>) {}};
}

std::vector<double> sum_of(const std::vector<double>& parts, double largest) {
  FixedPointSum s;
  const double bound[1] = {largest};
  s.start(1, bound, static_cast<std::int64_t>(parts.size()), alone());
  for (double v : parts) s.add(0, 0, v);
  s.reduce(alone());
  std::vector<double> out;
  s.result(0, out);
  return out;
}

TEST(FixedPointSum, OrderDoesNotChangeTheBits) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> parts;
  for (int k = 0; k < 1000; ++k) parts.push_back(u(rng) * std::pow(10.0, k % 7 - 3));
  const double largest = 1e3;
  const std::vector<double> a = sum_of(parts, largest);
  double plain_a = 0.0;
  for (double v : parts) plain_a += v;
  bool plain_differs = false;
  for (int shuffle = 0; shuffle < 20; ++shuffle) {
    std::shuffle(parts.begin(), parts.end(), rng);
    EXPECT_EQ(sum_of(parts, largest), a);
    double plain = 0.0;
    for (double v : parts) plain += v;
    plain_differs = plain_differs || plain != plain_a;
  }
  EXPECT_TRUE(plain_differs); // (the double sum does depend on the order here)
  EXPECT_NEAR(a[0], plain_a, 1e-9);
}

TEST(FixedPointSum, LargestPartsDoNotOverflow) {
  const double largest = 3.7e5;
  const std::int64_t n = 100000;
  FixedPointSum s;
  const double bound[2] = {largest, largest};
  s.start(2, bound, n, alone());
  for (std::int64_t k = 0; k < n; ++k) {
    s.add(0, 1, largest);
    s.add(1, 0, -largest);
  }
  s.reduce(alone());
  std::vector<double> pos, neg;
  s.result(0, pos);
  s.result(1, neg);
  const double exact = largest * static_cast<double>(n);
  EXPECT_NEAR(pos[1], exact, static_cast<double>(n) * s.resolution(0));
  EXPECT_EQ(neg[0], -pos[1]);
  EXPECT_EQ(pos[0], 0.0);
  // The scale's rule: 2^-s = 2^(e - 62) with N max < 2^e.
  int e = 0;
  std::frexp(exact, &e);
  EXPECT_EQ(s.resolution(0), std::ldexp(1.0, e - 62));
}

TEST(FixedPointSum, NonFiniteBoundStops) {
  FixedPointSum s;
  for (double bad : {std::nan(""), HUGE_VAL}) {
    const double bound[1] = {bad};
    EXPECT_THROW(s.start(4, bound, 10, alone()), InstabilityError);
  }
}

} // namespace
} // namespace fluidem::coupling
