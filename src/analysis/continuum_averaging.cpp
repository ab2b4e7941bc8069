#include "analysis/continuum_averaging.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace fluidem {

namespace {

// Per-cell accumulators (each a sum over particles or contacts times the weight: 1/V_cell for
// the volume method, h or g for the weighted one), summed over the sampled steps.
constexpr std::size_t kMass = 0;     // sum w m
constexpr std::size_t kVolume = 1;   // sum w V_p
constexpr std::size_t kMomentum = 2; // sum w m v (3)
constexpr std::size_t kSecond = 5;   // sum w m v (x) v (9)
constexpr std::size_t kInertia = 14; // sum w I
constexpr std::size_t kSpin = 15;    // sum w I omega (3)
constexpr std::size_t kContact = 18; // sum w f (x) branch (9)
constexpr std::size_t kCouple = 27;  // sum w moment (x) branch (9)
constexpr std::size_t kAccumulators = 36;

using Sums = std::array<double, kAccumulators>;

void add_particle(Sums& s, double w, const ParticleStore& p, std::size_t i) {
  const double r = p.radius[i];
  const double m = p.mass[i];
  const double inertia = p.inv_inertia[i] > 0.0 ? 1.0 / p.inv_inertia[i] : 0.0;
  const double v[3] = {p.vx[i], p.vy[i], p.vz[i]};
  const double wm = w * m;
  s[kMass] += wm;
  s[kVolume] += w * (4.0 / 3.0) * std::numbers::pi * r * r * r;
  for (int a = 0; a < 3; ++a) {
    s[kMomentum + a] += wm * v[a];
    for (int b = 0; b < 3; ++b) s[kSecond + 3 * a + b] += wm * v[a] * v[b];
  }
  const double wi = w * inertia;
  s[kInertia] += wi;
  s[kSpin + 0] += wi * p.wx[i];
  s[kSpin + 1] += wi * p.wy[i];
  s[kSpin + 2] += wi * p.wz[i];
}

/// s += w f (x) l at kContact and w m (x) l at kCouple.
void add_contact(Sums& s, double w, const Vec3& f, const Vec3& m, const Vec3& l) {
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      s[kContact + 3 * a + b] += w * f[a] * l[b];
      s[kCouple + 3 * a + b] += w * m[a] * l[b];
    }
}

/// Stable counting sort of items 0..n-1 by key[item] in [0, bins): start (bins + 1), order.
void bin_items(const std::vector<std::size_t>& key, std::size_t bins,
               std::vector<std::size_t>& start, std::vector<std::size_t>& order) {
  start.assign(bins + 1, 0);
  for (std::size_t k : key) ++start[k + 1];
  for (std::size_t b = 0; b < bins; ++b) start[b + 1] += start[b];
  order.resize(key.size());
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < key.size(); ++i) order[next[key[i]]++] = i;
}

double erf_difference(double lo, double hi) { // erf(hi) - erf(lo) without cancellation
  if (lo > 0.0) return std::erfc(lo) - std::erfc(hi);
  if (hi < 0.0) return std::erfc(-hi) - std::erfc(-lo);
  return std::erf(hi) - std::erf(lo);
}

} // namespace

ContinuumAverager::ContinuumAverager(const ContinuumGrid& grid, const ContinuumSettings& settings)
    : grid_(grid), settings_(settings) {
  const std::string who = "continuum averaging: ";
  for (int a = 0; a < 3; ++a) {
    if (grid_.cells[a] < 1)
      throw std::invalid_argument(who + "cells must be >= 1 along every axis");
    if (!(grid_.spacing[a] > 0.0) || !std::isfinite(grid_.spacing[a]) ||
        !std::isfinite(grid_.lo[a]))
      throw std::invalid_argument(who + "the cell size must be finite and > 0");
    length_[a] = grid_.spacing[a] * grid_.cells[a];
  }
  if (grid_.dimension != 2 && grid_.dimension != 3)
    throw std::invalid_argument(who + "dimension must be 2 or 3");
  if (grid_.dimension == 2 && grid_.cells[1] != 1)
    throw std::invalid_argument(who + "a 2-D run has one cell along y");
  if (settings_.method == AveragingMethod::Weighted) {
    const double w = settings_.width, c = settings_.cutoff;
    if (!(w > 0.0) || !std::isfinite(w)) throw std::invalid_argument(who + "width must be > 0");
    if (!(c > 0.0) || !std::isfinite(c)) throw std::invalid_argument(who + "cutoff must be > 0");
    radius_ = c * w;
    for (int a = 0; a < 3; ++a)
      if (grid_.periodic[a] && !(grid_.dimension == 2 && a == 1) && radius_ > 0.5 * length_[a])
        throw std::invalid_argument(who + "cutoff * width exceeds half the periodic length along " +
                                    std::string(1, "xyz"[a]));
    // Normalised over the truncated ball (disc in 2-D, spread over the depth): int h dV = 1.
    if (grid_.dimension == 3) {
      const double mass = std::erf(c / std::numbers::sqrt2) -
                          std::sqrt(2.0 / std::numbers::pi) * c * std::exp(-0.5 * c * c);
      norm_ = 1.0 / (std::pow(2.0 * std::numbers::pi, 1.5) * w * w * w * mass);
    } else {
      const double mass = -std::expm1(-0.5 * c * c);
      norm_ = 1.0 / (2.0 * std::numbers::pi * w * w * mass * length_[1]);
    }
  }
  state_.sums.assign(grid_.size() * kAccumulators, 0.0);
}

