#include "neighbour/spatial_order.hpp"

#include <algorithm>
#include <array>
#include <cmath>

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
  // (code, index) pairs: sorting them orders by code, then by index (the ties).
  std::vector<std::pair<std::uint64_t, std::uint32_t>> key(n);
  const std::array<const std::vector<double>*, 3> pos{&p.x, &p.y, &p.z};
#pragma omp parallel for schedule(static) if (n > 4096)
  for (std::size_t i = 0; i < n; ++i) {
    std::array<std::uint32_t, 3> c{};
    for (int a = 0; a < 3; ++a) {
      double rel = (*pos[a])[i] - box.lo[a];
      if (box.periodic[a]) rel -= box.length(a) * std::floor(rel / box.length(a));
      c[a] =
          static_cast<std::uint32_t>(std::clamp(static_cast<int>(rel * inv[a]), 0, ncell[a] - 1));
    }
    key[i] = {morton_code(c[0], c[1], c[2]), static_cast<std::uint32_t>(i)};
  }
  std::sort(key.begin(), key.end());
  std::vector<std::uint32_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = key[k].second;
  return order;
}

} // namespace fluidem
