// Neighbour list: every pair within r_i + r_j + skin appears exactly once (checked against an
// all-pairs search), rebuilds happen on the skin/2 displacement criterion, and contact history
// survives a rebuild, negated when the pair changes owner (the history is seen from the owner:
// [Deen07 eq. 31] integrates the velocity of the owner relative to its partner).
#include <gtest/gtest.h>

#include <algorithm>
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

} // namespace
} // namespace fluidem
