#include "analysis/velocity_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fluidem {

namespace {
constexpr double pi = 3.14159265358979323846;
}

double normal_density(double x) {
  return std::exp(-0.5 * x * x) / std::sqrt(2.0 * pi);
}
double maxwell_speed_density(double c) {
  return c < 0.0 ? 0.0 : std::sqrt(2.0 / pi) * c * c * std::exp(-0.5 * c * c);
}
double rayleigh_speed_density(double c) {
  return c < 0.0 ? 0.0 : c * std::exp(-0.5 * c * c);
}

namespace {
void check_options(const VelocityDistributionOptions& o) {
  if (o.bins < 1 || !(o.range > 0.0))
    throw std::invalid_argument("velocity_distribution: need bins >= 1 and range > 0");
}
} // namespace

void append_velocity_fluctuations(const ParticleStore& p, const std::array<double, 3>& lo,
                                  const std::array<double, 3>& hi,
                                  const VelocityDistributionOptions& o,
                                  std::vector<std::array<double, 3>>& C,
                                  std::vector<std::size_t>* which) {
  check_options(o);
  std::array<int, 3> nc = o.cells;
  for (int d = 0; d < 3; ++d)
    if (nc[d] < 1 || !(hi[d] > lo[d]))
      throw std::invalid_argument("velocity_distribution: bad cells or box along axis " +
                                  std::to_string(d));
  const std::size_t ncell = static_cast<std::size_t>(nc[0]) * nc[1] * nc[2];
  const std::size_t n = p.size();
  std::vector<std::size_t> cell(n);
  std::vector<double> mass(ncell, 0.0), mv[3];
  for (auto& v : mv) v.assign(ncell, 0.0);
  std::vector<long> count(ncell, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double x[3] = {p.x[i], p.y[i], p.z[i]};
    std::size_t q = 0, stride = 1;
    for (int d = 0; d < 3; ++d) {
      const int c = std::clamp(
          static_cast<int>(std::floor((x[d] - lo[d]) / (hi[d] - lo[d]) * nc[d])), 0, nc[d] - 1);
      q += static_cast<std::size_t>(c) * stride;
      stride *= static_cast<std::size_t>(nc[d]);
    }
    cell[i] = q;
    mass[q] += p.mass[i];
    mv[0][q] += p.mass[i] * p.vx[i];
    mv[1][q] += p.mass[i] * p.vy[i];
    mv[2][q] += p.mass[i] * p.vz[i];
    ++count[q];
  }
  // Fluctuations about the mass-weighted local mean.
  C.reserve(C.size() + n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t q = cell[i];
    if (count[q] < 2) continue;
    const double v[3] = {p.vx[i], p.vy[i], p.vz[i]};
    std::array<double, 3> c{};
    for (int d = 0; d < 3; ++d) c[d] = v[d] - mv[d][q] / mass[q];
    C.push_back(c);
    if (which) which->push_back(i);
  }
}

VelocityDistribution fluctuation_distribution(const std::vector<std::array<double, 3>>& C,
                                              const VelocityDistributionOptions& o) {
  check_options(o);
  const int h1 = o.vertical_axis == 0 ? 1 : 0, h2 = o.vertical_axis == 2 ? 1 : 2;
  std::array<int, 3> comps{0, 1, 2};
  const int ncomp = o.two_d ? 2 : 3;
  if (o.two_d) comps = {0, 2, 1};
  if (C.size() < 2)
    throw std::invalid_argument("velocity_distribution: fewer than 2 particles share a cell");
  VelocityDistribution r;
  r.samples = static_cast<long>(C.size());
  const double ns = static_cast<double>(C.size());
  std::array<double, 3> m2{}, m3{}, m4{};
  for (const auto& c : C)
    for (int d = 0; d < 3; ++d) {
      const double c2 = c[d] * c[d];
      m2[d] += c2;
      m3[d] += c2 * c[d];
      m4[d] += c2 * c2;
    }
  double sum_var = 0.0;
  for (int k = 0; k < ncomp; ++k) {
    const int d = comps[static_cast<std::size_t>(k)];
    r.variance[d] = m2[d] / ns;
    if (!(r.variance[d] > 0.0))
      throw std::invalid_argument("velocity_distribution: no fluctuation along axis " +
                                  std::to_string(d));
    const double s = std::sqrt(r.variance[d]);
    r.skewness[d] = m3[d] / ns / (s * s * s);
    r.kurtosis[d] = m4[d] / ns / (r.variance[d] * r.variance[d]);
    sum_var += r.variance[d];
  }
  r.granular_temperature = sum_var / ncomp;
  // Horizontal: the other in-plane axis for discs (x-z plane), the mean of the two otherwise.
  const double horizontal =
      o.two_d ? r.variance[o.vertical_axis == 2 ? 0 : 2] : 0.5 * (r.variance[h1] + r.variance[h2]);
  r.anisotropy = r.variance[o.vertical_axis] / horizontal;
  // Histograms as densities.
  const double w = 2.0 * o.range / o.bins;
  r.bin_centres.resize(static_cast<std::size_t>(o.bins));
  for (int b = 0; b < o.bins; ++b) r.bin_centres[b] = -o.range + (b + 0.5) * w;
  const double ws = o.range / o.bins;
  r.speed_centres.resize(static_cast<std::size_t>(o.bins));
  for (int b = 0; b < o.bins; ++b) r.speed_centres[b] = (b + 0.5) * ws;
  r.speed_density.assign(static_cast<std::size_t>(o.bins), 0.0);
  for (int k = 0; k < ncomp; ++k) {
    const int d = comps[static_cast<std::size_t>(k)];
    auto& h = r.density[d];
    h.assign(static_cast<std::size_t>(o.bins), 0.0);
    const double s = std::sqrt(r.variance[d]);
    for (const auto& c : C) {
      const int b = static_cast<int>(std::floor((c[d] / s + o.range) / w));
      if (b >= 0 && b < o.bins)
        h[static_cast<std::size_t>(b)] += 1.0 / (ns * w);
      else
        r.outside[d] += 1.0 / ns;
    }
  }
  const double st = std::sqrt(r.granular_temperature);
  for (const auto& c : C) {
    double c2 = 0.0;
    for (int k = 0; k < ncomp; ++k) c2 += c[comps[k]] * c[comps[k]];
    const int b = static_cast<int>(std::floor(std::sqrt(c2) / st / ws));
    if (b >= 0 && b < o.bins)
      r.speed_density[static_cast<std::size_t>(b)] += 1.0 / (ns * ws);
    else
      r.speed_outside += 1.0 / ns;
  }
  return r;
}

VelocityDistribution velocity_distribution(const ParticleStore& p, const std::array<double, 3>& lo,
                                           const std::array<double, 3>& hi,
                                           const VelocityDistributionOptions& o) {
  std::vector<std::array<double, 3>> C;
  append_velocity_fluctuations(p, lo, hi, o, C);
  return fluctuation_distribution(C, o);
}

} // namespace fluidem
