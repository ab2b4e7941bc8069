#include "analysis/collision_statistics.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "core/nearest_integer.hpp"

namespace fluidem {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = std::numbers::pi;
} // namespace

CollisionStatistics::CollisionStatistics(Settings settings, double time)
    : s_(std::move(settings)), t0_(time), region_(s_.regions.size()),
      hist_(static_cast<std::size_t>(std::max(1, s_.histogram_bins)) + 1, 0) {}

bool CollisionStatistics::inside(const CollisionRegion& r, const Vec3& x) const {
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (s_.dimension == 2 && a == 1) continue; // circles in the x-z plane
    double d = x[a] - r.centre[a];
    if (s_.periodic[a]) d -= s_.box_length[a] * nearest_integer(d / s_.box_length[a]);
    d2 += d * d;
  }
  return d2 < r.radius * r.radius;
}

void CollisionStatistics::begin(std::int64_t b, const Vec3& point) {
  if (b < 0) {
    ++interval_.walls_begun, ++total_.walls_begun;
    return;
  }
  ++interval_.pairs_begun, ++total_.pairs_begun;
  for (std::size_t k = 0; k < s_.regions.size(); ++k)
    if (inside(s_.regions[k], point)) ++region_[k].collisions;
}

void CollisionStatistics::end(const Ongoing& c, double time) {
  if (c.b < 0) {
    ++interval_.walls_ended, ++total_.walls_ended;
    return;
  }
  const double extent = c.max_overlap / c.diameter;
  const double duration = time - c.begin;
  for (Acc* acc : {&interval_, &total_}) {
    ++acc->pairs_ended;
    if (c.multiple) ++acc->pairs_multiple;
    acc->sum_extent += extent;
    acc->max_extent = std::max(acc->max_extent, extent);
    acc->sum_duration += duration;
  }
  for (std::size_t k = 0; k < s_.regions.size(); ++k)
    if (inside(s_.regions[k], c.point)) {
      ++region_[k].ended;
      if (c.multiple) ++region_[k].multiple;
    }
  const double w = s_.histogram_max / static_cast<double>(hist_.size() - 1);
  const double k = std::floor(extent / w);
  const std::size_t bin =
      k < static_cast<double>(hist_.size() - 1) ? static_cast<std::size_t>(k) : hist_.size() - 1;
  ++hist_[bin];
}

void CollisionStatistics::sample_regions(const ParticleStore& p) {
  if (s_.regions.empty()) return;
  const bool disc = s_.dimension == 2;
  for (std::size_t k = 0; k < s_.regions.size(); ++k) {
    RegionAcc& r = region_[k];
    ++r.samples;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!inside(s_.regions[k], p.position(i))) continue;
      const double ri = p.radius[i];
      r.sum_count += 1.0;
      r.sum_volume += disc ? kPi * ri * ri : 4.0 / 3.0 * kPi * ri * ri * ri;
    }
  }
}

void CollisionStatistics::add_step(const ContactRecord& record, const ParticleStore& p,
                                   double time) {
  const std::size_t n = record.samples.size();
  entries_.resize(n);
  ab_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const ContactSample& c = record.samples[k];
    const auto i = static_cast<std::size_t>(c.i);
    if (c.j >= 0) {
      const auto j = static_cast<std::size_t>(c.j);
      ab_[k] = {std::min(c.id_i, c.id_j), std::max(c.id_i, c.id_j)};
      entries_[k] = {0, static_cast<std::uint32_t>(k), c.overlap,
                     2.0 * std::min(p.radius[i], p.radius[j])};
    } else {
      ab_[k] = {c.id_i, c.id_j};
      entries_[k] = {0, static_cast<std::uint32_t>(k), c.overlap, 2.0 * p.radius[i]};
    }
  }
  merge(time, [&](std::size_t k) { return record.samples[k].contact_point; });
  sample_regions(p);
}

void CollisionStatistics::add_keyed_step(const std::vector<KeyedContact>& contacts,
                                         const ParticleStore& in_regions, double time) {
  const std::size_t n = contacts.size();
  entries_.resize(n);
  ab_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const KeyedContact& c = contacts[k];
    ab_[k] = {c.a, c.b};
    entries_[k] = {0, static_cast<std::uint32_t>(k), c.overlap, c.diameter};
  }
  merge(time, [&](std::size_t k) { return contacts[k].contact_point; });
  sample_regions(in_regions);
}

bool CollisionStatistics::in_a_region(const Vec3& x) const {
  for (const CollisionRegion& r : s_.regions)
    if (inside(r, x)) return true;
  return false;
}

