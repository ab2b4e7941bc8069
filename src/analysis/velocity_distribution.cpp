#include "analysis/velocity_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

namespace {
/// Each particle's cell (or SIZE_MAX for none) and the cells' mass-weighted mean velocities and
/// particle counts.
struct CellMeans {
  std::vector<std::size_t> cell;
  std::vector<double> mass, mv[3];
  std::vector<long> count;
};

CellMeans cell_means(const ParticleStore& p, const std::array<double, 3>& lo,
                     const std::array<double, 3>& hi, const VelocityDistributionOptions& o) {
  check_options(o);
  std::array<int, 3> nc = o.cells;
  for (int d = 0; d < 3; ++d)
    if (nc[d] < 1 || !(hi[d] > lo[d]))
      throw std::invalid_argument("velocity_distribution: bad cells or box along axis " +
                                  std::to_string(d));
  const std::size_t ncell = static_cast<std::size_t>(nc[0]) * nc[1] * nc[2];
  const std::size_t n = p.size();
  CellMeans m;
  m.cell.resize(n);
  m.mass.assign(ncell, 0.0);
  for (auto& v : m.mv) v.assign(ncell, 0.0);
  m.count.assign(ncell, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double x[3] = {p.x[i], p.y[i], p.z[i]};
    std::size_t q = 0, stride = 1;
    for (int d = 0; d < 3; ++d) {
      const int c = std::clamp(
          static_cast<int>(std::floor((x[d] - lo[d]) / (hi[d] - lo[d]) * nc[d])), 0, nc[d] - 1);
      q += static_cast<std::size_t>(c) * stride;
      stride *= static_cast<std::size_t>(nc[d]);
    }
    m.cell[i] = q;
    m.mass[q] += p.mass[i];
    m.mv[0][q] += p.mass[i] * p.vx[i];
    m.mv[1][q] += p.mass[i] * p.vy[i];
    m.mv[2][q] += p.mass[i] * p.vz[i];
    ++m.count[q];
  }
  return m;
}

/// C_i: particle i's velocity less the mass-weighted mean of its cell.
std::array<double, 3> fluctuation(const ParticleStore& p, const CellMeans& m, std::size_t i) {
  const std::size_t q = m.cell[i];
  const double v[3] = {p.vx[i], p.vy[i], p.vz[i]};
  std::array<double, 3> c{};
  for (int d = 0; d < 3; ++d) c[d] = v[d] - m.mv[d][q] / m.mass[q];
  return c;
}
} // namespace

void append_velocity_fluctuations(const ParticleStore& p, const std::array<double, 3>& lo,
                                  const std::array<double, 3>& hi,
                                  const VelocityDistributionOptions& o,
                                  std::vector<std::array<double, 3>>& C,
                                  std::vector<std::size_t>* which,
                                  std::vector<std::array<double, 3>>* local_scale) {
  const CellMeans m = cell_means(p, lo, hi, o);
  // The cells' rms fluctuations, for local_scale.
  std::array<std::vector<double>, 3> sum2;
  if (local_scale) {
    for (auto& s : sum2) s.assign(m.count.size(), 0.0);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto c = fluctuation(p, m, i);
      for (int d = 0; d < 3; ++d) sum2[d][m.cell[i]] += c[d] * c[d];
    }
  }
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  // Fluctuations about the mass-weighted local mean.
  C.reserve(C.size() + p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t q = m.cell[i];
    if (m.count[q] < 2) continue;
    C.push_back(fluctuation(p, m, i));
    if (which) which->push_back(i);
    if (!local_scale) continue;
    std::array<double, 3> s{nan, nan, nan};
    if (m.count[q] >= o.min_local)
      for (int d = 0; d < 3; ++d) s[d] = std::sqrt(sum2[d][q] / static_cast<double>(m.count[q]));
    local_scale->push_back(s);
  }
}

LocalMoments local_moments(const std::vector<std::array<double, 3>>& C,
                           const std::vector<std::array<double, 3>>& scale,
                           const VelocityDistributionOptions& o) {
  if (scale.size() != C.size())
    throw std::invalid_argument("local_moments: one scale per fluctuation sample needed");
  const int ncomp = o.two_d ? 2 : 3;
  const std::array<int, 3> comps =
      o.two_d ? std::array<int, 3>{0, 2, 1} : std::array<int, 3>{0, 1, 2};
  LocalMoments r;
  std::array<double, 3> m2{}, m3{}, m4{};
  for (std::size_t k = 0; k < C.size(); ++k) {
    bool finite = true;
    for (int j = 0; j < ncomp; ++j) {
      const double s = scale[k][comps[static_cast<std::size_t>(j)]];
      finite = finite && std::isfinite(s) && s > 0.0;
    }
    if (!finite) continue;
    ++r.samples;
    for (int j = 0; j < ncomp; ++j) {
      const int d = comps[static_cast<std::size_t>(j)];
      const double u = C[k][d] / scale[k][d], u2 = u * u;
      m2[d] += u2, m3[d] += u2 * u, m4[d] += u2 * u2;
    }
  }
  if (r.samples < 2)
    throw std::invalid_argument("local_moments: fewer than 2 samples in cells of " +
                                std::to_string(o.min_local) + " particles or more");
  const double ns = static_cast<double>(r.samples);
  for (int j = 0; j < ncomp; ++j) {
    const int d = comps[static_cast<std::size_t>(j)];
    const double var = m2[d] / ns;
    r.skewness[d] = m3[d] / ns / (var * std::sqrt(var));
    r.kurtosis[d] = m4[d] / ns / (var * var);
  }
  return r;
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
