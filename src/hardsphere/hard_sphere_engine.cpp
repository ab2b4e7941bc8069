#include "hardsphere/hard_sphere_engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <omp.h>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/material_mixing.hpp"
#include "core/simd_clones.hpp"
#include "hardsphere/fixed_partner_time.hpp"

namespace fluidem {

namespace {
/// Below this many particles the per-step loops run on one thread, as in NeighbourList: a fork
/// and its barriers cost more than the loops (and, on a machine whose cores are shared, a
/// barrier can wait a whole time slice: the 2400-sphere bubble bed took 99 ms per step on two
/// threads at load 12 with the loops parallel above 512 particles).
constexpr std::size_t kParallelMin = 4096;

/// Time until spheres of separation r (from the partner to this one) and relative velocity v
/// (this one's minus the partner's), whose radii sum to sigma, touch, moving in straight lines:
/// [Deen07 eq. 45], written as c / (-b + sqrt(b^2 - v^2 c)) to avoid cancellation. Infinity if
/// they move apart, miss, or cannot meet within `horizon` (the root is at least c / (2 |b|),
/// since sqrt(disc) <= |b|: such pairs are passed over without the square root and the division;
/// the margin 1e-9 covers the round-off of the root, so the choice is the same as with it).
/// Touching spheres (c <= 0, round-off) collide now if approaching along the normal, judged with
/// the same arithmetic as the collision operator so that both agree. The engine's loops use
/// pair_times below, eight pairs at once and bitwise the same, and this for the touching pairs.
double time_to_contact(const Vec3& r, const Vec3& v, double sigma, double horizon) {
  constexpr double never = std::numeric_limits<double>::infinity();
  const double b = dot(r, v);
  if (b >= 0.0) return never; // moving apart
  const double c = norm2(r) - sigma * sigma;
  if (c <= 0.0) return dot(v, r / norm(r)) >= 0.0 ? never : 0.0;
  if (c > -2.0 * b * horizon * (1.0 + 1e-9)) return never;
  const double disc = b * b - norm2(v) * c;
  if (disc < 0.0) return never; // miss
  return c / (-b + std::sqrt(disc));
}

/// Up to kLanes pairs of one particle, as separations and relative velocities (as for
/// time_to_contact), for pair_times; unused lanes hold zeros.
struct PairLanes {
  static constexpr int kLanes = 8;
  alignas(64) double rx[kLanes], ry[kLanes], rz[kLanes], vx[kLanes], vy[kLanes], vz[kLanes],
      sigma[kLanes];
  alignas(64) double dt[kLanes];       ///< out: time to contact, infinity if none
  alignas(64) double touching[kLanes]; ///< out: 1 where c <= 0 and b < 0 (time_to_contact's
                                       ///< special case, left to it), else 0
  /// Zeros in lanes m.. (pairs that never meet).
  void clear_from(int m) {
    for (int k = m; k < kLanes; ++k) clear(k);
  }
  /// Zeros in lane k (a pair that never meets, or one with a fixed particle: computed apart).
  void clear(int k) { rx[k] = ry[k] = rz[k] = vx[k] = vy[k] = vz[k] = sigma[k] = 0.0; }
  double time_to_contact(int k, double horizon) const {
    return fluidem::time_to_contact(Vec3{rx[k], ry[k], rz[k]}, Vec3{vx[k], vy[k], vz[k]}, sigma[k],
                                    horizon);
  }
};

/// time_to_contact(r, v, sigma, horizon) of every lane at once, without its branches: the
/// pairs moving apart, missing, beyond the horizon or touching get infinity (the touching ones
/// flagged, for time_to_contact), the others c / (-b + sqrt(disc)) with the same operations in
/// the same order, so the same bits. Whether a pair moves apart is a coin toss in a dense bed;
/// as branches, these tests were the event engine's most frequent mispredictions.
FLUIDEM_SIMD_CLONES void pair_times(PairLanes& l, double horizon) {
  constexpr double never = std::numeric_limits<double>::infinity();
#pragma GCC ivdep
  for (int k = 0; k < PairLanes::kLanes; ++k) {
    const double rx = l.rx[k], ry = l.ry[k], rz = l.rz[k];
    const double vx = l.vx[k], vy = l.vy[k], vz = l.vz[k];
    const double b = rx * vx + ry * vy + rz * vz;
    const double c = (rx * rx + ry * ry + rz * rz) - l.sigma[k] * l.sigma[k];
    const double disc = b * b - (vx * vx + vy * vy + vz * vz) * c;
    const double t = c / (-b + std::sqrt(disc > 0.0 ? disc : 0.0));
    const bool meets =
        b < 0.0 && c > 0.0 && !(c > -2.0 * b * horizon * (1.0 + 1e-9)) && disc >= 0.0;
    l.dt[k] = meets ? t : never;
    l.touching[k] = b < 0.0 && c <= 0.0 ? 1.0 : 0.0;
  }
}

hardsphere::CollisionLaw law_from(const MixedCoefficients& m) {
  return {m.restitution, m.friction, m.tangential_restitution};
}
} // namespace

HardSphereEngine::HardSphereEngine(const CaseSpec& spec, const BoxGeometry& box)
    : dimension_(spec.simulation.dimension), nspecies_(static_cast<int>(spec.species.size())),
      opts_(spec.hardsphere), box_(box) {
  pair_law_.resize(nspecies_ * nspecies_);
  wall_law_.resize(nspecies_ * 6);
  for (int i = 0; i < nspecies_; ++i) {
    for (int j = 0; j < nspecies_; ++j)
      pair_law_[i * nspecies_ + j] =
          law_from(mix_pair(spec.species[i].material, spec.species[j].material));
    for (int f = 0; f < 6; ++f)
      wall_law_[i * 6 + f] = law_from(wall_coefficients(spec.domain.wall_material[f]));
  }
}

std::size_t HardSphereEngine::build_list(const ParticleStore& p, double short_skin) {
  // Cells at least 2 R_max + skin wide; each particle scans the (up to 27, deduplicated on
  // periodic axes with fewer than 3 cells) cells around its own for the partners above it
  // closer than R_i + R_j + skin: each pair once, from the positions alone (the separation and
  // the cut are the same bits from either side), so the list does not depend on the number of
  // threads. The rows' parts below their particles are then the transpose of these.
  const std::size_t n = p.size();
  double rmax = 0.0;
#pragma omp parallel for schedule(static) reduction(max : rmax) if (n >= kParallelMin)
  for (std::size_t i = 0; i < n; ++i) rmax = std::max(rmax, p.radius[i]);
  // (The grid's work and memory are bounded by the particle count: CellGrid.)
  cell_size_ = 2.0 * rmax + skin_;
  grid_.bin(box_, cell_size_, p.x.data(), p.y.data(), p.z.data(), n, n >= kParallelMin);

  std::size_t within_short = 0;
  const int nthreads = n >= kParallelMin ? omp_get_max_threads() : 1;
  if (static_cast<int>(thread_rows_.size()) < nthreads) thread_rows_.resize(nthreads);
  split_.resize(n); // each row's part above its particle: its length, until the offsets
  int used = 1;     // the threads the scan had
#pragma omp parallel num_threads(nthreads) reduction(+ : within_short)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    if (t == 0) used = nt;
    const std::size_t i0 = n * t / nt, i1 = n * (t + 1) / nt;
    std::vector<std::uint32_t>& rows = thread_rows_[t];
    rows.clear();
    // The scan's arrays, box and skin in locals: the rows' stores would otherwise make the
    // compiler reload them for every candidate. min_image() as it is, without its division
    // where the separation is at most half a period (nearest_integer(d / l) is then 0, ties
    // going to even): the same separations, so the same rows.
    const double *const px = p.x.data(), *const py = p.y.data(), *const pz = p.z.data(),
                        *const pr = p.radius.data();
    const double skin = skin_;
    std::array<double, 3> period{}, half{};
    for (int a = 0; a < 3; ++a) {
      period[a] = box_.periodic[a] ? box_.length(a) : std::numeric_limits<double>::infinity();
      half[a] = 0.5 * period[a];
    }
    const auto image = [&](double d, int a) {
      return std::abs(d) <= half[a] ? d : d - period[a] * nearest_integer(d / period[a]);
    };
    for (std::size_t i = i0; i < i1; ++i) {
      const double xi = px[i], yi = py[i], zi = pz[i], ri = pr[i];
      const bool fixed_i = p.fixed(i); // two fixed particles never meet: no pair of them
      const std::size_t before = rows.size();
      grid_.for_each_near_above(i, box_.periodic, [&](std::uint32_t j) {
        if (fixed_i && p.fixed(j)) return;
        const double ddx = image(px[j] - xi, 0);
        const double ddy = image(py[j] - yi, 1);
        const double ddz = image(pz[j] - zi, 2);
        const double cut = ri + pr[j] + skin, cut_short = ri + pr[j] + short_skin;
        const double d2 = ddx * ddx + ddy * ddy + ddz * ddz;
        if (d2 < cut * cut) { // (short_skin <= skin_: the short list's pairs are among these)
          rows.push_back(j);
          within_short += d2 < cut_short * cut_short ? 1 : 0;
        }
      });
      std::sort(rows.begin() + static_cast<std::ptrdiff_t>(before), rows.end());
      split_[i] = static_cast<std::uint32_t>(rows.size() - before);
    }
  }
  // The full rows in ascending partner order: row i's partners below i, then those above
  // (split_[i], the first of these). The pairs (i, j > i) taken in ascending i hand each row j
  // its part below j in ascending order, and each such entry its mirror_, the entry (i, j) of
  // row i which holds the pair's time in the sweep, in the same pass.
  std::vector<std::uint32_t>& lower = mirror_cursor_;
  lower.assign(n, 0);
  for (int t = 0; t < used; ++t)
    for (const std::uint32_t j : thread_rows_[t]) ++lower[j];
  full_offset_.resize(n + 1);
  full_offset_[0] = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t above = split_[i];
    split_[i] = full_offset_[i] + lower[i];
    full_offset_[i + 1] = split_[i] + above;
    lower[i] = full_offset_[i]; // from here: row i's next entry below i
  }
  full_partner_.resize(full_offset_[n]);
  mirror_.resize(full_offset_[n]);
  std::size_t i = 0;
  for (int t = 0; t < used; ++t) {
    const std::uint32_t* row = thread_rows_[t].data();
    for (const std::size_t i1 = n * (t + 1) / used; i < i1; ++i)
      for (std::uint32_t e = split_[i]; e < full_offset_[i + 1]; ++e) {
        const std::uint32_t j = *row++;
        full_partner_[e] = j;
        full_partner_[lower[j]] = static_cast<std::uint32_t>(i);
        mirror_[lower[j]++] = e;
      }
  }
  return 2 * within_short; // (entries: each pair counts in both rows)
}