void ContinuumAverager::reset() {
  std::fill(state_.sums.begin(), state_.sums.end(), 0.0);
  state_.samples = 0;
}

void ContinuumAverager::set_state(ContinuumState s) {
  if (s.sums.size() != grid_.size() * kAccumulators || s.samples < 0)
    throw std::invalid_argument("continuum averaging: the saved sums do not fit the grid");
  state_ = std::move(s);
}

std::array<int, 3> ContinuumAverager::cell_of(double x, double y, double z) const {
  const double q[3] = {x, y, z};
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) {
    double v = q[a] - grid_.lo[a];
    if (grid_.periodic[a]) v -= length_[a] * std::floor(v / length_[a]);
    const double k = std::floor(v / grid_.spacing[a]);
    c[a] = static_cast<int>(std::clamp(k, 0.0, static_cast<double>(grid_.cells[a] - 1)));
  }
  return c;
}

Vec3 ContinuumAverager::min_image(Vec3 d) const {
  for (int a = 0; a < 3; ++a)
    if (grid_.periodic[a]) d[a] -= length_[a] * std::round(d[a] / length_[a]);
  return d;
}

double ContinuumAverager::weight(double rx, double ry, double rz) const {
  const double r2 = grid_.dimension == 2 ? rx * rx + rz * rz : rx * rx + ry * ry + rz * rz;
  if (r2 > radius_ * radius_) return 0.0;
  const double w = settings_.width;
  return norm_ * std::exp(-r2 / (2.0 * w * w));
}

double ContinuumAverager::segment_weight(const Vec3& a_in, const Vec3& d_in) const {
  Vec3 a = a_in, d = d_in;
  if (grid_.dimension == 2) a.y = d.y = 0.0;
  const double w = settings_.width;
  const double dd = norm2(d);
  if (!(dd > 1e-24 * w * w)) return weight(a.x, a.y, a.z); // a point
  const double b = dot(a, d);
  const double s0 = -b / dd;                              // closest point of the line
  const double p2 = std::max(0.0, norm2(a) - b * b / dd); // its squared distance
  const double r2 = radius_ * radius_;
  if (p2 >= r2) return 0.0;
  const double half = std::sqrt((r2 - p2) / dd); // the chord inside the cutoff ball, in s
  const double s_lo = std::max(0.0, s0 - half), s_hi = std::min(1.0, s0 + half);
  if (!(s_hi > s_lo)) return 0.0;
  const double len = std::sqrt(dd);
  const double k = len / (std::numbers::sqrt2 * w);
  // int exp(-(len^2 (s - s0)^2 + p2) / (2 w^2)) ds = exp(-p2/2w^2) sqrt(pi)/(2k) [erf]
  return norm_ * std::exp(-p2 / (2.0 * w * w)) * 0.5 * std::sqrt(std::numbers::pi) / k *
         erf_difference(k * (s_lo - s0), k * (s_hi - s0));
}

void ContinuumAverager::accumulate(const ParticleStore& p,
                                   const std::vector<ContactSample>& contacts) {
  if (settings_.method == AveragingMethod::Volume)
    accumulate_volume(p, contacts);
  else
    accumulate_weighted(p, contacts);
  ++state_.samples;
}

std::size_t ContinuumAverager::flat(const std::array<int, 3>& c) const {
  const auto& g = grid_.cells;
  return static_cast<std::size_t>(c[0]) +
         static_cast<std::size_t>(g[0]) *
             (static_cast<std::size_t>(c[1]) +
              static_cast<std::size_t>(g[1]) * static_cast<std::size_t>(c[2]));
}

void ContinuumAverager::bin_particles(const ParticleStore& p) {
  key_.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) key_[i] = flat(cell_of(p.x[i], p.y[i], p.z[i]));
  bin_items(key_, grid_.size(), start_, order_);
}

