// CollisionStatistics on hand-made contact records, against values worked out by hand:
// collision births and ends across steps, durations (steps seen x dt), overlap extents
// (max overlap / smaller diameter) and their histogram bin, the frequency f = 2 C / (N T),
// wall contacts counted apart, spherical regions (particles whose centre lies inside, minimum
// image on periodic axes; void fraction 1 - particle volume / sphere volume), hard-sphere steps,
// binary and multiple collisions (a particle of the pair in another contact at some step of the
// collision [Chang08 binary-collision paper]), and the checkpoint state (restore mid-contact
// continues identically).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <vector>

#include "analysis/collision_statistics.hpp"

namespace fluidem {
namespace {

constexpr double kPi = std::numbers::pi;

/// Four particles: ids 10, 11, 12, 13; radii 1, 1, 0.5, 2 (m); centres given.
ParticleStore particles() {
  ParticleStore p;
  p.add({0.0, 0.0, 0.0}, {}, 1.0, 1.0, 0, 10);
  p.add({1.9, 0.0, 0.0}, {}, 1.0, 1.0, 0, 11);
  p.add({0.0, 1.4, 0.0}, {}, 0.5, 1.0, 0, 12);
  p.add({9.5, 0.0, 0.0}, {}, 2.0, 1.0, 0, 13);
  return p;
}

ContactSample pair(int i, int j, std::int64_t id_i, std::int64_t id_j, double overlap,
                   Vec3 point = {}) {
  ContactSample s;
  s.i = i, s.j = j, s.id_i = id_i, s.id_j = id_j, s.overlap = overlap, s.contact_point = point;
  return s;
}
ContactSample wall(int i, std::int64_t id, int face, double overlap) {
  ContactSample s;
  s.i = i, s.j = -1, s.id_i = id, s.id_j = -1 - face, s.overlap = overlap;
  return s;
}

CollisionStatistics::Settings settings() {
  CollisionStatistics::Settings s;
  s.box_length = {10.0, 10.0, 10.0};
  s.periodic = {true, false, false};
  return s;
}

TEST(CollisionStatistics, BirthsEndsDurationsAndExtents) {
  const ParticleStore p = particles();
  CollisionStatistics c(settings(), 0.0);
  ContactRecord r;
  r.enabled = true;
  // Steps at t = 1..6 (dt = 1). Pair 10-11 (diameters 2, 2) seen at t = 1..3 with overlaps
  // 0.01, 0.03, 0.02, listed once as (11, 10): the same contact. Pair 10-12 (smaller diameter 1)
  // at t = 2 only, overlap 0.0123. Wall contact of 13 on face 4 at t = 1..2.
  r.samples = {pair(0, 1, 10, 11, 0.01), wall(3, 13, 4, 0.1)};
  c.add_step(r, p, 1.0);
  r.samples = {wall(3, 13, 4, 0.2), pair(0, 2, 10, 12, 0.0123), pair(1, 0, 11, 10, 0.03)};
  c.add_step(r, p, 2.0);
  EXPECT_EQ(c.ongoing(), 3u);
  r.samples = {pair(0, 1, 10, 11, 0.02)};
  c.add_step(r, p, 3.0);
  EXPECT_EQ(c.pair_collisions(), 2);
  EXPECT_EQ(c.pair_collisions_ended(), 1); // 10-12 ended at t = 3
  EXPECT_EQ(c.wall_collisions(), 1);
  EXPECT_EQ(c.wall_collisions_ended(), 1);
  r.samples.clear();
  c.add_step(r, p, 4.0);
  EXPECT_EQ(c.ongoing(), 0u);
  // Extents: 0.0123 / 1 and 0.03 / 2 = 0.015; durations 1 and 3.
  EXPECT_DOUBLE_EQ(c.mean_overlap(), 0.5 * (0.0123 + 0.015));
  EXPECT_DOUBLE_EQ(c.max_overlap(), 0.015);
  EXPECT_DOUBLE_EQ(c.mean_duration(), 2.0);
  // Histogram: 200 bins of 0.0005 on [0, 0.1): 0.0123 -> bin 24, 0.015 -> bin 30.
  ASSERT_EQ(c.histogram().size(), 201u);
  EXPECT_EQ(c.histogram()[24], 1);
  EXPECT_EQ(c.histogram()[30], 1);
  const auto row = c.take_row(4.0, p.size());
  EXPECT_EQ(row.pair_collisions, 2);
  EXPECT_EQ(row.wall_collisions, 1);
  EXPECT_DOUBLE_EQ(row.frequency, 2.0 * 2.0 / (4.0 * 4.0));
  EXPECT_DOUBLE_EQ(row.mean_free_time, 4.0);
  EXPECT_DOUBLE_EQ(row.max_overlap, 0.015);
  // The next interval starts empty.
  const auto next = c.take_row(5.0, p.size());
  EXPECT_EQ(next.pair_collisions, 0);
  EXPECT_EQ(next.frequency, 0.0);
  EXPECT_TRUE(std::isinf(next.mean_free_time));
  EXPECT_TRUE(std::isnan(next.mean_overlap));
}

/// Steps of many keyed contacts, each step's in a shuffled order: the statistics must be those a
/// map from key to the ongoing contact gives (contacts begin when a key appears, end when it is
/// missing, ended in key order: the same sums in the same order). `id_base`: the ids start
/// there; `wide`: some ids are that plus 2^40 (keys spanning more than 2^32: the comparison
/// sort), else within 2^17 (the radix sort, above 4096 contacts a step).
void expect_map_statistics(std::int64_t id_base, bool wide) {
  CollisionStatistics c(settings(), 0.0);
  struct Ref {
    double begin, max_overlap, diameter;
    bool multiple;
  };
  std::map<std::pair<std::int64_t, std::int64_t>, Ref> ongoing;
  long pairs = 0, walls = 0, ended = 0, multiple = 0;
  double sum_extent = 0.0, sum_duration = 0.0;
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::int64_t> id(0, 60000);
  std::uniform_real_distribution<double> overlap(1e-6, 1e-4);
  const auto shifted = [&](std::int64_t v) {
    return id_base + (wide && v % 7 == 0 ? v + (std::int64_t{1} << 40) : v);
  };
  for (int step = 1; step <= 6; ++step) {
    const double t = 1e-5 * step;
    std::map<std::pair<std::int64_t, std::int64_t>, std::size_t> seen;
    std::vector<KeyedContact> rec;
    for (int k = 0; k < 8000; ++k) {
      // Half of the keys carry over from the step before (ongoing contacts).
      KeyedContact kc;
      if (k % 2 == 0 && !ongoing.empty() && step > 1) {
        auto it = ongoing.begin();
        std::advance(it, static_cast<long>(rng() % std::min<std::size_t>(ongoing.size(), 5000)));
        kc.a = it->first.first, kc.b = it->first.second;
      } else {
        const std::int64_t x = shifted(id(rng)), y = rng() % 10 == 0
                                                         ? -1 - static_cast<std::int64_t>(rng() % 6)
                                                         : shifted(id(rng));
        if (y >= 0 && x == y) continue;
        kc.a = y < 0 ? x : std::min(x, y), kc.b = y < 0 ? y : std::max(x, y);
      }
      if (seen.count({kc.a, kc.b})) continue; // one contact loop lists a contact once
      seen[{kc.a, kc.b}] = rec.size();
      kc.overlap = overlap(rng), kc.diameter = 0.004;
      rec.push_back(kc);
    }
    std::shuffle(rec.begin(), rec.end(), rng);
    for (auto it = ongoing.begin(); it != ongoing.end();) {
      if (seen.count(it->first)) {
        ++it;
        continue;
      }
      if (it->first.second >= 0) {
        ++ended;
        if (it->second.multiple) ++multiple;
        sum_extent += it->second.max_overlap / it->second.diameter;
        sum_duration += t - it->second.begin;
      }
      it = ongoing.erase(it);
    }
    std::map<std::int64_t, int> contacts_of; // particle ids (>= 0) in this step's contacts
    for (const KeyedContact& kc : rec)
      for (const std::int64_t particle : {kc.a, kc.b})
        if (particle >= 0) ++contacts_of[particle];
    for (const KeyedContact& kc : rec) {
      const bool now = kc.b >= 0 && (contacts_of[kc.a] > 1 || contacts_of[kc.b] > 1);
      auto [it, fresh] = ongoing.try_emplace({kc.a, kc.b}, Ref{t, kc.overlap, kc.diameter, now});
      if (fresh)
        ++(kc.b < 0 ? walls : pairs);
      else
        it->second.max_overlap = std::max(it->second.max_overlap, kc.overlap),
        it->second.multiple = it->second.multiple || now;
    }
    c.add_keyed_step(rec, ParticleStore{}, t);
  }
  ASSERT_GT(pairs, 20000);
  EXPECT_EQ(c.pair_collisions(), pairs);
  EXPECT_EQ(c.wall_collisions(), walls);
  EXPECT_EQ(c.pair_collisions_ended(), ended);
  EXPECT_EQ(c.multiple_collisions(), multiple);
  EXPECT_GT(multiple, 0);
  EXPECT_LT(multiple, ended);
  EXPECT_EQ(c.ongoing(), ongoing.size());
  EXPECT_EQ(c.mean_overlap(), sum_extent / static_cast<double>(ended));
  EXPECT_EQ(c.mean_duration(), sum_duration / static_cast<double>(ended));
}

TEST(CollisionStatistics, ManyContactsInAnyOrderAsAMapOfOngoingContacts) {
  expect_map_statistics(0, false);
  expect_map_statistics(-5, false); // (no pair has a negative id, but the packing must not care)
  expect_map_statistics(1000, true);
}

TEST(CollisionStatistics, OverflowBin) {
  const ParticleStore p = particles();
  CollisionStatistics c(settings(), 0.0);
  ContactRecord r;
  r.samples = {pair(0, 1, 10, 11, 0.5)}; // extent 0.25 >= 0.1
  c.add_step(r, p, 1.0);
  r.samples.clear();
  c.add_step(r, p, 2.0);
  EXPECT_EQ(c.histogram().back(), 1);
}

TEST(CollisionStatistics, RegionsCountCentresAndContactPoints) {
  const ParticleStore p = particles();
  auto s = settings();
  // A sphere of radius 2 around the origin holds the centres of 10, 11 (1.9 away) and 12; 13 at
  // x = 9.5 is 0.5 away through the periodic x boundary (box 10): inside too. A second sphere
  // far away holds none.
  s.regions = {{"A", {0.0, 0.0, 0.0}, 2.0}, {"far", {5.0, 5.0, 5.0}, 1.0}};
  CollisionStatistics c(s, 0.0);
  ContactRecord r;
  r.samples = {pair(0, 1, 10, 11, 0.01, {0.95, 0.0, 0.0}), pair(0, 2, 10, 12, 0.01, {0, 3, 0})};
  c.add_step(r, p, 1.0);
  r.samples.clear();
  c.add_step(r, p, 2.0);
  const auto row = c.take_row(2.0, p.size());
  ASSERT_EQ(row.regions.size(), 2u);
  const double v_particles = 4.0 / 3.0 * kPi * (1.0 + 1.0 + 0.125 + 8.0);
  const double v_sphere = 4.0 / 3.0 * kPi * 8.0;
  EXPECT_DOUBLE_EQ(row.regions[0].particles, 4.0);
  EXPECT_DOUBLE_EQ(row.regions[0].void_fraction, 1.0 - v_particles / v_sphere);
  EXPECT_EQ(row.regions[0].collisions, 1); // the second contact point lies outside
  EXPECT_DOUBLE_EQ(row.regions[0].frequency, 2.0 * 1.0 / (4.0 * 2.0));
  EXPECT_DOUBLE_EQ(row.regions[1].particles, 0.0);
  EXPECT_DOUBLE_EQ(row.regions[1].void_fraction, 1.0);
  EXPECT_TRUE(std::isnan(row.regions[1].frequency));
}

TEST(CollisionStatistics, TwoDimensionalRegionsAreCircles) {
  ParticleStore p;
  p.add({0.0, 0.0, 0.0}, {}, 1.0, 1.0, 0, 0);
  auto s = settings();
  s.dimension = 2;
  s.regions = {{"c", {0.0, 7.0, 0.0}, 2.0}}; // y ignored in 2-D
  CollisionStatistics c(s, 0.0);
  c.add_step(ContactRecord{}, p, 1.0);
  const auto row = c.take_row(1.0, p.size());
  EXPECT_DOUBLE_EQ(row.regions[0].void_fraction, 1.0 - 1.0 / 4.0);
}

TEST(CollisionStatistics, HardSphereStepsCountWithoutOverlap) {
  const ParticleStore p = particles();
  CollisionStatistics c(settings(), 0.0);
  c.add_instant_step({{10, 11, {}}, {12, -1 - 3, {}}, {11, 13, {}}}, p, 0.5);
  EXPECT_EQ(c.pair_collisions(), 2);
  EXPECT_EQ(c.wall_collisions(), 1);
  EXPECT_EQ(c.ongoing(), 0u);
  const auto row = c.take_row(1.0, p.size());
  EXPECT_DOUBLE_EQ(row.frequency, 2.0 * 2.0 / 4.0);
  EXPECT_TRUE(std::isnan(row.mean_overlap));
  EXPECT_TRUE(std::isnan(row.mean_duration));
}

// Five particles in a chain and a pair apart, worked out by hand. Steps of 1 s:
//   t = 1: 0-1 and 1-2 touch (1 has two contacts: both multiple); 3-4 alone (binary so far);
//   t = 2: 0-1 gone (ends, multiple); 1-2 continues alone (stays multiple: it was); 3-4 and a
//          wall contact of 4 (4 has two contacts: 3-4 becomes multiple);
//   t = 3: 1-2 and 3-4 gone (end, both multiple); 5-6 begins alone;
//   t = 4: 5-6 gone (ends, binary). The wall contact ended at t = 3.
TEST(CollisionStatistics, MultipleWhenAParticleOfThePairTouchesAnotherDuringTheCollision) {
  ParticleStore p;
  for (int k = 0; k < 7; ++k) p.add({2.0 * k, 0.0, 0.0}, {}, 1.0, 1.0, 0, k);
  CollisionStatistics c(settings(), 0.0);
  ContactRecord r;
  r.samples = {pair(0, 1, 0, 1, 0.01), pair(1, 2, 1, 2, 0.01), pair(3, 4, 3, 4, 0.01)};
  c.add_step(r, p, 1.0);
  r.samples = {pair(1, 2, 1, 2, 0.01), pair(3, 4, 3, 4, 0.01), wall(4, 4, 0, 0.01)};
  c.add_step(r, p, 2.0);
  EXPECT_EQ(c.pair_collisions_ended(), 1);
  EXPECT_EQ(c.multiple_collisions(), 1); // 0-1
  r.samples = {pair(5, 6, 5, 6, 0.01)};
  c.add_step(r, p, 3.0);
  EXPECT_EQ(c.pair_collisions_ended(), 3);
  EXPECT_EQ(c.multiple_collisions(), 3); // 1-2 (from t = 1), 3-4 (the wall at t = 2)
  c.add_step(ContactRecord{}, p, 4.0);
  EXPECT_EQ(c.pair_collisions_ended(), 4);
  EXPECT_EQ(c.multiple_collisions(), 3); // 5-6 was binary
  const auto row = c.take_row(4.0, p.size());
  EXPECT_EQ(row.pair_collisions_ended, 4);
  EXPECT_EQ(row.multiple_collisions, 3);
}

// The same pair listed twice in one record is one contact, not two: it does not make the pair
// multiple. Hard-sphere collisions are never multiple (instantaneous).
TEST(CollisionStatistics, ADuplicateKeyIsOneContactAndHardSphereCollisionsAreBinary) {
  const ParticleStore p = particles();
  CollisionStatistics c(settings(), 0.0);
  ContactRecord r;
  r.samples = {pair(0, 1, 10, 11, 0.01), pair(1, 0, 11, 10, 0.02)};
  c.add_step(r, p, 1.0);
  c.add_step(ContactRecord{}, p, 2.0);
  EXPECT_EQ(c.pair_collisions_ended(), 1);
  EXPECT_EQ(c.multiple_collisions(), 0);
  c.add_instant_step({{10, 11, {}}, {11, 12, {}}}, p, 3.0);
  EXPECT_EQ(c.multiple_collisions(), 0);
}

// Per region: the collisions ended whose contact point lay inside when they began, and the
// multiple ones among them; a checkpoint taken mid-collision keeps the flag and the point.
TEST(CollisionStatistics, RegionsCountMultipleCollisionsByWhereTheyBegan) {
  ParticleStore p;
  for (int k = 0; k < 4; ++k) p.add({2.0 * k, 0.0, 0.0}, {}, 1.0, 1.0, 0, k);
  auto s = settings();
  s.regions = {{"A", {0.0, 0.0, 0.0}, 1.5}, {"B", {6.0, 0.0, 0.0}, 0.5}};
  CollisionStatistics a(s, 0.0);
  ContactRecord r;
  // 0-1 begins at x = 1 (in A), 2-3 at x = 5 (in neither); 1-2 touches 1 too: 0-1 multiple.
  r.samples = {pair(0, 1, 0, 1, 0.01, {1.0, 0, 0}), pair(1, 2, 1, 2, 0.01, {3.0, 0, 0}),
               pair(2, 3, 2, 3, 0.01, {5.0, 0, 0})};
  a.add_step(r, p, 1.0);
  CollisionStatistics b(s, 0.0);
  b.restore(a.state());
  for (CollisionStatistics* c : {&a, &b}) {
    ContactRecord r2; // the contact points move (ignored: where a collision began counts)
    r2.samples = {pair(0, 1, 0, 1, 0.01, {6.0, 0, 0}), pair(2, 3, 2, 3, 0.01, {6.0, 0, 0})};
    c->add_step(r2, p, 2.0);
    c->add_step(ContactRecord{}, p, 3.0);
  }
  for (CollisionStatistics* c : {&a, &b}) {
    const auto row = c->take_row(3.0, p.size());
    EXPECT_EQ(row.pair_collisions_ended, 3);
    EXPECT_EQ(row.multiple_collisions, 3); // 2 touched 1 and 3 at t = 1
    EXPECT_EQ(row.regions[0].ended, 1);
    EXPECT_EQ(row.regions[0].multiple, 1);
    EXPECT_EQ(row.regions[1].ended, 0);
  }
}

TEST(CollisionStatistics, StateRestoresMidContact) {
  const ParticleStore p = particles();
  auto s = settings();
  s.regions = {{"A", {0.0, 0.0, 0.0}, 2.0}};
  CollisionStatistics a(s, 0.0);
  ContactRecord r;
  r.samples = {pair(0, 1, 10, 11, 0.01, {0.95, 0, 0}), wall(3, 13, 5, 0.1)};
  a.add_step(r, p, 1.0);
  CollisionStatistics b(s, 0.0);
  b.restore(a.state());
  for (CollisionStatistics* c : {&a, &b}) {
    ContactRecord r2;
    r2.samples = {pair(0, 1, 10, 11, 0.04)};
    c->add_step(r2, p, 2.0);
    c->add_step(ContactRecord{}, p, 3.0);
  }
  const auto ra = a.take_row(3.0, 4), rb = b.take_row(3.0, 4);
  EXPECT_EQ(ra.pair_collisions, rb.pair_collisions);
  EXPECT_EQ(ra.wall_collisions, rb.wall_collisions);
  EXPECT_EQ(ra.frequency, rb.frequency);
  EXPECT_EQ(ra.mean_overlap, rb.mean_overlap);
  EXPECT_EQ(ra.mean_duration, rb.mean_duration);
  EXPECT_EQ(ra.regions[0].void_fraction, rb.regions[0].void_fraction);
  EXPECT_EQ(ra.regions[0].frequency, rb.regions[0].frequency);
  EXPECT_EQ(a.histogram(), b.histogram());
  EXPECT_DOUBLE_EQ(ra.mean_overlap, 0.02);
  CollisionStatistics other(settings(), 0.0); // no region: the state does not fit
  EXPECT_THROW(other.restore(a.state()), std::runtime_error);
}

} // namespace
} // namespace fluidem