void HardSphereEngine::link_rows() {
  // In one pass over the rows in order, each row's entries below its split (ascending
  // partners) are handed out by a cursor as the rows of those partners come by, instead of a
  // binary search per entry (the list is symmetric: j is in row i exactly when i is in row j).
  const std::size_t n = full_offset_.size() - 1;
  split_.resize(n);
  mirror_.resize(full_partner_.size());
  std::vector<std::uint32_t>& cursor = mirror_cursor_; // kept between builds
  cursor.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto row0 = full_partner_.begin() + full_offset_[i];
    const auto row1 = full_partner_.begin() + full_offset_[i + 1];
    split_[i] = static_cast<std::uint32_t>(
        std::upper_bound(row0, row1, static_cast<std::uint32_t>(i)) - full_partner_.begin());
    cursor[i] = full_offset_[i];
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t e = split_[i]; e < full_offset_[i + 1]; ++e)
      mirror_[cursor[full_partner_[e]]++] = e;
}

void HardSphereEngine::permute(const std::vector<std::uint32_t>& new_to_old) {
  // The per-particle state that lives between steps follows its particle; the list is
  // renumbered, each row sorted again by partner: the list a build at the same positions in
  // the new order makes, so it keeps its life (and the skin policy its counts).
  const std::size_t n = new_to_old.size();
  const auto follow = [&](auto& a) {
    if (a.size() != n) return; // (none yet)
    const auto old = a;
    for (std::size_t k = 0; k < n; ++k) a[k] = old[new_to_old[k]];
  };
  follow(last_collision_);
  follow(counter_);
  follow(built_x_);
  follow(built_y_);
  follow(built_z_);
  if (full_offset_.size() != n + 1) return;
  std::vector<std::uint32_t> old_to_new(n);
  for (std::size_t k = 0; k < n; ++k) old_to_new[new_to_old[k]] = static_cast<std::uint32_t>(k);
  std::vector<std::uint32_t> offset(n + 1, 0), partner(full_partner_.size());
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t o = new_to_old[k];
    const std::uint32_t e0 = full_offset_[o], e1 = full_offset_[o + 1];
    offset[k + 1] = offset[k] + (e1 - e0);
    for (std::uint32_t e = e0; e < e1; ++e)
      partner[offset[k] + (e - e0)] = old_to_new[full_partner_[e]];
    std::sort(partner.begin() + offset[k], partner.begin() + offset[k + 1]);
  }
  // (copied into the list's own arrays, which keep their capacity for the next builds)
  std::copy(offset.begin(), offset.end(), full_offset_.begin());
  std::copy(partner.begin(), partner.end(), full_partner_.begin());
  link_rows();
}