void ContinuumAverager::accumulate_volume(const ParticleStore& p,
                                          const std::vector<ContactSample>& contacts) {
  const std::size_t n = p.size(), cells = grid_.size();
  bin_particles(p);
  const std::vector<std::size_t>& key = key_;
  // Half contacts: item 2k is contact k seen from i, 2k + 1 from j (unused for walls).
  std::vector<std::size_t> half_key;
  std::vector<std::size_t> half_item;
  half_key.reserve(2 * contacts.size());
  half_item.reserve(2 * contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const ContactSample& c = contacts[k];
    half_key.push_back(key[static_cast<std::size_t>(c.i)]);
    half_item.push_back(2 * k);
    if (c.j >= 0) {
      half_key.push_back(key[static_cast<std::size_t>(c.j)]);
      half_item.push_back(2 * k + 1);
    }
  }
  bin_items(half_key, cells, seg_start_, seg_order_);

  const double inv_v = 1.0 / grid_.cell_volume();
  double* const acc = state_.sums.data();
  const long ncell = static_cast<long>(cells);
  // Threads only for large steps: a parallel region costs more than a small bed's sums.
  const bool parallel = n + contacts.size() > settings_.parallel_threshold;
#pragma omp parallel for schedule(dynamic, 16) if (parallel)
  for (long cl = 0; cl < ncell; ++cl) {
    const std::size_t c = static_cast<std::size_t>(cl);
    Sums s{};
    for (std::size_t q = start_[c]; q < start_[c + 1]; ++q) add_particle(s, 1.0, p, order_[q]);
    for (std::size_t q = seg_start_[c]; q < seg_start_[c + 1]; ++q) {
      const std::size_t item = half_item[seg_order_[q]];
      const ContactSample& cs = contacts[item / 2];
      const bool partner = item % 2 == 1;
      const std::size_t i = static_cast<std::size_t>(partner ? cs.j : cs.i);
      // Branch from the particle's centre to the contact point [Zhu07 Table 5, Method 3].
      const Vec3 l = min_image(cs.contact_point - p.position(i));
      const Vec3 f = partner ? -cs.force : cs.force;
      const Vec3 t = partner ? -cs.torque_roll : cs.torque_roll;
      add_contact(s, 1.0, f, cross(l, f) + t, l);
    }
    for (std::size_t a = 0; a < kAccumulators; ++a) acc[c * kAccumulators + a] += s[a] * inv_v;
  }
}

void ContinuumAverager::accumulate_weighted(const ParticleStore& p,
                                            const std::vector<ContactSample>& contacts) {
  const std::size_t n = p.size(), cells = grid_.size();
  const auto& g = grid_.cells;
  bin_particles(p);

  // One segment per contact: the branch d from x_i to x_j (pairs) or to the contact point on
  // the wall, binned by its midpoint. f: force on i; q: the moment the couple stress takes.
  struct Segment {
    Vec3 mid, d, f, q;
  };
  std::vector<Segment> seg(contacts.size());
  std::vector<std::size_t> seg_key(contacts.size());
  double half_max = 0.0;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const ContactSample& c = contacts[k];
    const Vec3 xi = p.position(static_cast<std::size_t>(c.i));
    const Vec3 li = min_image(c.contact_point - xi);
    Segment& s = seg[k];
    s.f = c.force;
    if (c.j >= 0) {
      s.d = min_image(p.position(static_cast<std::size_t>(c.j)) - xi);
      // (m_ij - m_ji) / 2 with m_ij = l_i x f + t, m_ji = (l_i - d) x (-f) - t.
      s.q = cross(li - 0.5 * s.d, c.force) + c.torque_roll;
    } else {
      s.d = li;
      s.q = cross(li, c.force) + c.torque_roll;
    }
    s.mid = xi + 0.5 * s.d;
    seg_key[k] = flat(cell_of(s.mid.x, s.mid.y, s.mid.z));
    half_max = std::max(half_max, 0.5 * norm(s.d));
  }
  bin_items(seg_key, cells, seg_start_, seg_order_);

  // Bins to visit around a cell along axis a for items within `reach` of its centre.
  const auto range = [&](int a, double reach) { // {count, all}
    const int r = static_cast<int>(std::ceil(reach / grid_.spacing[a])) + 1;
    return r;
  };
  std::array<int, 3> rp{}, rs{};
  for (int a = 0; a < 3; ++a) {
    rp[a] = range(a, radius_);
    rs[a] = range(a, radius_ + half_max);
  }
  double* const acc = state_.sums.data();
  const long ncell = static_cast<long>(cells);
  const bool parallel = n + contacts.size() > settings_.parallel_threshold / 16;
