// LoadShares (core/load_shares.hpp): the threads' shares of the particles move toward equal busy
// times. Reference: with thread t taking s_t of the particles at r_t seconds per particle, the
// busy times are equal when s_t is proportional to 1/r_t (s = (1/r_t) / sum(1/r)). The first
// measured step sets each thread's rate; later steps move it by 5% of their difference, a step's
// rate clamped to half to twice the estimate.
#include "core/load_shares.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace fluidem {
namespace {

/// Run `steps` steps of a loop whose thread t works `rate[t]` seconds per particle on its share
/// of `n` particles; returns the boundaries after the last update.
std::vector<double> settle(LoadShares& shares, const std::vector<double>& rate, int steps,
                           double n = 10000.0) {
  const int nt = static_cast<int>(rate.size());
  const double* bounds = nullptr;
  for (int s = 0; s < steps; ++s) {
    bounds = shares.prepare(nt);
    std::vector<double> share(static_cast<std::size_t>(nt));
    for (int t = 0; t < nt; ++t) share[t] = (bounds[t + 1] - bounds[t]) * n;
    for (int t = 0; t < nt; ++t) shares.record(t, share[t], share[t] * rate[t]);
    shares.update();
  }
  bounds = shares.prepare(nt);
  return {bounds, bounds + nt + 1};
}

TEST(LoadShares, EvenSharesToStartWith) {
  LoadShares shares;
  const double* b = shares.prepare(4);
  EXPECT_EQ(shares.threads(), 4);
  for (int t = 0; t <= 4; ++t) EXPECT_DOUBLE_EQ(b[t], t / 4.0);
}

TEST(LoadShares, EqualRatesKeepEvenShares) {
  LoadShares shares;
  const std::vector<double> b = settle(shares, {2e-8, 2e-8}, 50);
  EXPECT_NEAR(b[1], 0.5, 1e-12);
}

TEST(LoadShares, SharesBecomeProportionalToSpeed) {
  // Thread 0 twice as slow per particle as thread 1: shares 1/3 and 2/3.
  LoadShares shares;
  const std::vector<double> b = settle(shares, {4e-8, 2e-8}, 300);
  EXPECT_NEAR(b[1], 1.0 / 3.0, 1e-4);
  EXPECT_DOUBLE_EQ(b[0], 0.0);
  EXPECT_DOUBLE_EQ(b[2], 1.0);
  // Three threads at rates 1, 2, 4: shares 4/7, 2/7, 1/7.
  LoadShares three;
  const std::vector<double> c = settle(three, {1e-8, 2e-8, 4e-8}, 300);
  EXPECT_NEAR(c[1], 4.0 / 7.0, 1e-4);
  EXPECT_NEAR(c[2], 6.0 / 7.0, 1e-4);
}

TEST(LoadShares, NoThreadIsStarved) {
  // Thread 1 a hundred times slower: its share stops at a quarter of an even one (1/8 of two),
  // so that it keeps being measured.
  LoadShares shares;
  const std::vector<double> b = settle(shares, {1e-8, 1e-6}, 400);
  // Normalised speeds 0.990 and 0.0099 -> 0.125: thread 1's share 0.125 / (0.990 + 0.125).
  EXPECT_NEAR(1.0 - b[1], 0.125 / (0.990 + 0.125), 1e-3);
}

TEST(LoadShares, OneOutlierStepMovesTheSharesLittle) {
  LoadShares shares;
  settle(shares, {2e-8, 2e-8}, 50);
  // One step in which thread 1 took 50 times as long (its core taken away for a moment): the
  // step's rate is clamped to twice the estimate, which moves by 5% of the difference.
  const double* bounds = shares.prepare(2);
  shares.record(0, 5000.0, 5000.0 * 2e-8);
  shares.record(1, 5000.0, 50 * 5000.0 * 2e-8);
  shares.update();
  bounds = shares.prepare(2);
  // Rates 2e-8 and 2.1e-8: share of thread 0 = (1/2) / (1/2 + 1/2.1) = 0.5122.
  EXPECT_NEAR(bounds[1], 0.5122, 1e-3);
}

TEST(LoadShares, AThreadWithoutWorkGetsItsShareBack) {
  // Thread 1 measured four times slower, then given no particles for 100 steps (as when its
  // share falls between two group boundaries): its estimate moves 5% a step toward thread 0's,
  // so the shares return to within 0.95^100 ~ 0.6% of even.
  LoadShares shares;
  settle(shares, {1e-8, 4e-8}, 20);
  for (int s = 0; s < 100; ++s) {
    shares.prepare(2);
    shares.record(0, 10000.0, 10000.0 * 1e-8);
    shares.record(1, 0.0, 0.0);
    shares.update();
  }
  const double* b = shares.prepare(2);
  EXPECT_NEAR(b[1], 0.5, 0.01);
  EXPECT_GT(b[1], 0.5); // approached from thread 0's larger share
}

TEST(LoadShares, ANewTeamSizeStartsFromEvenShares) {
  LoadShares shares;
  settle(shares, {4e-8, 2e-8}, 100);
  const double* b = shares.prepare(3);
  EXPECT_EQ(shares.threads(), 3);
  EXPECT_DOUBLE_EQ(b[1], 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(b[2], 2.0 / 3.0);
}

} // namespace
} // namespace fluidem