void HardSphereEngine::first_events(double now) {
  // At the start of a step every clock is `now`: the flights of predict() vanish (x + 0 = x),
  // and a pair's time is the same from either side (r and v change sign exactly). So each pair
  // is computed once (under its lower index), and each particle then takes the earliest of its
  // row in row order, as predict() does: the same events, with half the pair arithmetic.
  const std::size_t n = kin_.size();
  pair_time_.resize(full_partner_.size());
  constexpr double none = std::numeric_limits<double>::infinity();
#pragma omp parallel if (n >= kParallelMin)
  {
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const Kin& ki = kin_[i];
      const std::uint32_t end = full_offset_[i + 1];
      PairLanes lanes;
      for (std::uint32_t base = split_[i]; base < end; base += PairLanes::kLanes) {
        const auto m = static_cast<int>(std::min<std::uint32_t>(PairLanes::kLanes, end - base));
        for (int k = 0; k < m; ++k) {
          const std::uint32_t j = full_partner_[base + static_cast<std::uint32_t>(k)];
          const Kin& kj = kin_[j];
          if (any_fixed_ && (fixed_[i] || fixed_[j])) { // the moving one's parabola, below
            lanes.clear(k);
            continue;
          }
          lanes.rx[k] = min_image(ki.x - kj.x, 0);
          lanes.ry[k] = min_image(ki.y - kj.y, 1);
          lanes.rz[k] = min_image(ki.z - kj.z, 2);
          lanes.vx[k] = ki.vx - kj.vx;
          lanes.vy[k] = ki.vy - kj.vy;
          lanes.vz[k] = ki.vz - kj.vz;
          lanes.sigma[k] = ki.r + kj.r;
        }
        lanes.clear_from(m);
        pair_times(lanes, t_end_ - now);
        for (int k = 0; k < m; ++k) {
          double dt = lanes.dt[k];
          if (lanes.touching[k] != 0.0) dt = lanes.time_to_contact(k, t_end_ - now);
          pair_time_[base + static_cast<std::uint32_t>(k)] = dt < none ? now + dt : none;
        }
        for (int k = 0; k < m && any_fixed_; ++k) { // the pairs with a fixed particle
          const std::uint32_t j = full_partner_[base + static_cast<std::uint32_t>(k)];
          if (!fixed_[i] && !fixed_[j]) continue;
          const Kin& moving = fixed_[i] ? kin_[j] : ki;
          pair_time_[base + static_cast<std::uint32_t>(k)] =
              fixed_pair_time(moving, Vec3{moving.x, moving.y, moving.z},
                              Vec3{moving.vx, moving.vy, moving.vz}, fixed_[i] ? ki : kin_[j], now);
        }
      }
    }
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      double best = t_end_;
      std::uint32_t partner = kNone;
      if (any_fixed_ && fixed_[i]) { // no event of its own: its moving partners have them
        next_[i] = Event{best, static_cast<std::uint32_t>(i), kNone, 0u, 0u};
        continue;
      }
      for (std::uint32_t e = full_offset_[i]; e < full_offset_[i + 1]; ++e) {
        const double t = pair_time_[e < split_[i] ? mirror_[e] : e];
        if (t < best) best = t, partner = full_partner_[e];
      }
      const Kin& ki = kin_[i];
      wall_event(ki, Vec3{ki.x, ki.y, ki.z}, Vec3{ki.vx, ki.vy, ki.vz}, now, best, partner);
      const auto ii = static_cast<std::uint32_t>(i);
      next_[i] = partner == kNone
                     ? Event{best, ii, partner, 0u, 0u}
                     : Event{best, ii, partner, counter_[i], partner < n ? counter_[partner] : 0u};
    }
  }
}

