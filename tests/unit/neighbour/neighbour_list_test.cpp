// Neighbour list: every pair within r_i + r_j + skin appears exactly once (checked against an
// all-pairs search), rebuilds happen on the skin/2 displacement criterion, and contact history
// survives a rebuild, negated when the pair changes owner (the history is seen from the owner:
// [Deen07 eq. 31] integrates the velocity of the owner relative to its partner).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>

#include "neighbour/neighbour_list.hpp"

namespace fluidem {
namespace {

BoxGeometry box(double lx, double ly, double lz, std::array<bool, 3> periodic) {
  BoxGeometry b;
  b.hi = {lx, ly, lz};
  b.periodic = periodic;
  for (int f = 0; f < 6; ++f) b.wall[f] = !periodic[f / 2];
  return b;
}

std::set<std::pair<std::uint32_t, std::uint32_t>> listed_pairs(const NeighbourList& nl,
                                                               std::size_t n) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const std::uint32_t j = nl.partner[e];
      EXPECT_TRUE(out.insert({std::min(i, j), std::max(i, j)}).second) << "pair listed twice";
    }
  return out;
}

/// Every pair within r_i + r_j + skin, by an all-pairs search (the definition).
std::set<std::pair<std::uint32_t, std::uint32_t>>
pairs_within(const NeighbourList& nl, const ParticleStore& p, double skin) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> expected;
  for (std::uint32_t i = 0; i < p.size(); ++i)
    for (std::uint32_t j = i + 1; j < p.size(); ++j) {
      const double dx = nl.min_image(p.x[j] - p.x[i], 0);
      const double dy = nl.min_image(p.y[j] - p.y[i], 1);
      const double dz = nl.min_image(p.z[j] - p.z[i], 2);
      const double cut = p.radius[i] + p.radius[j] + skin;
      if (dx * dx + dy * dy + dz * dz < cut * cut) expected.insert({i, j});
    }
  return expected;
}

TEST(NeighbourList, FindsExactlyThePairsWithinTheCutoff) {
  for (const auto periodic :
       {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, true, false}}) {
    const auto b = box(0.03, 0.02, 0.02, periodic);
    ParticleStore p;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 2000; ++k)
      p.add({0.03 * u(rng), 0.02 * u(rng), 0.02 * u(rng)}, {}, 0.0004 + 0.0004 * u(rng), 2500.0, 0,
            k + 1);
    const double skin = 2e-4;
    NeighbourList nl(b, skin, 3);
    nl.build(p);
    std::set<std::pair<std::uint32_t, std::uint32_t>> expected;
    for (std::uint32_t i = 0; i < p.size(); ++i)
      for (std::uint32_t j = i + 1; j < p.size(); ++j) {
        const double dx = nl.min_image(p.x[j] - p.x[i], 0);
        const double dy = nl.min_image(p.y[j] - p.y[i], 1);
        const double dz = nl.min_image(p.z[j] - p.z[i], 2);
        const double cut = p.radius[i] + p.radius[j] + skin;
        if (dx * dx + dy * dy + dz * dz < cut * cut) expected.insert({i, j});
      }
    EXPECT_EQ(listed_pairs(nl, p.size()), expected);
    EXPECT_GT(expected.size(), 1000u);
    // Slabs cover every particle once.
    std::vector<std::uint32_t> all(nl.slab_particles);
    std::sort(all.begin(), all.end());
    for (std::uint32_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i], i);
  }
}

TEST(NeighbourList, RebuildOnlyAfterHalfTheSkin) {
  ParticleStore p;
  p.add({0.01, 0.005, 0.005}, {}, 0.001, 2500.0, 0, 1);
  p.add({0.0119, 0.005, 0.005}, {}, 0.001, 2500.0, 0, 2);
  NeighbourList nl(box(0.1, 0.01, 0.01, {false, false, false}), 2e-4, 3);
  nl.build(p);
  p.x[0] += 0.99e-4;
  EXPECT_FALSE(nl.needs_rebuild(p));
  p.x[0] += 0.02e-4;
  EXPECT_TRUE(nl.needs_rebuild(p));
}

