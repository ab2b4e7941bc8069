// Spatial sorting of the particle store for memory locality: particles close in space are put
// close in memory, so that the contact loop's partner reads and force writes hit the cache.
// The order follows the contact loop's slabs (neighbour_list.hpp): slab by slab along the slab
// axis (the axis over which the particles spread across the most cells, the neighbour list's
// own rule), and within a slab, one cell thick, along a Morton (Z-order) curve through its cells
// (the curve visits a block of 2^k x 2^k cells before it leaves it, so a particle's partners lie
// within a few blocks of it in memory on both axes). Slab-major order keeps the particles of a
// slab contiguous: the two threads of the slab-parallel contact loop then write to separate
// memory (a plain 3-D Morton order interleaves the slabs in memory, and the threads then share
// cache lines). LAMMPS sorts by bins for the same reason (atom_modify sort);
// a fluidised bed mixes within seconds, so the store must be sorted again periodically.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "neighbour/neighbour_list.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// The slab axis of cells spanning cmin..cmax: the axis of the largest span, the lowest of tied
/// ones (NeighbourList::build's rule).
int slab_axis(const std::array<std::uint32_t, 3>& cmin, const std::array<std::uint32_t, 3>& cmax);

/// 64-bit Morton code of cell (cx, cy, cz), each coordinate < 2^21: bit b of cx goes to bit 3b.
std::uint64_t morton_code(std::uint32_t cx, std::uint32_t cy, std::uint32_t cz);

/// The new order of the particles (new index k takes old particle new_to_old[k]) over cells of
/// side `cell_size` from box.lo (floor(length / cell_size) per axis, as the neighbour list's;
/// periodic axes wrapped into the box, closed axes clamped): ascending cell index along the slab
/// axis, then ascending Morton code of the cell's coordinates on the other two axes (lower axis
/// first), then ascending index. Deterministic; does not depend on the thread count.
std::vector<std::uint32_t> spatial_order(const ParticleStore& p, const BoxGeometry& box,
                                         double cell_size);

} // namespace fluidem
