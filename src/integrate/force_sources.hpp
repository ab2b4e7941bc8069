// The forces on the particles, as the list the set-up assembles from the case. Newton's second
// law of a particle [Deen07 eq. 17-18; Zhu07 eq. 1-2]:
//   m_i dv_i/dt = F_contact,i + sum_s F_s,i + m_i (g + a(x_i)),   I_i dw_i/dt = T_contact,i,
// with the contacts from the contact loop (or the collision operator), g uniform (gravity), a(x)
// a body-force field, and F_s the per-particle forces of the sources s (the gas: drag and
// pressure; next the non-contact and fluid forces). The steppers see only the sums: a new source
// is a ForceSource added at set-up, and no stepper changes.
//
// Energy: e_total = e_kin + e_rot + e_pot + e_el + e_dsp stays constant up to the integration
// error when the sources keep their books: a conservative source reports its potential energy
// (added to e_pot), a dissipative one has its work -dt sum_i F_i . v_i with the full-step
// velocities added to e_dsp (the rule of the contacts' dashpots, ARCHITECTURE.md "One time
// step"), and an external one (the gas) does work that the balance leaves out (docs/output.md).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "core/body_force.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// What a source's work is to the energy balance.
enum class EnergyRole {
  Conservative, ///< reports its potential energy (part of e_pot)
  Dissipative,  ///< its work with the full-step velocities goes into e_dsp
  External      ///< work from outside the particle system (the gas): not in e_total
};

/// A force on each particle (N per particle and axis).
class ForceSource {
public:
  virtual ~ForceSource() = default;
  virtual std::string_view name() const = 0;
  virtual EnergyRole energy_role() const = 0;
  /// The force on particle i along `axis` is force(axis)[i]; nullptr before its first
  /// evaluation (no force yet).
  virtual const double* force(int axis) const = 0;
  /// The torque on particle i about `axis` is torque(axis)[i], N m; nullptr: the source exerts
  /// none (or none yet).
  virtual const double* torque(int /*axis*/) const { return nullptr; }
  /// Conservative sources: the potential energy of the particles' configuration, J.
  virtual double potential_energy(const ParticleStore&) const { return 0.0; }
  /// The particles were reordered (ParticleStore::permute with the same new_to_old).
  virtual void permute(const std::vector<std::uint32_t>& new_to_old) = 0;
};

/// A source evaluated at every particle step, like the contacts: at the new positions with the
/// half-step velocities (velocity Verlet). Its forces are its state (kept in checkpoints).
class StepForceSource : public ForceSource {
public:
  /// Fills forces() for the particles of p at time t (every moving particle; fixed particles
  /// feel nothing whatever is written).
  virtual void evaluate(const ParticleStore& p, double t) = 0;
  const double* force(int axis) const final {
    const auto& f = forces_[static_cast<std::size_t>(axis)];
    return f.empty() ? nullptr : f.data();
  }
  /// Permutes the forces, then tells the source (permuted()).
  void permute(const std::vector<std::uint32_t>& new_to_old) final;
  std::array<std::vector<double>, 3>& forces() { return forces_; }
  const std::array<std::vector<double>, 3>& forces() const { return forces_; }

protected:
  /// The particles were reordered (after the forces were): a source with per-particle state
  /// reorders it.
  virtual void permuted(const std::vector<std::uint32_t>& /*new_to_old*/) {}
  std::array<std::vector<double>, 3> forces_; ///< N, per particle
};

/// The list. Uniform accelerations (gravity) and the body-force field act per unit mass; the
/// sources' forces are summed into one array per axis (read directly when there is one source:
/// the sum of one term is that term, bitwise).
class ForceSources {
public:
  explicit ForceSources(const std::array<double, 3>& gravity, const BodyForceSpec* field = nullptr)
      : gravity_(gravity), field_(field) {}

  void add(ForceSource* source); ///< not owned; lives as long as the list
  void add(std::unique_ptr<ForceSource> source);

  const std::array<double, 3>& gravity() const { return gravity_; }
  const BodyForceSpec* field() const { return field_; }
  /// Whether any source is in the list.
  bool any_particle_forces() const { return !sources_.empty(); }
  /// Whether any source is dissipative (its work is booked after each finished second kick).
  bool books_work() const { return books_work_; }
  /// Whether any source is evaluated every step (StepForceSource).
  bool any_step_sources() const { return !step_sources_.empty(); }
  /// The summed force along `axis` per particle, N (nullptr: none yet). Current after refresh().
  const double* total(int axis) const;
  /// The summed torque about `axis` per particle, N m (nullptr: no source exerts one). Current
  /// after refresh().
  const double* total_torque(int axis) const;
  /// Sums the sources' forces again (after any source changed them); n particles.
  void refresh(std::size_t n);
  /// Evaluates the StepForceSources at the particles' state, then refresh().
  void evaluate_step_sources(const ParticleStore& p, double t);
  /// Sum of the conservative sources' potential energies, J.
  double potential_energy(const ParticleStore& p) const;
  /// -dt sum_i F_i . v_i of the dissipative sources with p's velocities (serial, fixed order).
  double dissipated_work(const ParticleStore& p, double dt) const;
  void permute(const std::vector<std::uint32_t>& new_to_old);
  /// v_i += dt F_i / m_i with the summed forces, w_i += dt T_i / I_i with the summed torques (the
  /// hard-sphere engine's kick per flow step).
  void kick(ParticleStore& p, double dt) const;
  const std::vector<StepForceSource*>& step_sources() const { return step_sources_; }

private:
  std::array<double, 3> gravity_;
  const BodyForceSpec* field_;
  std::vector<ForceSource*> sources_;
  std::vector<StepForceSource*> step_sources_;
  std::vector<std::unique_ptr<ForceSource>> owned_;
  bool books_work_ = false;
  std::array<std::vector<double>, 3> sum_; ///< with two sources or more
  /// Summed torques: with torques from two sources or more (else the one source's, read directly)
  std::array<std::vector<double>, 3> torque_sum_;
  const ForceSource* torque_source_ = nullptr; ///< the one source with torques, if one
  int torque_sources_ = 0;                     ///< how many sources exert torques
};

} // namespace fluidem
