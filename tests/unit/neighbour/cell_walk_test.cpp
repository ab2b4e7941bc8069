// The cells around a cell (cell_walk.hpp) against the definition: the 27 offsets dz, dy, dx =
// -1 .. 1 (dx fastest), wrapped across periodic axes, dropped across closed ones, each distinct
// cell kept at its first occurrence. Every cell of grids of 1 .. 4 cells per axis, every
// combination of periodic axes: the same cells in the same order (the neighbour lists' entry
// order, and so the contact sums, follow it).
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "neighbour/cell_walk.hpp"

namespace fluidem {
namespace {

std::vector<std::uint32_t> by_definition(std::uint32_t cell, const std::array<int, 3>& n,
                                         const std::array<bool, 3>& periodic) {
  const int c[3] = {static_cast<int>(cell % n[0]), static_cast<int>((cell / n[0]) % n[1]),
                    static_cast<int>(cell / (n[0] * n[1]))};
  std::vector<std::uint32_t> out;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int d[3] = {dx, dy, dz};
        int q[3];
        bool inside = true;
        for (int a = 0; a < 3; ++a) {
          q[a] = c[a] + d[a];
          if (q[a] >= 0 && q[a] < n[a]) continue;
          if (periodic[a])
            q[a] = (q[a] + n[a]) % n[a];
          else
            inside = false;
        }
        if (!inside) continue;
        const auto flat = static_cast<std::uint32_t>((q[2] * n[1] + q[1]) * n[0] + q[0]);
        if (std::find(out.begin(), out.end(), flat) == out.end()) out.push_back(flat);
      }
  return out;
}

TEST(CellWalk, SameCellsInTheSameOrderAsTheDefinition) {
  int grids = 0;
  for (int nx = 1; nx <= 4; ++nx)
    for (int ny = 1; ny <= 4; ++ny)
      for (int nz = 1; nz <= 4; ++nz)
        for (int per = 0; per < 8; ++per) {
          const std::array<int, 3> n{nx, ny, nz};
          const std::array<bool, 3> periodic{(per & 1) != 0, (per & 2) != 0, (per & 4) != 0};
          for (std::uint32_t cell = 0; cell < static_cast<std::uint32_t>(nx * ny * nz); ++cell) {
            std::vector<std::uint32_t> got;
            for_each_cell_around(cell, n, periodic, [&](std::uint32_t q) { got.push_back(q); });
            ASSERT_EQ(got, by_definition(cell, n, periodic))
                << "grid " << nx << " x " << ny << " x " << nz << ", periodic mask " << per
                << ", cell " << cell;
          }
          ++grids;
        }
  EXPECT_EQ(grids, 512);
}

TEST(CellWalk, InteriorCellOfALargeGridHas27Neighbours) {
  std::vector<std::uint32_t> got;
  const std::array<int, 3> n{5, 5, 5};
  for_each_cell_around(62, n, {false, false, false}, [&](std::uint32_t q) { got.push_back(q); });
  ASSERT_EQ(got.size(), 27u);  // cell (2, 2, 2): the full block
  EXPECT_EQ(got.front(), 31u); // (1, 1, 1)
  EXPECT_EQ(got.back(), 93u);  // (3, 3, 3)
}

} // namespace
} // namespace fluidem
