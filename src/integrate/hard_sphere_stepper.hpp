// The event-driven hard-sphere engine's flow step [Hoomans96 Fig. 7]: the held forces of the
// sources (the gas: drag and pressure) as one velocity kick, then the collision sequence of DT
// with the particles on exact parabolas under gravity. A space-varying body force (`[body_force]`)
// cannot be flown on exact parabolas: it acts as two half kicks around the collision sequence
// (kick-drift-kick, second order in DT), each with the acceleration at the particle's position
// at the time, like the gas forces which act as one kick per DT.
// Every sort_interval-th list build, the store is sorted in space (neighbour/spatial_order.hpp)
// after the step, for the memory locality of the partner reads, as the soft-sphere engine does.
#pragma once
#include <memory>

#include "hardsphere/hard_sphere_engine.hpp"
#include "integrate/force_sources.hpp"
#include "integrate/particle_stepper.hpp"

namespace fluidem {

class HardSphereStepper final : public ParticleStepper {
public:
  /// p and forces outlive the stepper. Sources evaluated every step (StepForceSource) have no
  /// place in a collision sequence: ForceSources with one is refused (std::logic_error).
  HardSphereStepper(const CaseSpec& spec, const BoxGeometry& box, double dt, ParticleStore& p,
                    ForceSources& forces, bool record_collisions);

  void step(double t, const StepNeeds& needs) override;
  void finish_kick() override {}
  double dissipated_energy() const override { return engine_.stats().dissipated; }
  const ContactStats& contact_stats() const override { return no_contacts_; }
  Seconds seconds() const override { return {t_collisions_, 0.0, 0.0}; }
  std::size_t bytes() const override { return engine_.bytes(); }

  /// Spatial sorts of the store done by this stepper (neighbour.sort_interval).
  long sorts() const { return sorts_; }
  const HardSphereEngine& engine() const { return engine_; }
  HardSphereEngine& engine() { return engine_; }

private:
  /// v += h a(x) for every moving particle: the body-force field at its position (none: no-op).
  void body_force_kick(double h);
  /// Sorts the store in space; the forces and the engine follow.
  void sort();

  ParticleStore& p_;
  ForceSources& forces_;
  HardSphereEngine engine_;
  BoxGeometry box_;
  double dt_;
  int sort_interval_;
  long sorts_ = 0;
  ContactStats no_contacts_;
  double t_collisions_ = 0.0;
};

} // namespace fluidem