TEST(NeighbourList, HistorySurvivesRebuildAndIsNegatedWhenTheOwnerChanges) {
  // Two touching particles in neighbouring slabs along x (the axis of widest spread).
  ParticleStore p;
  p.add({0.0100, 0.005, 0.005}, {}, 0.001, 2500.0, 0, 1);
  p.add({0.0119, 0.005, 0.005}, {}, 0.001, 2500.0, 0, 2);
  p.add({0.0900, 0.005, 0.005}, {}, 0.001, 2500.0, 0, 3); // far away: spreads the x axis
  NeighbourList nl(box(0.1, 0.01, 0.01, {false, false, false}), 2e-4, 3);
  nl.build(p);
  ASSERT_EQ(nl.offset[1] - nl.offset[0], 1u); // particle 0 (lower slab) owns the pair
  ASSERT_EQ(nl.partner[nl.offset[0]], 1u);
  double* h = &nl.history[nl.offset[0] * 3];
  h[0] = 1.5e-5, h[1] = -2.5e-6, h[2] = 4.0e-7;

  // Same owner after a rebuild: history copied.
  p.y[0] += 1e-6;
  nl.build(p);
  ASSERT_EQ(nl.offset[1] - nl.offset[0], 1u);
  EXPECT_EQ(nl.history[nl.offset[0] * 3 + 0], 1.5e-5);
  EXPECT_EQ(nl.history[nl.offset[0] * 3 + 1], -2.5e-6);

  // Swap the x positions: particle 1 is now in the lower slab and owns the pair.
  std::swap(p.x[0], p.x[1]);
  nl.build(p);
  ASSERT_EQ(nl.offset[1] - nl.offset[0], 0u);
  ASSERT_EQ(nl.offset[2] - nl.offset[1], 1u);
  const double* g = &nl.history[nl.offset[1] * 3];
  EXPECT_EQ(g[0], -1.5e-5);
  EXPECT_EQ(g[1], 2.5e-6);
  EXPECT_EQ(g[2], -4.0e-7);

  // A pair that left the cutoff is dropped; when it comes back its history starts at zero.
  p.x[1] -= 0.01;
  nl.build(p);
  EXPECT_EQ(nl.partner.size(), 0u);
  p.x[1] += 0.01;
  nl.build(p);
  ASSERT_EQ(nl.partner.size(), 1u);
  EXPECT_EQ(nl.history[0], 0.0);
}

TEST(NeighbourList, WallEntriesForParticlesWithinTheSkinOfAWall) {
  ParticleStore p;
  p.add({0.00115, 0.005, 0.005}, {}, 0.001, 2500.0, 0, 1); // 0.15 mm from x_lo: listed
  p.add({0.05, 0.005, 0.005}, {}, 0.001, 2500.0, 0, 2);    // y and z walls within skin? no
  NeighbourList nl(box(0.1, 0.01, 0.01, {false, false, false}), 2e-4, 3);
  nl.build(p);
  ASSERT_EQ(nl.wall_particle.size(), 1u);
  EXPECT_EQ(nl.wall_particle[0], 0u);
  EXPECT_EQ(nl.wall_face[0], 0); // x_lo
}

// A few particles in a huge box (issue 32 item 23: one 100 um sphere in a 4 cm box made the
// build sweep 3.7e7 cells every time): 300 spheres of 100 um in a 1 m periodic box, most in a
// small cluster, some scattered (cells of 0.12 mm: 5.8e11 of them, which the grid over the whole
// box could not even allocate). The pairs are still exactly those of the all-pairs search, and
// the grid and the slabs hold no more than a few entries per particle.
TEST(NeighbourList, HugeSparseBoxCostsTheParticlesNotTheBox) {
  for (const auto periodic :
       {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{false, false, false}}) {
    const auto b = box(1.0, 1.0, 1.0, periodic);
    ParticleStore p;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 250; ++k) // a cluster 1 mm wide at the corner (across it, periodic)
      p.add({0.9995 + 0.001 * u(rng), 0.5 + 0.001 * u(rng), 0.0005 * u(rng)}, {}, 5e-5, 2500.0, 0,
            k + 1);
    for (int k = 0; k < 50; ++k) p.add({u(rng), u(rng), u(rng)}, {}, 5e-5, 2500.0, 0, 1000 + k);
    for (std::size_t i = 0; i < p.size(); ++i) p.x[i] -= std::floor(p.x[i]); // into the box
    const double skin = 2e-5;
    NeighbourList nl(b, skin, 3);
    nl.build(p);
    const auto expected = pairs_within(nl, p, skin);
    EXPECT_EQ(listed_pairs(nl, p.size()), expected);
    EXPECT_GT(expected.size(), 300u);
    EXPECT_EQ(nl.cells_per_axis()[0], 8333);
    EXPECT_LE(nl.stored_cells(), p.size());
    EXPECT_LE(nl.grid_bytes(), 128 * p.size()); // (the hash table: 12 bytes a slot, <= 4n slots)
    EXPECT_LE(static_cast<std::size_t>(nl.slab_count()), p.size());
    std::vector<std::uint32_t> all(nl.slab_particles);
    std::sort(all.begin(), all.end());
    for (std::uint32_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i], i);
  }
}