void CollisionStatistics::merge(double time, const std::function<Vec3(std::size_t)>& point) {
  // The step's contacts (entries_, their keys ab_, in the record's order: slab order, or the
  // ranks' order) sorted by key; equal keys (the same pair twice in one record: never from one
  // contact loop) keep their order in the record, so that the result does not depend on the
  // sort. The keys, less their minima, are packed into one integer and sorted by an LSD radix
  // sort (stable), or compared whole when they span more than 64 bits.
  const std::size_t n = entries_.size();
  std::array<std::int64_t, 2> lo{0, 0}, hi{0, 0};
  if (n > 0) lo = hi = ab_[0];
  for (const auto& ab : ab_)
    for (int m = 0; m < 2; ++m) lo[m] = std::min(lo[m], ab[m]), hi[m] = std::max(hi[m], ab[m]);
  // (a - a_min, b - b_min) packed into one integer whose order is the pairs' (a first).
  const auto span = [&](int m) {
    return static_cast<std::uint64_t>(hi[m]) - static_cast<std::uint64_t>(lo[m]);
  };
  const int bits_a = static_cast<int>(std::bit_width(span(0))),
            bits_b = static_cast<int>(std::bit_width(span(1)));
  const bool packed = bits_a + bits_b <= 64 && bits_b < 64; // (a shift by 64 is undefined)
  const std::uint64_t mask_b = bits_b == 0 ? 0 : ~std::uint64_t{0} >> (64 - bits_b);
  const auto offset = [&](std::int64_t v, int m) {
    return static_cast<std::uint64_t>(v) - static_cast<std::uint64_t>(lo[m]);
  };
  if (packed)
    for (Entry& e : entries_) e.key = offset(ab_[e.k][0], 0) << bits_b | offset(ab_[e.k][1], 1);
  const int bits = bits_a + bits_b;
  if (packed && n >= 4096) { // (below, the buckets would cost more than the keys)
    // As few passes of at most 16 bits as the keys' bits need (2^17 ids: 34 bits, 3 passes).
    const int passes = (bits + 15) / 16;
    const int digit = passes > 0 ? (bits + passes - 1) / passes : 0;
    const std::size_t buckets = std::size_t{1} << digit;
    entries_tmp_.resize(n);
    std::vector<std::uint32_t>& count = radix_count_;
    count.resize(buckets);
    for (int shift = 0; shift < bits; shift += digit) {
      std::fill(count.begin(), count.end(), 0u);
      for (const Entry& e : entries_) ++count[(e.key >> shift) & (buckets - 1)];
      if (count[(entries_[0].key >> shift) & (buckets - 1)] == n) continue; // one digit
      std::uint32_t at = 0;
      for (std::uint32_t& c : count) at += std::exchange(c, at);
      for (const Entry& e : entries_) entries_tmp_[count[(e.key >> shift) & (buckets - 1)]++] = e;
      std::swap(entries_, entries_tmp_);
    }
  } else if (packed) {
    std::sort(entries_.begin(), entries_.end(), [](const Entry& x, const Entry& y) {
      return x.key != y.key ? x.key < y.key : x.k < y.k;
    });
  } else {
    std::sort(entries_.begin(), entries_.end(), [&](const Entry& x, const Entry& y) {
      return ab_[x.k] != ab_[y.k] ? ab_[x.k] < ab_[y.k] : x.k < y.k;
    });
  }
  auto key_less = [](const Ongoing& x, const Ongoing& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  };
  const auto key_of = [&](const Entry& e) -> std::array<std::int64_t, 2> {
    if (!packed) return ab_[e.k];
    return {static_cast<std::int64_t>((e.key >> bits_b) + static_cast<std::uint64_t>(lo[0])),
            static_cast<std::int64_t>((e.key & mask_b) + static_cast<std::uint64_t>(lo[1]))};
  };
  // Contacts per particle this step (a duplicate key counted once, capped at 2): a pair whose
  // particle has more than one is multiple from this step on. Ids within a span of a few times
  // the contacts are counted in a dense array (degree_, all zeros between steps), else in a
  // sorted list of the step's ids.
  std::int64_t id_lo = std::numeric_limits<std::int64_t>::max(), id_hi = -1;
  for (const auto& [a, b] : ab_)
    for (const std::int64_t id : {a, b})
      if (id >= 0) id_lo = std::min(id_lo, id), id_hi = std::max(id_hi, id);
  const bool dense = id_hi >= 0 && static_cast<std::uint64_t>(id_hi - id_lo) <
                                       std::max<std::uint64_t>(8 * n, 1u << 20);
  ids_.clear();
  if (dense && degree_.size() < static_cast<std::size_t>(id_hi - id_lo) + 1)
    degree_.resize(static_cast<std::size_t>(id_hi - id_lo) + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0 && key_of(entries_[k]) == key_of(entries_[k - 1])) continue;
    const auto [a, b] = key_of(entries_[k]);
    for (const std::int64_t id : {a, b}) {
      if (id < 0) continue;
      if (!dense) {
        ids_.push_back(id);
        continue;
      }
      std::uint8_t& d = degree_[static_cast<std::size_t>(id - id_lo)];
      d = static_cast<std::uint8_t>(std::min(d + 1, 2));
    }
  }
  if (!dense) std::sort(ids_.begin(), ids_.end());
  const auto touches_another = [&](std::int64_t id) {
    if (id < 0) return false;
    if (dense) return degree_[static_cast<std::size_t>(id - id_lo)] > 1;
    const auto [first, last] = std::equal_range(ids_.begin(), ids_.end(), id);
    return last - first > 1;
  };
  // Merge with the ongoing contacts (sorted): new keys begin, missing keys end.
  merged_.clear();
  merged_.reserve(n);
  std::size_t io = 0;
  for (const Entry& e : entries_) {
    const auto [a, b] = key_of(e);
    Ongoing c{a,
              b,
              time,
              e.overlap,
              e.diameter,
              Vec3{},
              b >= 0 && (touches_another(a) || touches_another(b))};
    if (!merged_.empty() && merged_.back().a == c.a && merged_.back().b == c.b) {
      merged_.back().max_overlap = std::max(merged_.back().max_overlap, c.max_overlap);
      continue; // a duplicate key (same pair twice in one record): one contact
    }
    while (io < ongoing_.size() && key_less(ongoing_[io], c)) end(ongoing_[io++], time);
    if (io < ongoing_.size() && !key_less(c, ongoing_[io])) { // continues
      Ongoing o = ongoing_[io++];
      o.max_overlap = std::max(o.max_overlap, c.max_overlap);
      o.multiple = o.multiple || c.multiple;
      merged_.push_back(o);
    } else { // begins (the contact point only counts in a region)
      if (!s_.regions.empty()) c.point = point(e.k);
      begin(c.b, c.point);
      merged_.push_back(c);
    }
  }
  while (io < ongoing_.size()) end(ongoing_[io++], time);
  std::swap(ongoing_, merged_);
  if (dense)
    for (const auto& [a, b] : ab_)
      for (const std::int64_t id : {a, b})
        if (id >= 0) degree_[static_cast<std::size_t>(id - id_lo)] = 0;
}

