// The particle-size distribution of an [[insert]] block (`size_distribution`, docs/case-file.md):
// diameters drawn one by one from a uniform generator, exactly (no tabulated approximation):
//  - normal, truncated to [min, max]: the inverse of the truncated normal CDF
//    F(d) = (Phi(z) - Phi(z_min)) / (Phi(z_max) - Phi(z_min)), z = (d - mean) / std
//    [Johnson, Kotz & Balakrishnan, Continuous Univariate Distributions 1, 2nd ed. 1994, §10.1],
//    solved by bisection on Phi(z) = erfc(-z / sqrt 2) / 2 to the last bit;
//  - log_normal: ln d normal with mean ln d_g and standard deviation ln sigma_g, truncated to
//    [min, max], sampled as above in ln d;
//  - table: the inverse of the piecewise-linear CDF (uniform density between two points);
//  - discrete: the diameter whose cumulative fraction first exceeds u.
// basis = "mass": the parameters give the mass (volume) distribution q3(d); the number
// distribution is q0(d) = q3(d) d^-3 / integral(q3 d^-3) [Allen, Particle Size Measurement,
// 5th ed. 1997, §4.7]. Exactly, per kind:
//  - log_normal: again log-normal with the same sigma_g and the count median
//    d_g,number = d_g,mass exp(-3 ln^2 sigma_g) (Hatch-Choate [Hinds, Aerosol Technology, 2nd ed.
//    1999, eq. 4.48]); the truncation bounds are the same diameters;
//  - normal: rejection from a piecewise-constant envelope of q3(d) d^-3 over 512 equal panels of
//    [min, max] (the envelope on a panel [a, b] is the normal density at the point of [a, b]
//    nearest the mean times a^-3) [Devroye, Non-Uniform Random Variate Generation, 1986,
//    §II.3 and §VIII.2]: exact whatever the number of panels, which only sets the acceptance;
//  - table: within a segment [d_k, d_k+1] of uniform mass density the number density is
//    proportional to d^-3, with CDF proportional to d_k^-2 - d^-2, inverted in closed form; the
//    segment is chosen with its number weight (C_k+1 - C_k) (d_k^-2 - d_k+1^-2) / (2 (d_k+1 -
//    d_k));
//  - discrete: number fractions proportional to f_i / d_i^3.
// Fractions and the table's last cumulative value are divided by their sum (last value): the
// reader accepts them within 1e-6 of 1.
#pragma once
#include <cstddef>
#include <random>
#include <vector>

#include "core/case_spec.hpp"

namespace fluidem {

class SizeDistribution {
public:
  /// From a spec the case reader checked (positive, increasing diameters; min < max).
  explicit SizeDistribution(const SizeDistributionSpec& spec);

  /// One diameter, m; draws from `rng` (a variable number of draws for mass-basis normal).
  double sample(std::mt19937_64& rng) const;
  /// n diameters in the order drawn.
  std::vector<double> sample(std::size_t n, std::mt19937_64& rng) const;

  double smallest() const { return lo_; } ///< m: no sample is below
  double largest() const { return hi_; }  ///< m: no sample is above

private:
  SizeDistributionSpec spec_;
  double lo_ = 0.0, hi_ = 0.0;
  double mu_ = 0.0, sigma_ = 0.0;  ///< normal (in d) or log-normal (in ln d) parameters
  double z_lo_ = 0.0, z_hi_ = 0.0; ///< the standardised truncation bounds (mirrored)
  bool reflect_ = false;           ///< sampled as -z (an interval mostly above the mean)
  double p_lo_ = 0.0, p_hi_ = 0.0; ///< Phi at z_lo_ and z_hi_
  std::vector<double> cumulative_; ///< table: the CDF; discrete and mass table: choice
  std::vector<double> envelope_;   ///< mass normal: panel bounds of q3 d^-3
  std::vector<double> envelope_cumulative_;

  double truncated_normal(double u) const; ///< mu_ + sigma_ z, z the truncated quantile
};

} // namespace fluidem
