// The cells around a cell of a uniform grid (cell lists [Deen07 §4]): the 3 x 3 x 3 block
// centred on it, wrapped across periodic axes, cut at closed ones, each distinct cell once (a
// periodic axis of fewer than 3 cells would otherwise visit a cell twice). Shared by the soft-
// sphere neighbour list and the hard-sphere engine's list.
#pragma once
#include <array>
#include <cstdint>

namespace fluidem {

/// Calls visit(cell) for each distinct cell of the block around `cell` (flat index, x fastest:
/// (cz * ny + cy) * nx + cx), in the order dz, dy, dx = -1 .. 1 (dx fastest). Index: the flat
/// index's type, std::uint32_t for grids of up to 2^32 cells, std::uint64_t beyond (CellGrid's
/// hashed cells: up to 2^20 per axis).
///
/// The block is the product of three per-axis index lists (the offsets -1, 0, 1 of each axis,
/// wrapped or cut, each index at its first occurrence), so two cells of it are the same only if
/// all three indices are: deduplicating per axis visits each cell once, in the order of the
/// first offsets (dz, dy, dx) that reach it — the order of a walk over all 27 offsets that skips
/// the cells it has seen.
template <class Index, class Visit>
[[gnu::always_inline]] inline void for_each_cell_around(Index cell, const std::array<int, 3>& ncell,
                                                        const std::array<bool, 3>& periodic,
                                                        Visit&& visit) {
  const auto nx = static_cast<Index>(ncell[0]), ny = static_cast<Index>(ncell[1]);
  const int c[3] = {static_cast<int>(cell % nx), static_cast<int>((cell / nx) % ny),
                    static_cast<int>(cell / (nx * ny))};
  int idx[3][3];
  int count[3];
  for (int a = 0; a < 3; ++a) {
    count[a] = 0;
    for (int d = -1; d <= 1; ++d) {
      int q = c[a] + d;
      if (q < 0 || q >= ncell[a]) {
        if (!periodic[a]) continue;
        q = (q + ncell[a]) % ncell[a];
      }
      bool seen = false;
      for (int m = 0; m < count[a]; ++m) seen = seen || idx[a][m] == q;
      if (!seen) idx[a][count[a]++] = q;
    }
  }
  for (int kz = 0; kz < count[2]; ++kz)
    for (int ky = 0; ky < count[1]; ++ky) {
      const Index row = (static_cast<Index>(idx[2][kz]) * ny + static_cast<Index>(idx[1][ky])) * nx;
      for (int kx = 0; kx < count[0]; ++kx) visit(row + static_cast<Index>(idx[0][kx]));
    }
}

} // namespace fluidem
