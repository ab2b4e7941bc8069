#include "neighbour/spatial_order.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

namespace fluidem {

namespace {
/// The 21 low bits of v spread to every third bit (bit b -> bit 3b).
std::uint64_t spread_bits(std::uint32_t v) {
  std::uint64_t x = v & 0x1fffffu;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}
} // namespace

std::uint64_t morton_code(std::uint32_t cx, std::uint32_t cy, std::uint32_t cz) {
  return spread_bits(cx) | spread_bits(cy) << 1 | spread_bits(cz) << 2;
}

int slab_axis(const std::array<std::uint32_t, 3>& cmin, const std::array<std::uint32_t, 3>& cmax) {
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (cmax[a] - cmin[a] > cmax[axis] - cmin[axis]) axis = a;
  return axis;
}

std::vector<std::uint32_t> spatial_order(const ParticleStore& p, const BoxGeometry& box,
                                         double cell_size) {
  const std::size_t n = p.size();
  constexpr int kMaxCell = (1 << 21) - 1;
  std::array<double, 3> inv{};
  std::array<int, 3> ncell{};
  for (int a = 0; a < 3; ++a) {
    const double l = box.length(a);
    ncell[a] = std::clamp(static_cast<int>(std::floor(l / cell_size)), 1, kMaxCell);
    inv[a] = ncell[a] / l;
  }
  std::vector<std::array<std::uint32_t, 3>> cell(n);
  const std::array<const std::vector<double>*, 3> pos{&p.x, &p.y, &p.z};
  const bool threaded = threaded_particles(n);
  parallel_for(n, threaded, [&](std::size_t i) {
    for (int a = 0; a < 3; ++a) {
      double rel = (*pos[a])[i] - box.lo[a];
      if (box.periodic[a]) rel -= box.length(a) * std::floor(rel / box.length(a));
      cell[i][a] =
          static_cast<std::uint32_t>(std::clamp(static_cast<int>(rel * inv[a]), 0, ncell[a] - 1));
    }
  });
  std::array<std::uint32_t, 3> cmin{~0u, ~0u, ~0u}, cmax{0, 0, 0};
  for (const auto& c : cell)
    for (int a = 0; a < 3; ++a)
      cmin[a] = std::min(cmin[a], c[a]), cmax[a] = std::max(cmax[a], c[a]);
  const int s = n > 0 ? slab_axis(cmin, cmax) : 0;
  const int u = s == 0 ? 1 : 0, v = s == 2 ? 1 : 2; // the other two axes, in order
  // (slab cell, Morton code across the slab, index): sorting orders by all three.
  std::vector<std::tuple<std::uint32_t, std::uint64_t, std::uint32_t>> key(n);
  parallel_for(n, threaded, [&](std::size_t i) {
    key[i] = {cell[i][s], morton_code(cell[i][u], cell[i][v], 0), static_cast<std::uint32_t>(i)};
  });
  std::sort(key.begin(), key.end());
  std::vector<std::uint32_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = std::get<2>(key[k]);
  return order;
}

} // namespace fluidem