// The slabs are the occupied cell layers: rows of slab s hold partners in slabs s and s + 1
// only (and slab 0 from the last slab across a periodic axis), which the contact loop's
// parallel phases rely on. Two clusters far apart along x with an empty stretch between them.
TEST(NeighbourList, SlabsAreTheOccupiedLayersAndRowsReachOnlyTheNextSlab) {
  for (const bool periodic : {false, true}) {
    const auto b = box(0.2, 0.004, 0.004, {periodic, false, false});
    ParticleStore p;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 400; ++k) {
      const double x0 = k % 2 == 0 ? 0.0 : 0.15; // two clusters 5 cm wide
      p.add({x0 + 0.05 * u(rng), 0.004 * u(rng), 0.004 * u(rng)}, {}, 2e-4, 2500.0, 0, k + 1);
    }
    const double skin = 1e-4;
    NeighbourList nl(b, skin, 0);
    nl.build(p);
    EXPECT_EQ(listed_pairs(nl, p.size()), pairs_within(nl, p, skin));
    const int ns = nl.slab_count();
    std::vector<int> slab_of(p.size(), -1);
    for (int sl = 0; sl < ns; ++sl) {
      EXPECT_LT(nl.slab_start[sl], nl.slab_start[sl + 1]) << "empty slab " << sl;
      for (std::uint32_t m = nl.slab_start[sl]; m < nl.slab_start[sl + 1]; ++m)
        slab_of[nl.slab_particles[m]] = sl;
    }
    // 0.2 m of cells of 0.5 mm: 400 layers, about 200 of them occupied.
    EXPECT_LT(ns, 250);
    EXPECT_GT(ns, 150);
    for (std::uint32_t i = 0; i < p.size(); ++i)
      for (std::uint32_t e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
        const int si = slab_of[i], sj = slab_of[nl.partner[e]];
        const bool next = sj == si + 1 || (periodic && si == ns - 1 && sj == 0);
        EXPECT_TRUE(sj == si || next) << "row of slab " << si << " reaches slab " << sj;
      }
  }
}

// neighbour.skin = "auto": the skin of each build is clamp(2 k v_max dt, min, max) with the
// largest speed of that moment (NeighbourList::AutoSkin; docs/case-file.md).
TEST(NeighbourList, AutomaticSkinFollowsTheLargestSpeed) {
  ParticleStore p;
  p.add({0.01, 0.005, 0.005}, {0.1, 0.0, 0.0}, 5e-5, 2500.0, 0, 1);
  p.add({0.02, 0.005, 0.005}, {0.0, -0.3, 0.4}, 5e-5, 2500.0, 0, 2); // |v| = 0.5 m/s
  NeighbourList nl(box(0.04, 0.01, 0.01, {false, false, false}), 2e-5, 0);
  nl.set_auto_skin({1e-6, 10.0, 2e-5, 1e-4});
  nl.build(p);
  EXPECT_DOUBLE_EQ(nl.skin(), 2e-5); // 2 * 10 * 0.5 * 1e-6 = 1e-5: the lower bound
  p.vz[1] = 3.0;                     // |v| = sqrt(0.09 + 9)
  nl.build(p);
  EXPECT_DOUBLE_EQ(nl.skin(), 2.0 * 10.0 * std::sqrt(9.09) * 1e-6);
  p.vz[1] = 30.0; // 6e-4: the upper bound
  nl.build(p);
  EXPECT_DOUBLE_EQ(nl.skin(), 1e-4);
  EXPECT_DOUBLE_EQ(nl.cell_size(p), 2.0 * 5e-5 + 1e-4);
  // A list that lasts: the fast particle moves skin/2 in (skin/2) / (v dt) = 10 steps.
  p.vz[1] = 2.5;
  nl.build(p);
  const double dt = 1e-6;
  int steps = 0;
  while (!nl.needs_rebuild(p) && steps < 1000) {
    p.z[1] += p.vz[1] * dt;
    ++steps;
  }
  EXPECT_GE(steps, 10); // skin/2 = 10 v dt: due after 10 or 11 steps (round-off of the sums)
  EXPECT_LE(steps, 11);
  // A fixed skin ends the automatic one.
  nl.set_skin(3e-5);
  nl.build(p);
  EXPECT_DOUBLE_EQ(nl.skin(), 3e-5);
}

// A restored list is rebuilt with the checkpoint's skin, whatever the automatic rule would choose
// for the velocities now (else its pairs would differ from the saved ones).
TEST(NeighbourList, RestoreKeepsTheCheckpointedSkin) {
  ParticleStore p;
  for (int k = 0; k < 20; ++k)
    p.add({0.001 + 0.00013 * k, 0.005, 0.005}, {0.0, 0.0, 0.1 * (1 + k)}, 5e-5, 2500.0, 0, k + 1);
  NeighbourList a(box(0.04, 0.01, 0.01, {false, false, false}), 2e-5, 3);
  a.set_auto_skin({1e-6, 10.0, 2e-5, 1e-4});
  a.build(p);
  const NeighbourList::State s = a.state();
  EXPECT_DOUBLE_EQ(s.skin, 2.0 * 10.0 * 2.0 * 1e-6);
  EXPECT_EQ(s.partner.size(), 19u); // neighbours 0.13 mm apart: within 0.1 + 0.04 mm, not 0.12
  for (double& v : p.vz) v = 0.0;   // the rule would now choose 2e-5
  NeighbourList b(box(0.04, 0.01, 0.01, {false, false, false}), 2e-5, 3);
  b.set_auto_skin({1e-6, 10.0, 2e-5, 1e-4});
  EXPECT_NO_THROW(b.restore(p, s));
  EXPECT_EQ(b.skin(), s.skin);
  EXPECT_EQ(b.partner, a.partner);
  b.build(p); // the next build chooses again
  EXPECT_DOUBLE_EQ(b.skin(), 2e-5);
}

} // namespace
} // namespace fluidem