void CollisionStatistics::add_instant_step(const std::vector<InstantCollision>& collisions,
                                           const ParticleStore& p, double /*time*/) {
  for (const InstantCollision& c : collisions) begin(c.id_b < 0 ? -1 : c.id_b, c.point);
  // Instantaneous: every collision has ended as it began (no overlap, no duration).
  for (const InstantCollision& c : collisions) {
    Acc* accs[2] = {&interval_, &total_};
    for (Acc* acc : accs) ++(c.id_b < 0 ? acc->walls_ended : acc->pairs_ended);
  }
  sample_regions(p);
}

CollisionStatistics::Row CollisionStatistics::take_row(double time, std::size_t n_particles) {
  Row r;
  r.time = time;
  r.length = time - t0_;
  r.pair_collisions = interval_.pairs_begun;
  r.wall_collisions = interval_.walls_begun;
  r.pair_collisions_ended = interval_.pairs_ended;
  r.multiple_collisions = interval_.pairs_multiple;
  const double c2 = 2.0 * static_cast<double>(interval_.pairs_begun);
  r.frequency =
      r.length > 0.0 && n_particles > 0 ? c2 / (static_cast<double>(n_particles) * r.length) : kNaN;
  r.mean_free_time = 1.0 / r.frequency;
  // Overlap and duration: soft-sphere contacts only (the hard-sphere ones add no sums).
  const bool has = interval_.pairs_ended > 0 && interval_.sum_duration > 0.0;
  const double ne = static_cast<double>(interval_.pairs_ended);
  r.mean_overlap = has ? interval_.sum_extent / ne : kNaN;
  r.max_overlap = has ? interval_.max_extent : kNaN;
  r.mean_duration = has ? interval_.sum_duration / ne : kNaN;
  const bool disc = s_.dimension == 2;
  for (std::size_t k = 0; k < s_.regions.size(); ++k) {
    RegionAcc& a = region_[k];
    const double rad = s_.regions[k].radius;
    const double vol = disc ? kPi * rad * rad : 4.0 / 3.0 * kPi * rad * rad * rad;
    RegionRow rr;
    rr.collisions = a.collisions;
    rr.ended = a.ended;
    rr.multiple = a.multiple;
    const double samples = static_cast<double>(a.samples);
    rr.particles = a.samples > 0 ? a.sum_count / samples : kNaN;
    rr.void_fraction = a.samples > 0 ? 1.0 - a.sum_volume / samples / vol : kNaN;
    rr.frequency = r.length > 0.0 && rr.particles > 0.0
                       ? 2.0 * static_cast<double>(a.collisions) / (rr.particles * r.length)
                       : kNaN;
    r.regions.push_back(rr);
    a = RegionAcc{};
  }
  interval_ = Acc{};
  t0_ = time;
  return r;
}

