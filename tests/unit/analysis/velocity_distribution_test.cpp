// Velocity distributions (analysis/velocity_distribution.hpp) on sampled velocities whose
// distribution is known:
//  - 200,000 particles with Gaussian velocities, s = (0.1, 0.1, 0.2) m/s: variances within 1%
//    (statistical error sqrt(2/N) = 0.3%), skewness within 0.03 of 0 and kurtosis within 0.05
//    of 3 (errors sqrt(6/N) = 0.005, sqrt(24/N) = 0.011), anisotropy s_z^2 / s_x^2 = 4 within
//    2%, granular temperature (0.01 + 0.01 + 0.04)/3 within 1%; the component histograms match
//    the standard normal density and the speed histogram the Maxwell density (with the
//    isotropic s) within 0.02 in every bin;
//  - the same fluctuations on top of a mean flow that differs from cell to cell (a circulation
//    of 1 m/s): with the cells as averaging cells the variances are recovered within 1%; with
//    one cell the mean flow inflates them (the reason for local averaging);
//  - 2-D discs (x-z): temperature over two components, Rayleigh speed density;
//  - locally normalised moments: Gaussian velocities whose variance differs between two halves
//    of the box (s = 0.1 and 0.3 m/s): the pooled kurtosis is the mixture's
//    6 (a^2 + b^2) / (a + b)^2 = 4.92 (a = 0.01, b = 0.09) within 0.15, the locally normalised
//    one 3 (n - 1)/(n + 1) (n = 5,000 per cell: 2.999) within 0.05, as for one Gaussian.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "analysis/velocity_distribution.hpp"

namespace fluidem {
namespace {

ParticleStore gaussian(long n, std::array<double, 3> s, bool circulation, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  ParticleStore p;
  for (long i = 0; i < n; ++i) {
    const Vec3 x{pos(rng), pos(rng), pos(rng)};
    Vec3 v{s[0] * g(rng), s[1] * g(rng), s[2] * g(rng)};
    if (circulation) { // mean flow constant within each of 4 x 1 x 4 cells
      const int cx = static_cast<int>(x[0] * 4.0), cz = static_cast<int>(x[2] * 4.0);
      v[2] += (cx % 2 == 0 ? 1.0 : -1.0);
      v[0] += (cz % 2 == 0 ? 0.5 : -0.5);
    }
    p.add(x, v, 0.001, 2500.0, 0, i);
  }
  return p;
}

TEST(VelocityDistribution, GaussianMomentsAndDensities) {
  const ParticleStore p = gaussian(200000, {0.1, 0.1, 0.2}, false, 1);
  const VelocityDistribution r = velocity_distribution(p, {0, 0, 0}, {1, 1, 1});
  EXPECT_NEAR(r.variance[0] / 0.01, 1.0, 0.01);
  EXPECT_NEAR(r.variance[1] / 0.01, 1.0, 0.01);
  EXPECT_NEAR(r.variance[2] / 0.04, 1.0, 0.01);
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(r.skewness[d], 0.0, 0.03);
    EXPECT_NEAR(r.kurtosis[d], 3.0, 0.05);
    for (std::size_t b = 0; b < r.bin_centres.size(); ++b)
      EXPECT_NEAR(r.density[d][b], normal_density(r.bin_centres[b]), 0.02) << d << " " << b;
  }
  EXPECT_NEAR(r.anisotropy / 4.0, 1.0, 0.02);
  EXPECT_NEAR(r.granular_temperature / 0.02, 1.0, 0.01);
  const ParticleStore iso = gaussian(200000, {0.1, 0.1, 0.1}, false, 2);
  const VelocityDistribution s = velocity_distribution(iso, {0, 0, 0}, {1, 1, 1});
  EXPECT_NEAR(s.anisotropy, 1.0, 0.02);
  for (std::size_t b = 0; b < s.speed_centres.size(); ++b)
    EXPECT_NEAR(s.speed_density[b], maxwell_speed_density(s.speed_centres[b]), 0.02) << b;
}

TEST(VelocityDistribution, LocalMeansRemoveTheMeanFlow) {
  const ParticleStore p = gaussian(100000, {0.1, 0.1, 0.1}, true, 3);
  VelocityDistributionOptions o;
  o.cells = {4, 1, 4};
  const VelocityDistribution local = velocity_distribution(p, {0, 0, 0}, {1, 1, 1}, o);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(local.variance[d] / 0.01, 1.0, 0.01) << d;
  const VelocityDistribution global = velocity_distribution(p, {0, 0, 0}, {1, 1, 1});
  EXPECT_GT(global.variance[2], 50.0 * 0.01); // the +-1 m/s circulation counted as fluctuation
}

TEST(VelocityDistribution, DiscsUseTwoComponentsAndRayleigh) {
  ParticleStore p = gaussian(200000, {0.1, 0.0, 0.1}, false, 4);
  for (std::size_t i = 0; i < p.size(); ++i) p.vy[i] = 0.0;
  VelocityDistributionOptions o;
  o.two_d = true;
  const VelocityDistribution r = velocity_distribution(p, {0, 0, 0}, {1, 1, 1}, o);
  EXPECT_NEAR(r.granular_temperature / 0.01, 1.0, 0.01);
  EXPECT_NEAR(r.anisotropy, 1.0, 0.02);
  for (std::size_t b = 0; b < r.speed_centres.size(); ++b)
    EXPECT_NEAR(r.speed_density[b], rayleigh_speed_density(r.speed_centres[b]), 0.02) << b;
}

TEST(VelocityDistribution, LocalNormalisationRemovesTheMixtureOfTemperatures) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  ParticleStore p;
  for (long i = 0; i < 100000; ++i) { // 4 x 1 x 5 cells of 5,000 particles on average
    const Vec3 x{pos(rng), pos(rng), pos(rng)};
    const double s = x[0] < 0.5 ? 0.1 : 0.3;
    p.add(x, {s * g(rng), s * g(rng), s * g(rng)}, 0.001, 2500.0, 0, i);
  }
  VelocityDistributionOptions o;
  o.cells = {4, 1, 5};
  std::vector<std::array<double, 3>> C, scale;
  append_velocity_fluctuations(p, {0, 0, 0}, {1, 1, 1}, o, C, nullptr, &scale);
  ASSERT_EQ(C.size(), scale.size());
  const VelocityDistribution pooled = fluctuation_distribution(C, o);
  const LocalMoments local = local_moments(C, scale, o);
  EXPECT_EQ(local.samples, static_cast<long>(C.size()));
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(pooled.kurtosis[d], 6.0 * (1e-4 + 81e-4) / (0.1 * 0.1), 0.15) << d;
    EXPECT_NEAR(local.kurtosis[d], 3.0, 0.05) << d;
    EXPECT_NEAR(local.skewness[d], 0.0, 0.03) << d;
  }
  // Cells below min_local particles are left out; none left is an error.
  o.min_local = 1000000;
  C.clear(), scale.clear();
  append_velocity_fluctuations(p, {0, 0, 0}, {1, 1, 1}, o, C, nullptr, &scale);
  EXPECT_THROW(local_moments(C, scale, o), std::invalid_argument);
}

TEST(VelocityDistribution, NoFluctuationIsAnError) {
  ParticleStore p;
  p.add({0.5, 0.5, 0.5}, {1, 1, 1}, 0.001, 2500.0, 0, 0);
  p.add({0.6, 0.5, 0.5}, {1, 1, 1}, 0.001, 2500.0, 0, 1);
  EXPECT_THROW(velocity_distribution(p, {0, 0, 0}, {1, 1, 1}), std::invalid_argument);
}

} // namespace
} // namespace fluidem
