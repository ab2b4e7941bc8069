// Spatial sorting of the particle store for memory locality: particles close in space are put
// close in memory, so that the contact loop's partner reads and force writes hit the cache.
// The order is that of a Morton (Z-order) curve through cells of the interaction range: a curve
// visits a block of 2^k x 2^k x 2^k cells before it leaves it, so the partners of a particle lie
// within a few blocks of it in memory on every axis (x-fastest cell order keeps them close along
// x only: the partner one cell up in z sits a whole plane of cells further on). LAMMPS sorts by
// bins for the same reason (atom_modify sort); a fluidised bed mixes within seconds, so a store
// sorted once at the start loses its order and must be sorted again periodically.
#pragma once
#include <cstdint>
#include <vector>

#include "neighbour/neighbour_list.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// 64-bit Morton code of cell (cx, cy, cz), each coordinate < 2^21: bit b of cx goes to bit 3b.
std::uint64_t morton_code(std::uint32_t cx, std::uint32_t cy, std::uint32_t cz);

/// The new order of the particles (new index k takes old particle new_to_old[k]): ascending
/// Morton code of each particle's cell (cubes of side `cell_size` from box.lo; periodic axes
/// wrapped into the box, closed axes clamped), ties by ascending index. Deterministic; does not
/// depend on the thread count.
std::vector<std::uint32_t> spatial_order(const ParticleStore& p, const BoxGeometry& box,
                                         double cell_size);

} // namespace fluidem