// The event calendar: a binary min-heap of the particles that have an event before the end of
// the step, keyed by the time of their one current event (next_[i]); ties by index. A new
// prediction replaces the particle's entry in place, so no stale events pile up. Each entry
// holds its key (the time) beside the particle, so that a sift compares within the heap's own
// array instead of looking up next_ per comparison (faster; the measurements, with four and
// eight children per node, in bench/RESULTS.md). The keys (t, i) are distinct, so the
// earliest event, and with it the order of the collisions, does not depend on the heap's shape.
bool HardSphereEngine::earlier(const QueueEntry& a, const QueueEntry& b) {
  return a.t < b.t || (a.t == b.t && a.i < b.i);
}

void HardSphereEngine::sift_up(std::uint32_t k) {
  const QueueEntry e = queue_[k];
  while (k > 0) {
    const std::uint32_t up = (k - 1) / kArity;
    if (!earlier(e, queue_[up])) break;
    queue_[k] = queue_[up];
    slot_[queue_[k].i] = k;
    k = up;
  }
  queue_[k] = e;
  slot_[e.i] = k;
}

void HardSphereEngine::sift_down(std::uint32_t k) {
  const auto size = static_cast<std::uint32_t>(queue_.size());
  const QueueEntry e = queue_[k];
  for (;;) {
    const std::uint32_t first = kArity * k + 1;
    if (first >= size) break;
    const std::uint32_t last = std::min(first + kArity, size);
    std::uint32_t c = first;
    for (std::uint32_t m = first + 1; m < last; ++m)
      if (earlier(queue_[m], queue_[c])) c = m;
    if (!earlier(queue_[c], e)) break;
    queue_[k] = queue_[c];
    slot_[queue_[k].i] = k;
    k = c;
  }
  queue_[k] = e;
  slot_[e.i] = k;
}

void HardSphereEngine::set_event(const Event& ev) {
  const std::uint32_t i = ev.a;
  const bool has = ev.b != kNone;
  std::uint32_t k = slot_[i];
  if (k == kNone) {
    if (!has) return;
    next_[i] = ev;
    k = static_cast<std::uint32_t>(queue_.size());
    queue_.push_back({ev.t, i});
    sift_up(k);
    return;
  }
  const double before = next_[i].t;
  if (!has) { // leaves the calendar: the last entry takes its place
    slot_[i] = kNone;
    const QueueEntry last = queue_.back();
    queue_.pop_back();
    if (last.i == i) return;
    queue_[k] = last;
    slot_[last.i] = k;
    sift_up(k);
    sift_down(slot_[last.i]);
    return;
  }
  next_[i] = ev;
  queue_[k].t = ev.t;
  if (ev.t < before)
    sift_up(k);
  else
    sift_down(k);
}

HardSphereEngine::Event HardSphereEngine::predict(const ParticleStore& p, std::uint32_t i,
                                                  double now) const {
  const auto n = static_cast<std::uint32_t>(p.size());
  if (any_fixed_ && fixed_[i]) return {t_end_, i, kNone, 0u, 0u}; // never moves: no event
  const Kin& ki = kin_[i];
  const double ai = now - ki.t;
  const Vec3 xi{ki.x + (ki.vx + 0.5 * g_.x * ai) * ai, ki.y + (ki.vy + 0.5 * g_.y * ai) * ai,
                ki.z + (ki.vz + 0.5 * g_.z * ai) * ai};
  const Vec3 vi = Vec3{ki.vx, ki.vy, ki.vz} + g_ * ai;
  double best = t_end_;
  std::uint32_t partner = kNone;
  // Pairs: both fall with the same g, so their relative motion is a straight line
  // (time_to_contact), eight pairs at a time (pair_times).
  const std::uint32_t end = full_offset_[i + 1];
  PairLanes lanes;
  for (std::uint32_t base = full_offset_[i]; base < end; base += PairLanes::kLanes) {
    const auto m = static_cast<int>(std::min<std::uint32_t>(PairLanes::kLanes, end - base));
    bool fixed_partners = false;
    for (int k = 0; k < m; ++k) {
      const std::uint32_t j = full_partner_[base + static_cast<std::uint32_t>(k)];
      const Kin& kj = kin_[j];
      if (any_fixed_ && fixed_[j]) { // on i's parabola, below
        lanes.clear(k);
        fixed_partners = true;
        continue;
      }
      const double aj = now - kj.t;
      lanes.rx[k] = min_image(xi.x - (kj.x + (kj.vx + 0.5 * g_.x * aj) * aj), 0);
      lanes.ry[k] = min_image(xi.y - (kj.y + (kj.vy + 0.5 * g_.y * aj) * aj), 1);
      lanes.rz[k] = min_image(xi.z - (kj.z + (kj.vz + 0.5 * g_.z * aj) * aj), 2);
      lanes.vx[k] = vi.x - (kj.vx + g_.x * aj);
      lanes.vy[k] = vi.y - (kj.vy + g_.y * aj);
      lanes.vz[k] = vi.z - (kj.vz + g_.z * aj);
      lanes.sigma[k] = ki.r + kj.r;
    }
    lanes.clear_from(m);
    // The horizon is the step's end, not the earliest event so far as in time_to_contact's
    // calls: a pair it lets through beyond that event is later than it (the 1e-9 margin
    // exceeds the round-off of now + dt), so the choice below is the same.
    pair_times(lanes, t_end_ - now);
    for (int k = 0; k < m; ++k) {
      double dt = lanes.dt[k];
      if (lanes.touching[k] != 0.0) dt = lanes.time_to_contact(k, best - now); // (round-off)
      const double t = now + dt;
      const bool earlier_pair = t < best;
      best = earlier_pair ? t : best;
      partner = earlier_pair ? full_partner_[base + static_cast<std::uint32_t>(k)] : partner;
    }
    for (int k = 0; k < m && fixed_partners; ++k) {
      const std::uint32_t j = full_partner_[base + static_cast<std::uint32_t>(k)];
      if (!fixed_[j]) continue;
      const double t = fixed_pair_time(ki, xi, vi, kin_[j], now);
      if (t < best) best = t, partner = j;
    }
  }
  wall_event(ki, xi, vi, now, best, partner);
  if (partner == kNone) return {best, i, partner, 0u, 0u};
  return {best, i, partner, counter_[i], partner < n ? counter_[partner] : 0u};
}

