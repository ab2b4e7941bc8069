// A soft-sphere run steps at a fraction of its shortest contact [Deen07 eq. 40-42]. A contact so
// short that a stable run to simulation.end_time would need more than the allowed number of
// steps (a diameter of 1e-300 m, a stiffness of 1e300 N/m) is refused here, before the particles
// are inserted, naming the input that makes it short and the value that would do, rather than
// simulation.time_step, which the case may not even set.
//
// Which input is named: the contact's inputs (the diameters and densities of its species, the
// linear stiffness or the Young's moduli of its materials) are compared with the ranges met in
// practice, 1 um to 1 m, 1 to 1e5 kg/m^3, 1 to 1e10 N/m, 1 kPa to 1.2 TPa (diamond); the one
// farthest outside its range is named, and simulation.end_time when all are inside.
#pragma once
#include "contact/contact_table.hpp"
#include "core/case_spec.hpp"

namespace fluidem {

/// InputError when the shortest contact of `table` is not a positive finite duration, or when a
/// run to end_time at the automatic step (simulation.time_step_fraction of it; with a given
/// time_step, the largest stable step, 1 / min_steps_per_contact of it) would take more than
/// max_steps steps. Nothing is checked with simulation.force_time_step.
void check_contact_durations(const CaseSpec& spec, const ContactTable& table,
                             double min_steps_per_contact, double max_steps);

} // namespace fluidem
