// What the scheduler (Simulation) asks of a particle engine: advance the particles one time step
// with the forces of the list (force_sources.hpp), and say what the step left behind. Two
// engines implement it: the soft-sphere DEM (soft_sphere_stepper.hpp: velocity Verlet with the
// contact loop) and the event-driven hard spheres (hard_sphere_stepper.hpp).
#pragma once
#include "contact/contact_forces.hpp"

namespace fluidem {

/// What the scheduler needs of one step beyond the new state.
struct StepNeeds {
  /// The step's second half kick may wait for the next step (bitwise the same); the caller then
  /// reads no velocity, energy or dissipated energy before finish_kick().
  bool defer_second_kick = false;
  /// Record the step's contacts (ContactRecord) for an analysis.
  bool record_contacts = false;
  /// The continuum averages sample this step: the step ends with full-step velocities.
  bool sample_continuum = false;
};

class ParticleStepper {
public:
  virtual ~ParticleStepper() = default;
  /// One step from time t.
  virtual void step(double t, const StepNeeds& needs) = 0;
  /// Finishes a second half kick a step left pending (none: nothing to do); afterwards the
  /// particle store holds the full-step state.
  virtual void finish_kick() = 0;
  /// Energy dissipated since t = 0 (collisions, dashpots, friction, dissipative sources), J.
  virtual double dissipated_energy() const = 0;
  /// The last step's contacts (soft spheres; zeros for hard spheres, whose collisions are
  /// counted by the engine).
  virtual const ContactStats& contact_stats() const = 0;
  /// Seconds spent in the contacts (or collisions), the integration and the neighbour lists.
  struct Seconds {
    double contacts = 0.0, integration = 0.0, neighbour = 0.0;
    double step_sources = 0.0; ///< the force sources evaluated every step (non-contact forces)
  };
  virtual Seconds seconds() const = 0;
  /// Bytes held per particle by the engine (beyond the particle store).
  virtual std::size_t bytes() const = 0;
};

} // namespace fluidem
