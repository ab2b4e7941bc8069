// Particle insertion from the case's [[insert]] blocks: random sequential addition without
// overlap, a simple lattice, or positions read from a LAMMPS data file ("Atoms # sphere":
// id type diameter density x y z; an optional "Velocities" section: id vx vy vz wx wy wz). In
// 2-D every centre lies at the mid-plane y. Each block's particles get its velocity (and
// spread) and angular velocity, or the file's; a block with fixed = true holds its particles in
// place (ParticleStore::fix).
#pragma once
#include "core/case_spec.hpp"
#include "core/memory_budget.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// Insert every block in order. Throws InputError naming the block (insert[k].key) when the
/// particles do not fit, a file is malformed, a particle lies outside the domain, two
/// particles overlap by more than simulation.insertion_overlap_tolerance x the smaller diameter,
/// or a fixed particle overlaps a wall.
void insert_particles(const CaseSpec& spec, ParticleStore& store);

/// Memory of a run per particle, bytes: the particle arrays, the neighbour list and its contact
/// history, the output buffers (a run reports what it used: "memory N bytes per particle").
inline constexpr double kBytesPerParticle = 1000.0;
/// The share of the particles the [[insert]] blocks ask for (a file's are counted as it is read),
/// keyed to the block asking the most.
MemoryShare particle_memory_share(const CaseSpec& spec);

} // namespace fluidem
