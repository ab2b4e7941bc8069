// The liquid bridges (noncontact/liquid_bridges.hpp) as a force source evaluated at every
// particle step. Dissipative: the bridge forms at contact and ruptures at a finite force, so its
// capillary force does net work over a cycle, and its viscous force dissipates; the work of the
// whole bridge force with the full-step velocities goes into e_dsp (a rupture's loss, the bridge
// energy, is booked as the pair separates), which keeps e_total constant.
#pragma once
#include <string_view>

#include "integrate/force_sources.hpp"
#include "noncontact/liquid_bridges.hpp"

namespace fluidem {

class LiquidBridgeSource final : public StepForceSource {
public:
  LiquidBridgeSource(const BoxGeometry& box, const LiquidBridgeSpec& spec,
                     std::vector<double> liquid_fraction, const ParticleStore& p, double skin)
      : bridges_(box, spec, std::move(liquid_fraction), p, skin) {}
  std::string_view name() const override { return "liquid bridges"; }
  EnergyRole energy_role() const override { return EnergyRole::Dissipative; }
  void evaluate(const ParticleStore& p, double /*t*/) override { bridges_.compute(p, forces_); }
  LiquidBridges& bridges() { return bridges_; }
  const LiquidBridges& bridges() const { return bridges_; }

private:
  void permuted(const std::vector<std::uint32_t>& new_to_old) override {
    bridges_.permute(new_to_old);
  }
  LiquidBridges bridges_;
};

} // namespace fluidem