double CollisionStatistics::mean_overlap() const {
  return total_.pairs_ended > 0 && total_.sum_duration > 0.0
             ? total_.sum_extent / static_cast<double>(total_.pairs_ended)
             : kNaN;
}
double CollisionStatistics::max_overlap() const {
  return total_.pairs_ended > 0 && total_.sum_duration > 0.0 ? total_.max_extent : kNaN;
}
double CollisionStatistics::mean_duration() const {
  return total_.pairs_ended > 0 && total_.sum_duration > 0.0
             ? total_.sum_duration / static_cast<double>(total_.pairs_ended)
             : kNaN;
}

CollisionStatistics::State CollisionStatistics::state() const {
  State s;
  for (const Ongoing& o : ongoing_) {
    s.keys.insert(s.keys.end(), {o.a, o.b, o.multiple ? 1 : 0});
    s.ongoing.insert(s.ongoing.end(),
                     {o.begin, o.max_overlap, o.diameter, o.point[0], o.point[1], o.point[2]});
  }
  for (const Acc* a : {&interval_, &total_}) {
    s.counters.insert(s.counters.end(), {a->pairs_begun, a->walls_begun, a->pairs_ended,
                                         a->walls_ended, a->pairs_multiple});
    s.sums.insert(s.sums.end(), {a->sum_extent, a->max_extent, a->sum_duration});
  }
  s.sums.push_back(t0_);
  for (const RegionAcc& r : region_) {
    s.counters.insert(s.counters.end(), {r.collisions, r.samples, r.ended, r.multiple});
    s.sums.insert(s.sums.end(), {r.sum_count, r.sum_volume});
  }
  s.histogram = hist_;
  return s;
}

void CollisionStatistics::restore(const State& s) {
  const std::size_t nr = region_.size();
  if (s.keys.size() % 3 != 0 || s.ongoing.size() != s.keys.size() / 3 * 6 ||
      s.counters.size() != 10 + 4 * nr || s.sums.size() != 7 + 2 * nr ||
      s.histogram.size() != hist_.size())
    throw std::runtime_error("collision statistics in the checkpoint do not match the case "
                             "(regions or histogram bins differ, or the checkpoint was written "
                             "by a fluidem before 2026-12-07)");
  ongoing_.clear();
  for (std::size_t k = 0; k < s.keys.size() / 3; ++k) {
    const double* o = &s.ongoing[6 * k];
    ongoing_.push_back({s.keys[3 * k], s.keys[3 * k + 1], o[0], o[1], o[2], Vec3{o[3], o[4], o[5]},
                        s.keys[3 * k + 2] != 0});
  }
  std::size_t c = 0, d = 0;
  for (Acc* a : {&interval_, &total_}) {
    a->pairs_begun = s.counters[c++];
    a->walls_begun = s.counters[c++];
    a->pairs_ended = s.counters[c++];
    a->walls_ended = s.counters[c++];
    a->pairs_multiple = s.counters[c++];
    a->sum_extent = s.sums[d++];
    a->max_extent = s.sums[d++];
    a->sum_duration = s.sums[d++];
  }
  t0_ = s.sums[d++];
  for (RegionAcc& r : region_) {
    r.collisions = s.counters[c++];
    r.samples = s.counters[c++];
    r.ended = s.counters[c++];
    r.multiple = s.counters[c++];
    r.sum_count = s.sums[d++];
    r.sum_volume = s.sums[d++];
  }
  hist_ = s.histogram;
}

} // namespace fluidem
