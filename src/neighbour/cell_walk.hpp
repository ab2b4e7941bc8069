// The cells around a cell of a uniform grid (cell lists [Deen07 §4]): the 3 x 3 x 3 block
// centred on it, wrapped across periodic axes, cut at closed ones, each distinct cell once (a
// periodic axis of fewer than 3 cells would otherwise visit a cell twice). Shared by the soft-
// sphere neighbour list and the hard-sphere engine's list.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>

namespace fluidem {

/// Calls visit(cell) for each distinct cell of the block around `cell` (flat index, x fastest:
/// (cz * ny + cy) * nx + cx), in the order dz, dy, dx = -1 .. 1 (dx fastest).
template <class Visit>
void for_each_cell_around(std::uint32_t cell, const std::array<int, 3>& ncell,
                          const std::array<bool, 3>& periodic, Visit&& visit) {
  const auto nx = static_cast<std::uint32_t>(ncell[0]), ny = static_cast<std::uint32_t>(ncell[1]);
  const int cx = static_cast<int>(cell % nx);
  const int cy = static_cast<int>((cell / nx) % ny);
  const int cz = static_cast<int>(cell / (nx * ny));
  std::uint32_t seen[27];
  int nseen = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        int q[3] = {cx + dx, cy + dy, cz + dz};
        bool ok = true;
        for (int a = 0; a < 3 && ok; ++a) {
          if (q[a] < 0 || q[a] >= ncell[a]) {
            if (periodic[a])
              q[a] = (q[a] + ncell[a]) % ncell[a];
            else
              ok = false;
          }
        }
        if (!ok) continue;
        const auto c = static_cast<std::uint32_t>((q[2] * ncell[1] + q[1]) * ncell[0] + q[0]);
        if (std::find(seen, seen + nseen, c) != seen + nseen) continue;
        seen[nseen++] = c;
        visit(c);
      }
}

} // namespace fluidem
