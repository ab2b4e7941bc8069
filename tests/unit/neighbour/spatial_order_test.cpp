// Spatial sorting (neighbour/spatial_order.hpp): the Morton code interleaves the bits of the cell
// coordinates (checked against a bit-by-bit reference), the order is a permutation sorted by
// slab, Morton code across the slab, then index; periodic images fall into the box's cells; the
// slab axis is the neighbour list's (the axis of the widest span); and a rebuild of the neighbour
// list after a reordering of the store keeps each pair's and each wall contact's history with
// its particles (the reference: the same pairs looked up by particle id before and after).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <tuple>

#include "neighbour/neighbour_list.hpp"
#include "neighbour/spatial_order.hpp"

namespace fluidem {
namespace {

std::uint64_t morton_reference(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  std::uint64_t code = 0;
  for (int b = 0; b < 21; ++b) {
    code |= static_cast<std::uint64_t>((x >> b) & 1u) << (3 * b);
    code |= static_cast<std::uint64_t>((y >> b) & 1u) << (3 * b + 1);
    code |= static_cast<std::uint64_t>((z >> b) & 1u) << (3 * b + 2);
  }
  return code;
}

BoxGeometry closed_box(double lx, double ly, double lz) {
  BoxGeometry b;
  b.hi = {lx, ly, lz};
  for (int f = 0; f < 6; ++f) b.wall[f] = true;
  return b;
}

TEST(SpatialOrder, MortonCodeInterleavesTheBits) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::uint32_t> u(0, (1u << 21) - 1);
  for (int k = 0; k < 10000; ++k) {
    const std::uint32_t x = u(rng), y = u(rng), z = u(rng);
    ASSERT_EQ(morton_code(x, y, z), morton_reference(x, y, z)) << x << " " << y << " " << z;
  }
  EXPECT_EQ(morton_code(1, 0, 0), 1u);
  EXPECT_EQ(morton_code(0, 1, 0), 2u);
  EXPECT_EQ(morton_code(0, 0, 1), 4u);
  EXPECT_EQ(morton_code((1u << 21) - 1, (1u << 21) - 1, (1u << 21) - 1), ~0ULL >> 1);
}

TEST(SpatialOrder, SlabBySlabThenAlongAMortonCurveThenByIndex) {
  const BoxGeometry b = closed_box(0.04, 0.03, 0.05);
  const double cell = 0.004;
  ParticleStore p;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 5000; ++k)
    p.add({0.04 * u(rng), 0.03 * u(rng), 0.05 * u(rng)}, {}, 0.001, 2500.0, 0, k);
  const auto order = spatial_order(p, b, cell);
  ASSERT_EQ(order.size(), p.size());
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t k = 0; k < sorted.size(); ++k) ASSERT_EQ(sorted[k], k);
  // 10 x 7 x 12 cells of 4 mm (7 = floor(0.03 / 0.004)): the particles span the most cells
  // along z, the slab axis; across a slab the Morton code of (x cell, y cell).
  const auto c = [](double v, double l, int n) {
    return static_cast<std::uint32_t>(std::min(static_cast<int>(v / l * n), n - 1));
  };
  auto key = [&](std::uint32_t i) {
    return std::make_tuple(c(p.z[i], 0.05, 12),
                           morton_reference(c(p.x[i], 0.04, 10), c(p.y[i], 0.03, 7), 0), i);
  };
  for (std::size_t k = 1; k < order.size(); ++k)
    ASSERT_LT(key(order[k - 1]), key(order[k])) << "entry " << k;
  // Locality, the purpose: the particles of the first slab's first 2 x 2 block of cells come
  // first, before any other.
  std::size_t in_block = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (c(p.z[i], 0.05, 12) == 0 && c(p.x[i], 0.04, 10) < 2 && c(p.y[i], 0.03, 7) < 2) ++in_block;
  ASSERT_GT(in_block, 0u);
  for (std::size_t k = 0; k < in_block; ++k) {
    EXPECT_EQ(std::get<0>(key(order[k])), 0u);
    EXPECT_LT(std::get<1>(key(order[k])), 4u);
  }
}

