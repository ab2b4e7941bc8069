// The cell grid (cell_grid.hpp) against its definition: particle i's cell is floor((x - lo) /
// (L / n)) on each axis (wrapped on periodic axes, clamped on closed ones), and the walk around
// i visits the cells of for_each_cell_around (cell_walk_test.cpp checks those) in its order, the
// particles of each in ascending index order. Both storages, dense (a bed) and hashed (a few
// particles in a big box), give that same walk; the hashed one stores only occupied cells.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "neighbour/cell_grid.hpp"

namespace fluidem {
namespace {

struct Cloud {
  std::vector<double> x, y, z;
};

/// Each particle's cell by the definition (flat index, x fastest).
std::vector<std::uint64_t> cells_by_definition(const Cloud& c, const BoxGeometry& b,
                                               const std::array<int, 3>& n) {
  std::vector<std::uint64_t> out;
  for (std::size_t k = 0; k < c.x.size(); ++k) {
    const double pos[3] = {c.x[k], c.y[k], c.z[k]};
    std::uint64_t q[3];
    for (int a = 0; a < 3; ++a) {
      double rel = pos[a] - b.lo[a];
      if (b.periodic[a]) rel -= b.length(a) * std::floor(rel / b.length(a));
      const int v = static_cast<int>(rel * (n[a] / b.length(a)));
      q[a] = static_cast<std::uint64_t>(std::clamp(v, 0, n[a] - 1));
    }
    out.push_back(
        (q[2] * static_cast<std::uint64_t>(n[1]) + q[1]) * static_cast<std::uint64_t>(n[0]) + q[0]);
  }
  return out;
}

/// The walk around particle i by the definition: every particle of each cell of the block, in
/// the block's order, by ascending index (an all-particles scan per cell).
std::vector<std::uint32_t> walk_by_definition(const std::vector<std::uint64_t>& cell, std::size_t i,
                                              const BoxGeometry& b, const std::array<int, 3>& n) {
  std::vector<std::uint32_t> out;
  for_each_cell_around(cell[i], n, b.periodic, [&](std::uint64_t around) {
    for (std::size_t k = 0; k < cell.size(); ++k)
      if (cell[k] == around) out.push_back(static_cast<std::uint32_t>(k));
  });
  return out;
}

void expect_walks_by_definition(const Cloud& c, const BoxGeometry& b, double cell_size,
                                bool dense) {
  CellGrid g;
  const std::size_t n = c.x.size();
  g.bin(b, cell_size, c.x.data(), c.y.data(), c.z.data(), n, false);
  EXPECT_EQ(g.dense(), dense);
  const std::vector<std::uint64_t> cell = cells_by_definition(c, b, g.cells_per_axis());
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::uint32_t> walk;
    g.for_each_near(i, b.periodic, [&](std::uint32_t j) { walk.push_back(j); });
    ASSERT_EQ(walk, walk_by_definition(cell, i, b, g.cells_per_axis())) << "particle " << i;
  }
}

BoxGeometry cube(double l, bool periodic) {
  BoxGeometry b;
  b.hi = {l, l, l};
  b.periodic = {periodic, periodic, periodic};
  return b;
}

TEST(CellGrid, DenseAndHashedWalkTheCellsOfTheDefinition) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const bool periodic : {false, true}) {
    // A bed: 1000 particles in 10 x 10 x 10 cells (dense).
    Cloud bed;
    for (int k = 0; k < 1000; ++k)
      bed.x.push_back(0.01 * u(rng)), bed.y.push_back(0.01 * u(rng)),
          bed.z.push_back(0.01 * u(rng));
    expect_walks_by_definition(bed, cube(0.01, periodic), 0.001, true);
    // The same kind of cloud in a box of 10^12 cells (hashed), clustered across a corner.
    Cloud sparse;
    for (int k = 0; k < 300; ++k) {
      sparse.x.push_back(std::fmod(0.9999 + 0.0003 * u(rng), 1.0));
      sparse.y.push_back(0.0003 * u(rng));
      sparse.z.push_back(k % 10 == 0 ? u(rng) : 0.5 + 0.0003 * u(rng));
    }
    expect_walks_by_definition(sparse, cube(1.0, periodic), 1e-4, false);
  }
}

TEST(CellGrid, HashedGridStoresOnlyOccupiedCells) {
  // One particle in a 4 cm box with cells of 0.12 mm (issue 32 item 23): 333^3 = 3.7e7 cells.
  const double x = 0.02, y = 0.021, z = 0.019;
  CellGrid g;
  g.bin(cube(0.04, false), 1.2e-4, &x, &y, &z, 1, false);
  EXPECT_EQ(g.cells_per_axis()[0], 333);
  EXPECT_FALSE(g.dense());
  EXPECT_EQ(g.stored_cells(), 1u);
  EXPECT_LT(g.bytes(), 256u);
  std::vector<std::uint32_t> walk;
  g.for_each_near(0, {false, false, false}, [&](std::uint32_t j) { walk.push_back(j); });
  EXPECT_EQ(walk, std::vector<std::uint32_t>{0});
  // At most 2^20 cells per axis; no overflow of the flat index in a box of 10^18 cells.
  g.bin(cube(1e6, true), 1e-3, &x, &y, &z, 1, false);
  EXPECT_EQ(g.cells_per_axis()[2], CellGrid::kMaxCellsPerAxis);
  EXPECT_EQ(g.stored_cells(), 1u);
  EXPECT_EQ(g.coordinate(0, 0), static_cast<std::uint32_t>(0.02 / 1e6 * (1 << 20)));
}

} // namespace
} // namespace fluidem
