// Particle insertion from the case's [[insert]] blocks: random sequential addition without
// overlap, a simple lattice, or positions read from a LAMMPS data file ("Atoms # sphere":
// id type diameter density x y z). In 2-D every centre lies at the mid-plane y.
#pragma once
#include "core/case_spec.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// Insert every block in order. Throws InputError naming the block (insert[k].key) when the
/// particles do not fit, a file is malformed, a particle lies outside the domain, or two
/// particles overlap by more than simulation.insertion_overlap_tolerance x the smaller diameter.
void insert_particles(const CaseSpec& spec, ParticleStore& store);

} // namespace fluidem
