// The conservative non-contact forces (van der Waals, electrostatics; pair_forces.hpp) over
// rank-independent rows (neighbour/ordered_rows.hpp): each own particle sums its partners in
// ascending id, then its walls in face order, skipping those out of range, with the pair and
// wall terms of the single-process evaluation. The sum is a function of the particle's partners
// alone, the same on any rank, with any ghosts around it and any store order (docs/parallel.md).
#pragma once
#include <vector>

#include "core/noncontact_settings.hpp"
#include "neighbour/ordered_rows.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// The forces on the rows' own particles (the first rows.owned() of p), N, 3 per particle into
/// f, and each one's share of the potential energy, J, into u (half of each pair's, its walls'
/// whole). Resized; overwritten. The rows' reach must be noncontact_reach(spec, ...).
void ordered_noncontact_forces(const NonContactSpec& spec, const OrderedRows& rows,
                               const ParticleStore& p, std::vector<double>& f,
                               std::vector<double>& u);

} // namespace fluidem