void HardSphereEngine::wall_event(const Kin& ki, const Vec3& xi, const Vec3& vi, double now,
                                  double& best, std::uint32_t& partner) const {
  // Walls [Hoomans96 eq. 31], on the parabola: the gap d(t) = d0 + u t + g_n t^2 / 2 along the
  // wall's inward normal (u, g_n: velocity and gravity towards the wall).
  const auto n = static_cast<std::uint32_t>(kin_.size());
  const auto& box = box_;
  for (int f = 0; f < 6; ++f) {
    if (!box.wall[f]) continue;
    const int a = f / 2;
    const double sign = (f % 2 == 0) ? -1.0 : 1.0; // towards the wall
    const double u = sign * vi[a], gn = sign * g_[a];
    const double gap = (f % 2 == 0) ? xi[a] - box.lo[a] - ki.r : box.hi[a] - ki.r - xi[a];
    // Out of reach before the best event so far (the distance covered in a time T is at most
    // max(u, 0) T + max(g_n, 0) T^2 / 2; margin for the round-off of the root as above).
    const double horizon = best - now;
    if (gap > (std::max(u, 0.0) + 0.5 * std::max(gn, 0.0) * horizon) * horizon * (1.0 + 1e-9))
      continue;
    const double dt = wall_time(gap, u, gn);
    if (now + dt < best) best = now + dt, partner = n + static_cast<std::uint32_t>(f);
  }
}

void HardSphereEngine::schedule(const ParticleStore& p, std::uint32_t i, double now) {
  set_event(predict(p, i, now));
}

double HardSphereEngine::wall_time(double gap, double u, double gn) const {
  constexpr double never = std::numeric_limits<double>::infinity();
  if (gap <= 0.0) { // touching (round-off)
    if (u > 0.0) return 0.0;
    if (gn <= 0.0) return never;
    // Moving off (or at rest) and pulled back: it returns to the wall after 2 |u| / g_n. A
    // particle at rest on the wall is given a minimal flight, so that it reaches the wall
    // approaching (penetration g_n t^2 / 2, far below round-off of the position).
    return std::max(-2.0 * u / gn, min_flight());
  }
  // First root of gap - u t - g_n t^2 / 2 = 0 (distance s(t) = u t + g_n t^2/2 covered).
  if (gn == 0.0) return u > 0.0 ? gap / u : never;
  const double disc = u * u + 2.0 * gn * gap;
  if (disc < 0.0) return never; // decelerates and turns before reaching it
  // Stable form of (-u + sqrt(disc)) / g_n.
  const double root = u + std::sqrt(disc);
  if (root <= 0.0) return never; // moving away and pushed away
  return 2.0 * gap / root;
}

double HardSphereEngine::min_flight() const {
  return std::max(1e-3 * opts_.tc_time, 1e-9 * step_dt_);
}

double HardSphereEngine::fixed_pair_time(const Kin& ka, const Vec3& xa, const Vec3& va,
                                         const Kin& kb, double now) const {
  const Vec3 r{min_image(xa.x - kb.x, 0), min_image(xa.y - kb.y, 1), min_image(xa.z - kb.z, 2)};
  const double dt =
      hardsphere::time_to_fixed_contact(r, va, g_, ka.r + kb.r, t_end_ - now, min_flight());
  return dt < std::numeric_limits<double>::infinity() ? now + dt : dt;
}

