// The time steps of a run. Soft spheres: a fraction of the shortest contact that can happen
// [Deen07 eq. 41-42], at least kMinStepsPerContact steps per contact unless forced; with gas, the
// DEM step shortened so that a whole number of steps fills the flow step DT. Hard spheres: the
// flow step DT of the collision sequence [Hoomans96 Fig. 3]. An automatic step is shortened so
// that a whole number of steps ends exactly at end_time.
#pragma once
#include "contact/contact_table.hpp"
#include "core/case_spec.hpp"
#include "neighbour/box_geometry.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// At least this many particle steps per contact: below it the run is refused unless forced.
inline constexpr double kMinStepsPerContact = 10.0;
/// A run of more steps than this would not end in any useful time: refused.
inline constexpr double kMaxSteps = 1e12;

struct TimeSteps {
  double dt = 0.0;         ///< particle step, s
  double flow_dt = 0.0;    ///< gas step DT, s (0: no gas)
  long steps_per_flow = 1; ///< particle steps per DT (soft spheres)
  double stable_dt = 0.0;  ///< largest accepted soft-sphere step, s (hard spheres: 0)
  bool forced = false;     ///< dt above stable_dt (simulation.force_time_step)
};

/// The steps of the case for the particles p; the soft-sphere DEM gives its contact table, the
/// hard-sphere engine none. The resolved steps are written back into spec (simulation.time_step,
/// gas.time_step), so that case.resolved.toml reproduces the run. InputError naming the key for
/// a step above the stability limit, gas.time_step in a hard-sphere run or too many steps.
TimeSteps choose_time_steps(CaseSpec& spec, const ParticleStore& p, const ContactTable* table);

/// `spec` with each species' diameter lowered to the smallest one its [[insert]] blocks' size
/// distributions can draw (particles/size_distribution.hpp): the species' contact durations are
/// then those of its smallest particles, which the time step must resolve (the contact
/// coefficients do not depend on the diameter: contact_table.hpp).
CaseSpec with_smallest_diameters(const CaseSpec& spec);

/// The domain as the neighbour lists and guards see it.
BoxGeometry box_from(const CaseSpec& spec);

/// The shortest contact duration of the contacts that can happen among p, s (infinity: none).
double shortest_possible_contact(const CaseSpec& spec, const ParticleStore& p,
                                 const ContactTable& t);

/// Overlap under the bed's own weight against the floor, / diameter (`fluidem check`).
double expected_overlap_ratio(const CaseSpec& spec, const ParticleStore& p, const ContactTable& t);

} // namespace fluidem
