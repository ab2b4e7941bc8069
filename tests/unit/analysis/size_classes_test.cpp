// Analyses per size class (analysis/size_classes.hpp, docs/analysis.md), on constructed beds
// whose values are known exactly:
//  - two species of distinct diameters: one class each; a continuous distribution (1000
//    distinct diameters): 4 classes of 250 particles, split at the order statistics;
//  - the volume-weighted median diameter by hand counts of d^3 (and d^2 for discs);
//  - the velocity distribution per class: small particles moving at +-a on every axis, large
//    ones at +-b, mean zero, one averaging cell: the classes' granular temperatures are a^2 and
//    b^2 (to 1e-12 relative: sums of squares of equal numbers) and their samples together are
//    the whole bed's;
//  - segregation of a continuous bed split at the volume-weighted median: smaller particles
//    higher gives s > 0, the same bed upside down s < 0, and the mean heights are the hand
//    averages over the two halves.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/segregation.hpp"
#include "analysis/size_classes.hpp"
#include "analysis/velocity_distribution.hpp"

namespace fluidem {
namespace {

TEST(SizeClasses, DistinctDiametersOneClassEach) {
  const SizeClasses c = size_classes({2e-3, 1e-3, 2e-3, 1e-3, 1e-3});
  ASSERT_EQ(c.size(), 2u);
  EXPECT_TRUE(c.distinct);
  EXPECT_EQ(c.count, (std::vector<long>{3, 2}));
  EXPECT_EQ(c.of(1e-3), 0u);
  EXPECT_EQ(c.of(2e-3), 1u);
  EXPECT_EQ(c.d_min[1], 2e-3);
}

TEST(SizeClasses, ContinuousEqualCountBins) {
  std::vector<double> d;
  for (int i = 999; i >= 0; --i) d.push_back(1e-3 + 1e-6 * i); // 1000 distinct, any order
  const SizeClasses c = size_classes(d);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_FALSE(c.distinct);
  EXPECT_EQ(c.count, (std::vector<long>{250, 250, 250, 250}));
  EXPECT_DOUBLE_EQ(c.d_min[1], 1e-3 + 250e-6);
  EXPECT_DOUBLE_EQ(c.d_max[3], 1e-3 + 999e-6);
  EXPECT_EQ(c.of(1e-3 + 249e-6), 0u);
  EXPECT_EQ(c.of(1e-3 + 250e-6), 1u);
}

TEST(SizeClasses, VolumeWeightedMedian) {
  // Seven of d = 1 (volume 7) and one of d = 2 (volume 8): half the volume (7.5) is reached at
  // d = 2; with nine of d = 1 (9 of 17) at d = 1.
  std::vector<double> d(7, 1.0);
  d.push_back(2.0);
  EXPECT_EQ(volume_weighted_median_diameter(d, false), 2.0);
  d.insert(d.begin(), 2, 1.0);
  EXPECT_EQ(volume_weighted_median_diameter(d, false), 1.0);
  // Discs: areas 1 and 4: three of d = 1 and one of d = 2 (3 of 7) -> 2; five of d = 1 -> 1.
  EXPECT_EQ(volume_weighted_median_diameter({1.0, 1.0, 1.0, 2.0}, true), 2.0);
  EXPECT_EQ(volume_weighted_median_diameter({1.0, 1.0, 1.0, 1.0, 1.0, 2.0}, true), 1.0);
}

TEST(SizeClasses, VelocityDistributionPerClass) {
  ParticleStore p;
  const double a = 0.3, b = 0.1;
  for (int i = 0; i < 400; ++i) {
    const double s = (i % 2 == 0) ? 1.0 : -1.0;
    const bool small = (i / 2) % 2 == 0; // pairs of opposite velocity in each class
    const double v = small ? a : b;
    // The masses differ, but each class's velocities cancel pair by pair: the bed's
    // mass-weighted mean is zero and C = v.
    p.add({1e-3 * i, 0.5, 0.5}, {s * v, -s * v, s * v}, small ? 1e-3 : 2e-3, 2500.0, small ? 0 : 1,
          i);
  }
  std::vector<std::array<double, 3>> C;
  std::vector<std::size_t> which;
  const VelocityDistributionOptions o;
  append_velocity_fluctuations(p, {0, 0, 0}, {1, 1, 1}, o, C, &which);
  ASSERT_EQ(C.size(), 400u);
  ASSERT_EQ(which.size(), 400u);
  std::vector<double> d;
  for (const double r : p.radius) d.push_back(2.0 * r);
  const SizeClasses c = size_classes(d);
  ASSERT_EQ(c.size(), 2u);
  std::vector<std::vector<std::array<double, 3>>> by(2);
  for (std::size_t j = 0; j < C.size(); ++j) by[c.of(2.0 * p.radius[which[j]])].push_back(C[j]);
  const VelocityDistribution small = fluctuation_distribution(by[0], o);
  const VelocityDistribution large = fluctuation_distribution(by[1], o);
  EXPECT_NEAR(small.granular_temperature, a * a, 1e-12 * a * a);
  EXPECT_NEAR(large.granular_temperature, b * b, 1e-12 * b * b);
  EXPECT_EQ(small.samples + large.samples, fluctuation_distribution(C, o).samples);
}

TEST(SizeClasses, SegregationOfAContinuousBed) {
  // 100 diameters 1.00 ... 1.99 mm; particle k at height z = (100 - k) mm (smaller higher).
  ParticleStore up, down;
  std::vector<double> d;
  for (int k = 0; k < 100; ++k) {
    const double dk = 1e-3 + 1e-5 * k;
    d.push_back(dk);
    up.add({0, 0, 1e-3 * (100 - k)}, {0, 0, 0}, 0.5 * dk, 2500.0, 0, k);
    down.add({0, 0, 1e-3 * (k + 1)}, {0, 0, 0}, 0.5 * dk, 2500.0, 0, k);
  }
  const double split = volume_weighted_median_diameter(d, false);
  // By hand: the first diameter whose cumulative d^3 reaches half the total.
  double total = 0.0, sum = 0.0, expect = 0.0;
  for (const double x : d) total += x * x * x;
  for (const double x : d)
    if ((sum += x * x * x) >= 0.5 * total) {
      expect = x;
      break;
    }
  EXPECT_EQ(split, expect);
  const Segregation s = segregation(up, split, 2, 0.0, true, false);
  const Segregation r = segregation(down, split, 2, 0.0, true, false);
  EXPECT_GT(s.s, 0.0);
  EXPECT_LT(r.s, 0.0);
  EXPECT_EQ(s.n_small + s.n_large, 100);
  double h_small = 0.0;
  for (long k = 0; k < s.n_small; ++k) h_small += 1e-3 * static_cast<double>(100 - k);
  EXPECT_NEAR(s.h_small, h_small / static_cast<double>(s.n_small), 1e-15);
}

} // namespace
} // namespace fluidem