void HardSphereEngine::process(ParticleStore& p, const Event& ev) {
  const auto n = static_cast<std::uint32_t>(p.size());
  const std::uint32_t a = ev.a, b = ev.b;
  const bool wall = b >= n;
  auto move_to = [&](std::uint32_t i) {
    if (!(any_fixed_ && fixed_[i])) advance_particle(kin_[i], ev.t - kin_[i].t);
    kin_[i].t = ev.t;
  };
  // A fixed partner (1/m = 0, 1/I = 0) is a body of infinite mass for the collision operator,
  // like a wall: it keeps no collision time or counter (TC model, stale events) and no event.
  const bool fixed_b = !wall && any_fixed_ && fixed_[b];
  auto body = [&](std::uint32_t i) {
    return hardsphere::Body{Vec3{kin_[i].vx, kin_[i].vy, kin_[i].vz}, p.angular_velocity(i),
                            p.radius[i], p.inv_mass[i], p.inv_inertia[i]};
  };
  auto kinetic = [&](const hardsphere::Body& x, std::uint32_t i) {
    return x.inv_m > 0.0 ? 0.5 * p.mass[i] * norm2(x.v) + 0.5 / x.inv_i * norm2(x.w) : 0.0;
  };
  move_to(a);
  hardsphere::Body ba = body(a), bb;
  Vec3 normal;
  hardsphere::CollisionLaw law;
  bool recent = ev.t - last_collision_[a] < opts_.tc_time;
  if (!wall) {
    move_to(b);
    bb = body(b);
    const Vec3 r{min_image(kin_[a].x - kin_[b].x, 0), min_image(kin_[a].y - kin_[b].y, 1),
                 min_image(kin_[a].z - kin_[b].z, 2)};
    normal = r / norm(r);
    law = pair_law_[p.species[a] * nspecies_ + p.species[b]];
    if (!fixed_b) recent = recent || ev.t - last_collision_[b] < opts_.tc_time;
  } else {
    const int f = static_cast<int>(b - n);
    normal[f / 2] = (f % 2 == 0) ? 1.0 : -1.0; // from the wall into the particle
    law = wall_law_[p.species[a] * 6 + f];
  }
  const double e_before = kinetic(ba, a) + (wall ? 0.0 : kinetic(bb, b));
  // TC model [Luding & McNamara 1998]: a collision within tc_time of a partner's previous one
  // dissipates nothing (e_n = 1 and smooth, so friction cannot drain the energy either), and
  // neither does one slower than elastic_below along the normal (McNamara & Falcon 2005);
  // the energy the real law would have taken is booked in tc_energy_kept.
  const bool dissipative = law.e_n < 1.0 || law.mu > 0.0;
  const bool slow = std::abs(dot(ba.v - bb.v, normal)) < elastic_below_;
  const bool tc = dissipative && (recent || slow);
  const hardsphere::CollisionLaw used = tc ? hardsphere::CollisionLaw{1.0, 0.0, 0.0} : law;
  hardsphere::Body ra = ba, rb = bb; // for the energy the real law would have dissipated
  const auto res = hardsphere::collide(ba, bb, normal, used);
  if (!res.approaching) {
    // Grazing after round-off: nothing to do. Count it toward the stall guard, so that a
    // disagreement between scheduler and operator can never loop forever, and look again.
    ++stats_.events_last_step;
    schedule(p, a, ev.t);
    return;
  }
  auto store = [&](std::uint32_t i, const hardsphere::Body& x) {
    kin_[i].vx = x.v.x, kin_[i].vy = x.v.y, kin_[i].vz = x.v.z;
    p.wx[i] = x.w.x, p.wy[i] = x.w.y, p.wz[i] = x.w.z;
  };
  store(a, ba);
  if (!wall && !fixed_b) store(b, bb);
  const double e_after = kinetic(ba, a) + (wall ? 0.0 : kinetic(bb, b));
  stats_.dissipated += e_before - e_after;
  if (tc) {
    ++(recent ? stats_.tc_elastic : stats_.slow_elastic);
    hardsphere::collide(ra, rb, normal, law);
    stats_.tc_energy_kept += e_before - kinetic(ra, a) - (wall ? 0.0 : kinetic(rb, b));
  }
  ++stats_.collisions;
  ++stats_.events_last_step;
  ++counter_[a];
  last_collision_[a] = ev.t;
  if (wall) {
    ++stats_.wall_collisions;
    ++stats_.wall_collisions_last_step;
  } else {
    ++stats_.pair_collisions_last_step;
    if (!fixed_b) {
      ++counter_[b];
      last_collision_[b] = ev.t;
    }
  }
  if (record_) {
    // normal: from b (or the wall) towards a; the contact point is r_a behind a's centre.
    log_.push_back({p.id[a], wall ? -1 - static_cast<std::int64_t>(b - n) : p.id[b],
                    Vec3{kin_[a].x, kin_[a].y, kin_[a].z} - normal * p.radius[a]});
  }
  schedule(p, a, ev.t);
  if (!wall && !fixed_b) schedule(p, b, ev.t);
}