#pragma omp parallel for schedule(dynamic, 4) if (parallel)
  for (long cl = 0; cl < ncell; ++cl) {
    const std::size_t c = static_cast<std::size_t>(cl);
    const int ci[3] = {
        static_cast<int>(c % static_cast<std::size_t>(g[0])),
        static_cast<int>((c / static_cast<std::size_t>(g[0])) % static_cast<std::size_t>(g[1])),
        static_cast<int>(c / (static_cast<std::size_t>(g[0]) * static_cast<std::size_t>(g[1])))};
    const Vec3 centre{grid_.lo[0] + (ci[0] + 0.5) * grid_.spacing[0],
                      grid_.lo[1] + (ci[1] + 0.5) * grid_.spacing[1],
                      grid_.lo[2] + (ci[2] + 0.5) * grid_.spacing[2]};
    // The bins along each axis, in increasing order, each once.
    const auto bins_along = [&](int a, int reach, std::vector<int>& out) {
      out.clear();
      const int lo = ci[a] - reach, hi = ci[a] + reach;
      if (grid_.periodic[a] && hi - lo + 1 < g[a]) {
        for (int k = lo; k <= hi; ++k) out.push_back(((k % g[a]) + g[a]) % g[a]);
        std::sort(out.begin(), out.end());
      } else {
        for (int k = std::max(0, lo); k <= std::min(g[a] - 1, hi); ++k) out.push_back(k);
      }
    };
    std::array<std::vector<int>, 3> b;
    Sums s{};
    for (int a = 0; a < 3; ++a) bins_along(a, rp[a], b[a]);
    for (int kz : b[2])
      for (int ky : b[1])
        for (int kx : b[0]) {
          const std::size_t bin = flat({kx, ky, kz});
          for (std::size_t q = start_[bin]; q < start_[bin + 1]; ++q) {
            const std::size_t i = order_[q];
            const Vec3 r = min_image(p.position(i) - centre);
            const double h = weight(r.x, r.y, r.z);
            if (h != 0.0) add_particle(s, h, p, i);
          }
        }
    for (int a = 0; a < 3; ++a) bins_along(a, rs[a], b[a]);
    for (int kz : b[2])
      for (int ky : b[1])
        for (int kx : b[0]) {
          const std::size_t bin = flat({kx, ky, kz});
          for (std::size_t q = seg_start_[bin]; q < seg_start_[bin + 1]; ++q) {
            const Segment& sg = seg[seg_order_[q]];
            const Vec3 a = min_image(sg.mid - centre) - 0.5 * sg.d;
            const double gw = segment_weight(a, sg.d);
            if (gw != 0.0) add_contact(s, gw, sg.f, sg.q, sg.d);
          }
        }
    for (std::size_t a = 0; a < kAccumulators; ++a) acc[c * kAccumulators + a] += s[a];
  }
}

ContinuumFields ContinuumAverager::result() const {
  const std::size_t cells = grid_.size();
  ContinuumFields f;
  f.samples = state_.samples;
  f.solid_fraction.assign(cells, 0.0);
  f.granular_temperature.assign(cells, 0.0);
  for (auto* group : {&f.velocity, &f.angular_vel})
    for (auto& v : *group) v.assign(cells, 0.0);
  for (auto* group : {&f.kinetic_stress, &f.contact_stress, &f.couple_stress})
    for (auto& v : *group) v.assign(cells, 0.0);
  if (state_.samples == 0) return f;
  const double inv_n = 1.0 / static_cast<double>(state_.samples);
  for (std::size_t c = 0; c < cells; ++c) {
    const double* s = state_.sums.data() + c * kAccumulators;
    f.solid_fraction[c] = s[kVolume] * inv_n;
    double u[3] = {0, 0, 0};
    if (s[kMass] > 0.0)
      for (int a = 0; a < 3; ++a) u[a] = s[kMomentum + a] / s[kMass];
    for (int a = 0; a < 3; ++a) {
      f.velocity[a][c] = u[a];
      f.angular_vel[a][c] = s[kInertia] > 0.0 ? s[kSpin + a] / s[kInertia] : 0.0;
      for (int b = 0; b < 3; ++b) {
        const std::size_t ab = static_cast<std::size_t>(3 * a + b);
        // -sum w m (v - u)(v - u) = -(sum w m v v - (sum w m) u u), u the time average
        f.kinetic_stress[ab][c] = -(s[kSecond + ab] - s[kMass] * u[a] * u[b]) * inv_n;
        f.contact_stress[ab][c] = s[kContact + ab] * inv_n;
        f.couple_stress[ab][c] = s[kCouple + ab] * inv_n;
      }
    }
    if (s[kMass] > 0.0) { // the mass density of the cell is s[kMass] * inv_n
      const double trace = f.kinetic_stress[0][c] + f.kinetic_stress[4][c] + f.kinetic_stress[8][c];
      const double dims = grid_.dimension == 2 ? 2.0 : 3.0;
      f.granular_temperature[c] = -trace / (dims * s[kMass] * inv_n);
    }
  }
  return f;
}

} // namespace fluidem
