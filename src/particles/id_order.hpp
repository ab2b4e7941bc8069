// The store's indices in ascending id order: the order a run's frames list the particles in, and
// a summation order that does not depend on how the store was sorted in space.
#pragma once
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "particles/particle_store.hpp"

namespace fluidem {

inline std::vector<std::uint32_t> id_order(const ParticleStore& p) {
  std::vector<std::uint32_t> order(p.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return p.id[a] < p.id[b]; });
  return order;
}

} // namespace fluidem