void HardSphereEngine::finish_step(ParticleStore& p) {
  // Everybody to the end of the step, periodic axes wrapped (the list's build positions are
  // not: displacements are taken minimum-image), into the particle store; then the overlap
  // check over every pair of the list once (j > i), which reports the first overlapping
  // particle (lowest index) whatever the number of threads. One parallel region for both.
  const std::size_t n = p.size();
  const double time = t_end_;
  auto overlaps = [&](std::size_t i, std::uint32_t j) { // kin_: the positions at the end
    const double dx = min_image(kin_[j].x - kin_[i].x, 0);
    const double dy = min_image(kin_[j].y - kin_[i].y, 1);
    const double dz = min_image(kin_[j].z - kin_[i].z, 2);
    const double sigma = kin_[i].r + kin_[j].r;
    return dx * dx + dy * dy + dz * dz < sigma * sigma * (1.0 - 1e-6);
  };
  const auto& box = box_;
  std::size_t first = n;
#pragma omp parallel if (n >= kParallelMin)
  {
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      Kin& k = kin_[i];
      if (!(any_fixed_ && fixed_[i])) advance_particle(k, t_end_ - k.t);
      double* q[3] = {&k.x, &k.y, &k.z};
      for (int ax = 0; ax < 3; ++ax)
        if (box.periodic[ax]) *q[ax] = wrapped(*q[ax], box.lo[ax], box.length(ax));
      p.x[i] = k.x, p.y[i] = k.y, p.z[i] = k.z;
      p.vx[i] = k.vx, p.vy[i] = k.vy, p.vz[i] = k.vz;
    }
#pragma omp for schedule(static) reduction(min : first)
    for (std::size_t i = 0; i < n; ++i) {
      bool any = false;
      for (std::uint32_t e = split_[i]; e < full_offset_[i + 1]; ++e)
        any |= overlaps(i, full_partner_[e]);
      if (any) first = std::min(first, i);
    }
  }
  if (first == n) return;
  std::uint32_t partner = 0;
  for (std::uint32_t e = split_[first]; e < full_offset_[first + 1]; ++e)
    if (overlaps(first, full_partner_[e])) {
      partner = full_partner_[e];
      break;
    }
  throw InstabilityError(
      fmt::format("hard-sphere run failed at t = {:.6g} s: particles {} and {} overlap (a "
                  "collision was missed); reduce simulation.time_step",
                  time, p.id[first], p.id[partner]));
}

void HardSphereEngine::advance_particle(Kin& k, double a) const {
  k.x += (k.vx + 0.5 * g_.x * a) * a;
  k.y += (k.vy + 0.5 * g_.y * a) * a;
  k.z += (k.vz + 0.5 * g_.z * a) * a;
  k.vx += g_.x * a, k.vy += g_.y * a, k.vz += g_.z * a;
}

void HardSphereEngine::update_neighbour_list(const ParticleStore& p, double time, double dt) {
  // The list must hold every pair that can meet before the end of the step: a particle moves
  // at most s = 1.5 (v_max + |g| DT) DT in one step [Deen07 eq. 44] (the 1.5 allows for
  // collisions speeding it up), so the list built with skin `skin` stays valid while the
  // largest displacement since the build plus s is below skin / 2. It is rebuilt, with a skin
  // of 8 s (valid for about four steps) or 2 s (one step) as hardsphere/skin_policy.hpp
  // chooses, only when that fails. The same pass copies the
  // kinematics of the hot loops into kin_ (one cache line per particle, clocks at `time`).
  const std::size_t n = p.size();
  kin_.resize(n);
  fixed_.resize(n);
  double vmax2 = 0.0, rmin = std::numeric_limits<double>::infinity(), moved2 = 0.0;
  std::size_t fixed = 0;
  const bool have = built_x_.size() == n;
#pragma omp parallel for schedule(static) reduction(max                                            \
                                                    : vmax2, moved2)                               \
    reduction(min                                                                                  \
              : rmin) reduction(+ : fixed) if (n >= kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    kin_[i] = {p.x[i], p.y[i], p.z[i], time, p.vx[i], p.vy[i], p.vz[i], p.radius[i]};
    fixed_[i] = p.fixed(i) ? 1 : 0;
    fixed += fixed_[i];
    vmax2 = std::max(vmax2, p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    rmin = std::min(rmin, p.radius[i]);
    if (have) {
      const double dx = min_image(p.x[i] - built_x_[i], 0);
      const double dy = min_image(p.y[i] - built_y_[i], 1);
      const double dz = min_image(p.z[i] - built_z_[i], 2);
      moved2 = std::max(moved2, dx * dx + dy * dy + dz * dz);
    }
  }
  rmin_ = rmin;
  any_fixed_ = fixed > 0;
  moving_ = n - fixed;
  const double vmax = std::sqrt(vmax2);
  const double step = 1.5 * (vmax + norm(g_) * dt) * dt;
  if (have && std::sqrt(moved2) + step <= 0.5 * skin_) {
    ++list_steps_;
    return;
  }
  if (probe_.build == list_builds_ - 1 && probe_.life == 0) probe_.life = list_steps_;
  // The skin: long (several steps) or short (one step), from the last probe's list sizes and
  // the last step's events (hardsphere/skin_policy.hpp).
  const double events =
      moving_ > 0 ? static_cast<double>(stats_.events_last_step) / static_cast<double>(moving_)
                  : 0.0;
  const double steps = fixed_skin_steps_ > 0.0
                           ? fixed_skin_steps_
                           : hardsphere::skin_steps(probe_, list_builds_, events);
  const double min_skin = 1e-3 * rmin;
  skin_ = std::max(steps * step, min_skin);
  const bool probe = steps == hardsphere::kLongSkinSteps;
  const std::size_t within_short =
      build_list(p, probe ? std::max(hardsphere::kShortSkinSteps * step, min_skin) : 0.0);
  if (probe && n > 0)
    probe_ = {list_builds_, static_cast<double>(full_partner_.size()) / static_cast<double>(n),
              static_cast<double>(within_short) / static_cast<double>(n), 0};
  built_x_ = p.x, built_y_ = p.y, built_z_ = p.z;
  ++list_builds_;
  list_steps_ = 1;
}

