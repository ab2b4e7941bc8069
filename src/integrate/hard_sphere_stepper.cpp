#include "integrate/hard_sphere_stepper.hpp"
#include "integrate/wall_clock.hpp"
#include "neighbour/spatial_order.hpp"

#include <stdexcept>

namespace fluidem {

HardSphereStepper::HardSphereStepper(const CaseSpec& spec, const BoxGeometry& box, double dt,
                                     ParticleStore& p, ForceSources& forces, bool record_collisions)
    : p_(p), forces_(forces), engine_(spec, box), box_(box), dt_(dt),
      sort_interval_(spec.neighbour.sort_interval) {
  engine_.set_record_collisions(record_collisions);
}

void HardSphereStepper::step(double t, const StepNeeds&) {
  if (forces_.any_step_sources())
    throw std::logic_error("HardSphereStepper: a force evaluated every step has no place in an "
                           "event-driven collision sequence");
  forces_.kick(p_, dt_); // the held forces over DT as one kick [Hoomans96 Fig. 7]
  body_force_kick(0.5 * dt_);
  const auto t0 = WallClock::now();
  engine_.advance(p_, t, dt_, forces_.gravity());
  body_force_kick(0.5 * dt_);
  // (after a build: the list builds, checkpointed, decide, so restarts sort at the same steps)
  if (sort_interval_ > 0 && engine_.built_last_step() &&
      engine_.list_builds() % sort_interval_ == 0)
    sort();
  t_collisions_ += seconds_since(t0);
}

void HardSphereStepper::sort() {
  const std::vector<std::uint32_t> order = spatial_order(p_, box_, engine_.cell_size());
  p_.permute(order);
  forces_.permute(order);
  engine_.permute(order);
  ++sorts_;
}

void HardSphereStepper::body_force_kick(double h) {
  const BodyForceSpec* b = forces_.field();
  if (b == nullptr) return;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (p_.fixed(i)) continue;
    const auto a = body_acceleration(*b, p_.x[i], p_.y[i], p_.z[i]);
    p_.vx[i] += h * a[0];
    p_.vy[i] += h * a[1];
    p_.vz[i] += h * a[2];
  }
}

} // namespace fluidem
