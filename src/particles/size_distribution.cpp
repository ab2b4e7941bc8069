#include "particles/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace fluidem {

namespace {

using Kind = SizeDistributionSpec::Kind;
using Basis = SizeDistributionSpec::Basis;

/// The standard normal CDF, Phi(z) = erfc(-z / sqrt 2) / 2 [Abramowitz & Stegun 26.2.29].
double phi_cdf(double z) {
  return 0.5 * std::erfc(-z / std::numbers::sqrt2);
}

/// Running sums of `w`, the last one 1 (w >= 0, not all 0).
std::vector<double> normalised_cumulative(const std::vector<double>& w) {
  std::vector<double> c(w.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) c[i] = sum += w[i];
  for (double& v : c) v /= sum;
  c.back() = 1.0;
  return c;
}

/// The first index i with u < c[i] (c non-decreasing, c.back() = 1, u in [0, 1)).
std::size_t pick(const std::vector<double>& c, double u) {
  const auto it = std::upper_bound(c.begin(), c.end(), u);
  return std::min(static_cast<std::size_t>(it - c.begin()), c.size() - 1);
}

constexpr int kEnvelopePanels = 512;

} // namespace

SizeDistribution::SizeDistribution(const SizeDistributionSpec& spec) : spec_(spec) {
  switch (spec.kind) {
  case Kind::Normal:
    mu_ = spec.mean, sigma_ = spec.std, lo_ = spec.min, hi_ = spec.max;
    break;
  case Kind::LogNormal: {
    sigma_ = std::log(spec.geometric_std);
    // Hatch-Choate: count median = mass median exp(-3 ln^2 sigma_g) [Hinds 1999 eq. 4.48].
    mu_ = std::log(spec.median) - (spec.basis == Basis::Mass ? 3.0 * sigma_ * sigma_ : 0.0);
    lo_ = spec.min, hi_ = spec.max;
    break;
  }
  case Kind::Table:
  case Kind::Discrete:
    lo_ = spec.diameters.front(), hi_ = spec.diameters.back();
    break;
  }
  const bool in_log = spec.kind == Kind::LogNormal;
  if (spec.kind == Kind::Normal || in_log) {
    const double a = in_log ? std::log(lo_) : lo_, b = in_log ? std::log(hi_) : hi_;
    z_lo_ = (a - mu_) / sigma_, z_hi_ = (b - mu_) / sigma_;
    // An interval mostly above the mean is sampled mirrored (-z): Phi is resolved to the last
    // bit near 0, not near 1 (1 - Phi(8) = 6e-16 is below the spacing of doubles at 1).
    reflect_ = z_lo_ + z_hi_ > 0.0;
    if (reflect_) std::swap(z_lo_, z_hi_), z_lo_ = -z_lo_, z_hi_ = -z_hi_;
    p_lo_ = phi_cdf(z_lo_), p_hi_ = phi_cdf(z_hi_);
  }
  if (spec.kind == Kind::Normal && spec.basis == Basis::Mass) {
    // Envelope of q3(d) d^-3 (unnormalised: exp(-z^2/2) d^-3) on each panel [a, b].
    const double w = (hi_ - lo_) / kEnvelopePanels;
    std::vector<double> area(kEnvelopePanels);
    envelope_.resize(kEnvelopePanels);
    for (int k = 0; k < kEnvelopePanels; ++k) {
      const double a = lo_ + k * w, b = k + 1 == kEnvelopePanels ? hi_ : lo_ + (k + 1) * w;
      const double z = (std::clamp(mu_, a, b) - mu_) / sigma_;
      envelope_[k] = std::exp(-0.5 * z * z) / (a * a * a);
      area[k] = envelope_[k] * (b - a);
    }
    envelope_cumulative_ = normalised_cumulative(area);
  }
  if (spec.kind == Kind::Table) {
    const auto& d = spec.diameters;
    const auto& c = spec.cumulative;
    if (spec.basis == Basis::Number) {
      cumulative_ = c;
      for (double& v : cumulative_) v /= c.back();
    } else {
      // Number weight of each segment of uniform mass density (C_k+1 - C_k) / (d_k+1 - d_k).
      std::vector<double> w(d.size() - 1);
      for (std::size_t k = 0; k + 1 < d.size(); ++k)
        w[k] = (c[k + 1] - c[k]) / (d[k + 1] - d[k]) *
               (1.0 / (d[k] * d[k]) - 1.0 / (d[k + 1] * d[k + 1])) / 2.0;
      cumulative_ = normalised_cumulative(w);
    }
  }
  if (spec.kind == Kind::Discrete) {
    std::vector<double> w = spec.fractions;
    if (spec.basis == Basis::Mass)
      for (std::size_t i = 0; i < w.size(); ++i) w[i] /= std::pow(spec.diameters[i], 3);
    cumulative_ = normalised_cumulative(w);
  }
}

