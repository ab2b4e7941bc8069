// The conservative non-contact forces (van der Waals, electrostatics; noncontact/pair_forces.hpp)
// as a force source evaluated at every particle step. Its potential energy is part of e_pot, so
// that the energy balance of an elastic, undamped system with these forces closes.
#pragma once
#include <numeric>
#include <string_view>

#include "integrate/force_sources.hpp"
#include "noncontact/pair_forces.hpp"

namespace fluidem {

class NonContactForceSource final : public StepForceSource {
public:
  NonContactForceSource(const BoxGeometry& box, const NonContactSpec& spec, const ParticleStore& p,
                        double skin)
      : forces_of_(box, spec, p, skin) {}
  std::string_view name() const override { return "non-contact"; }
  EnergyRole energy_role() const override { return EnergyRole::Conservative; }
  void evaluate(const ParticleStore& p, double /*t*/) override {
    forces_of_.compute(p, forces_, potential_);
  }
  /// At the positions of the last evaluation (the step's), J.
  double potential_energy(const ParticleStore&) const override {
    return std::accumulate(potential_.begin(), potential_.end(), 0.0);
  }
  const ConservativePairForces& pair_forces() const { return forces_of_; }

private:
  void permuted(const std::vector<std::uint32_t>& new_to_old) override {
    forces_of_.permute(new_to_old);
    if (potential_.size() != new_to_old.size()) return;
    const std::vector<double> old = potential_;
    for (std::size_t k = 0; k < new_to_old.size(); ++k) potential_[k] = old[new_to_old[k]];
  }
  ConservativePairForces forces_of_;
  std::vector<double> potential_; ///< each particle's share, J
};

} // namespace fluidem