TEST(SpatialOrder, SlabAxisIsTheNeighbourListsRule) {
  EXPECT_EQ(slab_axis({0, 0, 0}, {5, 3, 9}), 2);
  EXPECT_EQ(slab_axis({0, 0, 0}, {9, 3, 9}), 0); // ties: the lowest axis
  EXPECT_EQ(slab_axis({4, 0, 0}, {9, 7, 2}), 1);
}

TEST(SpatialOrder, PeriodicImagesFallIntoTheBox) {
  BoxGeometry b = closed_box(0.04, 0.04, 0.04);
  b.periodic = {true, false, false};
  ParticleStore p;
  p.add({0.039, 0.002, 0.002}, {}, 0.001, 2500.0, 0, 0);  // last x cell
  p.add({-0.001, 0.002, 0.002}, {}, 0.001, 2500.0, 0, 1); // its image: the same cell
  p.add({0.001, 0.002, 0.002}, {}, 0.001, 2500.0, 0, 2);  // first x cell
  const auto order = spatial_order(p, b, 0.004);
  EXPECT_EQ(order, (std::vector<std::uint32_t>{2, 0, 1}));
}

TEST(SpatialOrder, RebuildAfterReorderingKeepsEveryHistoryWithItsParticles) {
  // A compressed random bed in a closed box: many pairs and wall contacts.
  const BoxGeometry b = closed_box(0.02, 0.02, 0.02);
  ParticleStore p;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 3000; ++k)
    p.add({0.02 * u(rng), 0.02 * u(rng), 0.02 * u(rng)}, {}, 0.0006, 2500.0, 0, 100 + k);
  const int hw = 6;
  NeighbourList nl(b, 2e-4, hw);
  nl.build(p);
  // Give every entry a history that names its pair as seen from the owner (antisymmetric:
  // seen from the partner it is negated) and every wall entry one that names particle and face.
  auto pair_value = [](std::int64_t owner, std::int64_t other, int h) {
    const double v =
        static_cast<double>(std::min(owner, other) * 10007 + std::max(owner, other)) + 0.125 * h;
    return owner < other ? v : -v;
  };
  for (std::uint32_t i = 0; i < p.size(); ++i)
    for (std::uint32_t e = nl.offset[i]; e < nl.offset[i + 1]; ++e)
      for (int h = 0; h < hw; ++h)
        nl.history[e * hw + h] = pair_value(p.id[i], p.id[nl.partner[e]], h);
  for (std::size_t e = 0; e < nl.wall_particle.size(); ++e)
    for (int h = 0; h < hw; ++h)
      nl.wall_history[e * hw + h] =
          static_cast<double>(p.id[nl.wall_particle[e]] * 8 + nl.wall_face[e]) + 0.25 * h;
  const std::size_t pairs = nl.partner.size(), walls = nl.wall_particle.size();
  ASSERT_GT(pairs, 5000u);
  ASSERT_GT(walls, 300u);

  // Reorder the store (a random permutation, then the spatial order) and rebuild.
  for (int round = 0; round < 2; ++round) {
    std::vector<std::uint32_t> order(p.size());
    if (round == 0) {
      std::iota(order.begin(), order.end(), 0u);
      std::shuffle(order.begin(), order.end(), rng);
    } else {
      order = spatial_order(p, b, 2 * 0.0006 + 2e-4);
    }
    p.permute(order);
    nl.build(p, &order);
    ASSERT_EQ(nl.partner.size(), pairs);
    ASSERT_EQ(nl.wall_particle.size(), walls);
    for (std::uint32_t i = 0; i < p.size(); ++i)
      for (std::uint32_t e = nl.offset[i]; e < nl.offset[i + 1]; ++e)
        for (int h = 0; h < hw; ++h)
          ASSERT_EQ(nl.history[e * hw + h], pair_value(p.id[i], p.id[nl.partner[e]], h))
              << "round " << round << ", pair of ids " << p.id[i] << ", " << p.id[nl.partner[e]];
    for (std::size_t e = 0; e < nl.wall_particle.size(); ++e)
      for (int h = 0; h < hw; ++h)
        ASSERT_EQ(nl.wall_history[e * hw + h],
                  static_cast<double>(p.id[nl.wall_particle[e]] * 8 + nl.wall_face[e]) + 0.25 * h)
            << "round " << round;
  }
  const std::vector<std::uint32_t> wrong_size(3);
  EXPECT_THROW(nl.build(p, &wrong_size), std::invalid_argument);
}

} // namespace
} // namespace fluidem