double SizeDistribution::truncated_normal(double u) const {
  // Bisection on Phi(z) = p in [z_lo, z_hi] until the interval stops shrinking (the last bit).
  const bool in_log = spec_.kind == Kind::LogNormal;
  const double p = p_lo_ + u * (p_hi_ - p_lo_);
  double a = z_lo_, b = z_hi_;
  for (int it = 0; it < 200; ++it) {
    const double m = 0.5 * (a + b);
    if (m <= a || m >= b) break;
    (phi_cdf(m) < p ? a : b) = m;
  }
  const double z = 0.5 * (a + b);
  const double x = mu_ + sigma_ * (reflect_ ? -z : z);
  return std::clamp(in_log ? std::exp(x) : x, lo_, hi_);
}

double SizeDistribution::sample(std::mt19937_64& rng) const {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto& d = spec_.diameters;
  switch (spec_.kind) {
  case Kind::LogNormal:
    return truncated_normal(unit(rng));
  case Kind::Normal: {
    if (spec_.basis == Basis::Number) return truncated_normal(unit(rng));
    const double w = (hi_ - lo_) / kEnvelopePanels;
    for (;;) { // rejection from the envelope [Devroye 1986 §II.3]
      const std::size_t k = pick(envelope_cumulative_, unit(rng));
      const double a = lo_ + static_cast<double>(k) * w;
      const double b = k + 1 == kEnvelopePanels ? hi_ : lo_ + static_cast<double>(k + 1) * w;
      const double x = a + (b - a) * unit(rng);
      const double z = (x - mu_) / sigma_;
      if (unit(rng) * envelope_[k] <= std::exp(-0.5 * z * z) / (x * x * x)) return x;
    }
  }
  case Kind::Table: {
    const double u = unit(rng);
    if (spec_.basis == Basis::Number) {
      // The segment k with C_k <= u < C_k+1 (flat segments hold no probability).
      const std::size_t j = std::max<std::size_t>(pick(cumulative_, u), 1);
      const double c0 = cumulative_[j - 1], c1 = cumulative_[j];
      const double f = c1 > c0 ? (u - c0) / (c1 - c0) : 0.0;
      return std::clamp(d[j - 1] + f * (d[j] - d[j - 1]), d[j - 1], d[j]);
    }
    const std::size_t k = pick(cumulative_, u);
    const double v = unit(rng);
    const double a2 = 1.0 / (d[k] * d[k]), b2 = 1.0 / (d[k + 1] * d[k + 1]);
    return std::clamp(1.0 / std::sqrt(a2 - v * (a2 - b2)), d[k], d[k + 1]);
  }
  case Kind::Discrete:
    return d[pick(cumulative_, unit(rng))];
  }
  return lo_; // (every kind returned above)
}

std::vector<double> SizeDistribution::sample(std::size_t n, std::mt19937_64& rng) const {
  std::vector<double> out(n);
  for (double& v : out) v = sample(rng);
  return out;
}

} // namespace fluidem