void HardSphereEngine::advance(ParticleStore& p, double time, double dt,
                               const std::array<double, 3>& accel) {
  const std::size_t n = p.size();
  g_ = Vec3{accel[0], accel[1], accel[2]};
  step_dt_ = dt;
  update_neighbour_list(p, time, dt);
  // Default: the impact speed after a fall through a thousandth of the smallest diameter,
  // sqrt(2 |g| 1e-3 d_min): a bed whose gaps are below that is at rest for every purpose.
  elastic_below_ =
      opts_.elastic_below ? *opts_.elastic_below : std::sqrt(2.0 * norm(g_) * 1e-3 * 2.0 * rmin_);

  counter_.resize(n, 0);
  last_collision_.resize(n, -std::numeric_limits<double>::infinity());
  t_end_ = time + dt;
  stats_.events_last_step = 0;
  stats_.pair_collisions_last_step = 0;
  stats_.wall_collisions_last_step = 0;
  log_.clear();
  // Every particle's first event, in parallel (predict only reads); queued in index order, so
  // the queue is the same for any number of threads.
  next_.resize(n);
  first_events(time);
  queue_.clear();
  slot_.assign(n, kNone);
  for (std::uint32_t i = 0; i < n; ++i)
    if (next_[i].b != kNone)
      slot_[i] = static_cast<std::uint32_t>(queue_.size()), queue_.push_back({next_[i].t, i});
  // Bottom-up heap construction: every node with children, the last one first.
  if (queue_.size() > 1)
    for (auto k = static_cast<std::uint32_t>((queue_.size() - 2) / kArity + 1); k-- > 0;)
      sift_down(k);
  // Per moving particle: fixed ones have no events of their own.
  const auto limit =
      static_cast<long>(opts_.max_events_per_particle * static_cast<double>(moving_));
  while (!queue_.empty()) {
    const Event ev = next_[queue_[0].i];
    if (ev.t > t_end_) break;
    if (ev.b < n && counter_[ev.b] != ev.cb) { // the partner changed course: look again
      schedule(p, ev.a, ev.t);
      continue;
    }
    process(p, ev);
    if (stats_.events_last_step > limit) {
      throw InstabilityError(fmt::format(
          "hard-sphere run stalled at t = {:.9g} s: more than {} collisions per particle in one "
          "flow step (inelastic collapse); raise hardsphere.tc_time or hardsphere.elastic_below",
          ev.t, opts_.max_events_per_particle));
    }
  }
  finish_step(p);
}

std::size_t HardSphereEngine::bytes() const {
  auto b = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  std::size_t rows = 0;
  for (const auto& r : thread_rows_) rows += b(r);
  return grid_.bytes() + b(full_offset_) + b(full_partner_) + b(split_) + b(mirror_) +
         b(mirror_cursor_) + b(pair_time_) + rows + b(kin_) + b(last_collision_) + b(counter_) +
         b(next_) + b(queue_) + b(slot_) + b(built_x_) + b(built_y_) + b(built_z_);
}

} // namespace fluidem

namespace fluidem {

// The list in a checkpoint: its skin and build positions (built_x_, ...) and its pairs, from
// which restore() rebuilds the same list and checks it against them. (Checkpoints written
// before the engine had its own list hold the half list of NeighbourList, each pair once: the
// check compares the sets of pairs, so both load.)
HardSphereEngine::State HardSphereEngine::state() const {
  State s;
  s.last_collision = last_collision_;
  s.built_x = built_x_;
  s.built_y = built_y_;
  s.built_z = built_z_;
  s.counter = counter_;
  s.list_builds = list_builds_;
  s.stats = stats_;
  s.list.skin = skin_;
  s.list.builds = list_builds_;
  s.skin_probe = probe_;
  s.list_steps = list_steps_;
  s.list.x0 = built_x_;
  s.list.y0 = built_y_;
  s.list.z0 = built_z_;
  s.list.offset = full_offset_;
  s.list.partner = full_partner_;
  return s;
}

namespace {
/// The pairs (i < j) of a CSR list, sorted.
std::vector<std::uint64_t> pair_set(const std::vector<std::uint32_t>& offset,
                                    const std::vector<std::uint32_t>& partner) {
  std::vector<std::uint64_t> out;
  for (std::size_t i = 0; i + 1 < offset.size(); ++i)
    for (std::uint32_t e = offset[i]; e < offset[i + 1] && e < partner.size(); ++e) {
      const std::uint64_t a = std::min<std::uint64_t>(i, partner[e]);
      const std::uint64_t b = std::max<std::uint64_t>(i, partner[e]);
      out.push_back(a << 32 | b);
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}
} // namespace

void HardSphereEngine::restore(const ParticleStore& p, const State& s) {
  skin_ = s.list.skin;
  full_offset_.clear();
  full_partner_.clear();
  if (!s.list.x0.empty()) {
    if (s.list.x0.size() != p.size() || s.list.y0.size() != p.size() ||
        s.list.z0.size() != p.size())
      throw std::runtime_error("hard-sphere list: the restored build positions are for " +
                               std::to_string(s.list.x0.size()) + " particles, not " +
                               std::to_string(p.size()));
    ParticleStore at_build = p;
    at_build.x = s.list.x0;
    at_build.y = s.list.y0;
    at_build.z = s.list.z0;
    build_list(at_build);
    if (pair_set(full_offset_, full_partner_) != pair_set(s.list.offset, s.list.partner))
      throw std::runtime_error("hard-sphere list: the list rebuilt from the checkpoint's build "
                               "positions differs from the saved one");
  }
  last_collision_ = s.last_collision;
  built_x_ = s.built_x;
  built_y_ = s.built_y;
  built_z_ = s.built_z;
  counter_ = s.counter;
  list_builds_ = s.list_builds;
  stats_ = s.stats;
  probe_ = s.skin_probe;
  list_steps_ = s.list_steps;
}

} // namespace fluidem
