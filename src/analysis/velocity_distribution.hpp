// Particle velocity distributions and granular temperature [Deen07 §6.2; Goldschmidt et al.
// 2002]. The fluctuation velocity of particle i is C_i = v_i - <v>_cell(i), the particle velocity
// less the mean velocity of the particles in its averaging cell (so that the mean flow of the
// bed, e.g. bubble-driven circulation, is not counted as fluctuation); with one cell covering
// the domain it is v_i - <v>. Per component d: the variance s_d^2 = <C_d^2>, skewness
// <C_d^3>/s_d^3 and kurtosis <C_d^4>/s_d^4 (a Gaussian: 0 and 3), and the histogram of
// C_d / s_d as a probability density on [-range, range] to compare with the standard normal
// density; the speed |C| / sqrt(theta) against the Maxwell density (3-D) or the Rayleigh
// density (2-D discs). Granular temperature theta = <|C|^2> / D (D = 3, or 2 for discs in the
// x-z plane). Anisotropy: s_vertical^2 / s_horizontal^2 (1 for an isotropic distribution;
// Goldschmidt et al. found it above 1 for non-ideal particles).
//
// Locally normalised: C_d / s_d,cell, each fluctuation over the rms fluctuation of its own cell
// and frame. The pooled moments above mix cells of different granular temperature (a bubble's
// wake and a packed corner), and a mixture of Gaussians of different variances has a kurtosis
// above 3 (two halves of variances a and b: 6 (a^2 + b^2) / (a + b)^2); the normalised ones
// measure the shape of the local distribution. With n particles in a cell the scale is their own
// rms, which biases the kurtosis of Gaussian samples to 3 (n - 1) / (n + 1) (2.93 at n = 60):
// cells with fewer than `min_local` particles are left out.
#pragma once
#include <array>
#include <vector>

#include "particles/particle_store.hpp"

namespace fluidem {

struct VelocityDistribution {
  std::array<double, 3> variance{};           ///< s_d^2, m^2/s^2 (y unused in 2-D)
  std::array<double, 3> skewness{};           ///< <C^3>/s^3
  std::array<double, 3> kurtosis{};           ///< <C^4>/s^4 (Gaussian: 3)
  double granular_temperature = 0.0;          ///< theta, m^2/s^2
  double anisotropy = 0.0;                    ///< s_vertical^2 / mean horizontal s^2
  std::vector<double> bin_centres;            ///< of C_d / s_d, [-range, range]
  std::array<std::vector<double>, 3> density; ///< histogram of C_d / s_d as a pdf
  std::vector<double> speed_centres;          ///< of |C| / sqrt(theta), [0, range]
  std::vector<double> speed_density;          ///< histogram of |C| / sqrt(theta) as a pdf
  /// Fraction of the samples outside the histogram range (per component; speed): the densities
  /// integrate to 1 minus this.
  std::array<double, 3> outside{};
  double speed_outside = 0.0;
  long samples = 0;
};

struct VelocityDistributionOptions {
  std::array<int, 3> cells{1, 1, 1}; ///< averaging cells over [lo, hi] for the local mean
  int bins = 40;
  double range = 4.0; ///< histogram range in units of s (components) or sqrt(theta) (speed)
  int vertical_axis = 2;
  bool two_d = false; ///< discs in the x-z plane: components x and z only
  int min_local = 20; ///< fewest particles of a cell for the locally normalised moments
};

/// The distribution over the particles of `p` in the box [lo, hi] (particles outside are
/// clamped into the edge cells). Cells with a single particle contribute nothing (their
/// fluctuation is zero by construction): they are left out. std::invalid_argument when fewer
/// than 2 particles remain or a variance is zero.
VelocityDistribution velocity_distribution(const ParticleStore& p, const std::array<double, 3>& lo,
                                           const std::array<double, 3>& hi,
                                           const VelocityDistributionOptions& o = {});

/// The fluctuation velocities C_i (as velocity_distribution defines them, cells with a single
/// particle left out) of the particles of `p`, appended to `out`: to pool several frames (each
/// frame with its own local means) into one distribution. Throws for bad options as
/// velocity_distribution does. `which` (when given) gets the index in `p` of each appended
/// sample (to split the samples by particle, e.g. by size class); `local_scale` (when given)
/// the rms fluctuation per component of the sample's cell in this frame, NaN for cells of fewer
/// than `min_local` particles (for local_moments).
void append_velocity_fluctuations(const ParticleStore& p, const std::array<double, 3>& lo,
                                  const std::array<double, 3>& hi,
                                  const VelocityDistributionOptions& o,
                                  std::vector<std::array<double, 3>>& out,
                                  std::vector<std::size_t>* which = nullptr,
                                  std::vector<std::array<double, 3>>* local_scale = nullptr);

/// The distribution of the fluctuation velocities `C` (from append_velocity_fluctuations, one
/// or many frames): moments, granular temperature, anisotropy and histograms as above.
/// std::invalid_argument when `C` has fewer than 2 samples or a variance is zero.
VelocityDistribution fluctuation_distribution(const std::vector<std::array<double, 3>>& C,
                                              const VelocityDistributionOptions& o = {});

struct LocalMoments {
  std::array<double, 3> skewness{}, kurtosis{}; ///< of C_d / s_d,cell (Gaussian: 0, 3)
  long samples = 0;                             ///< those with a finite scale
};
/// The moments of C_d / scale_d over the samples whose scale is finite (C and scale from
/// append_velocity_fluctuations). std::invalid_argument when fewer than 2 samples are left.
LocalMoments local_moments(const std::vector<std::array<double, 3>>& C,
                           const std::vector<std::array<double, 3>>& scale,
                           const VelocityDistributionOptions& o = {});

/// Reference densities for unit variance per component: the standard normal
/// exp(-x^2/2)/sqrt(2 pi); the Maxwell speed density sqrt(2/pi) c^2 exp(-c^2/2) (3-D, <c^2> = 3);
/// the Rayleigh speed density c exp(-c^2/2) (2-D, <c^2> = 2).
double normal_density(double x);
double maxwell_speed_density(double c);
double rayleigh_speed_density(double c);

} // namespace fluidem
