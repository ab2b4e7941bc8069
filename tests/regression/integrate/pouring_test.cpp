// Pouring of 500 discs into a container [Hoomans96 §5.1]: the demo case
// cases/hoomans96/pouring_soft.toml run to its end_time (1 s, the bed has settled).
//
// Checks and tolerances:
// * Settled area fraction ("area under the upper layers of particles") in [0.80, 0.85]:
//   Hoomans et al. report 0.832 +- 0.010 for their hard-sphere model, against 0.80 (Hoogue &
//   Newland) and 0.805 (Rosato) from other authors; the band covers all three.
// * Energy balance: e_kin + e_rot + e_pot + e_el + e_dsp (dissipated, cumulative) equals its
//   initial value (the potential energy of the particles at rest) within 0.5% at the end: the
//   dissipation is booked exactly, what remains is the integration error.
// * Settled: kinetic energy at the end below 1e-6 of the initial potential energy.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "analysis/energies.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

double energy_sum(const Simulation& sim) {
  const Energies e = sim.energies();
  return e.kinetic + e.rotational + e.potential + sim.contact_stats().elastic_energy +
         sim.dissipated_energy();
}

TEST(Pouring, Hoomans96SettledBed) {
  const CaseSpec spec =
      read_case_file(std::string(FLUIDEM_SOURCE_DIR) + "/cases/hoomans96/pouring_soft.toml");
  Simulation sim(spec);
  ASSERT_EQ(sim.particles().size(), 500u);
  const Energies start = sim.energies();
  const double e0 = energy_sum(sim);
  const double epot0 = start.potential;
  ASSERT_GT(epot0, 0.0);

  const long steps = std::lround(spec.simulation.end_time / sim.time_step());
  sim.advance(steps);

  const Energies end = sim.energies();
  const double drift = (energy_sum(sim) - e0) / e0;
  const double phi = settled_area_fraction(sim.particles(), 0.0, 0.096, 0.0);
  const double settled = end.kinetic / epot0;
  const double dissipated = sim.dissipated_energy() / epot0;
  std::cout << fmt::format(
      "pouring_soft: {} steps of {:.4e} s; area fraction {:.4f} (published 0.832 +- 0.010); "
      "energy sum drift {:+.4e} of E0; e_kin(end)/e_pot(0) = {:.3e}; e_dsp/e_pot(0) = {:.4f}; "
      "e_pot drop/e_pot(0) = {:.4f}\n",
      steps, sim.time_step(), phi, drift, settled, dissipated, (epot0 - end.potential) / epot0);
  RecordProperty("area_fraction", fmt::format("{:.5f}", phi));
  RecordProperty("energy_drift", fmt::format("{:.4e}", drift));
  RecordProperty("kinetic_over_initial_potential", fmt::format("{:.4e}", settled));

  EXPECT_GE(phi, 0.80);
  EXPECT_LE(phi, 0.85);
  EXPECT_LT(std::abs(drift), 0.005);
  EXPECT_LT(settled, 1e-6);
}

} // namespace
} // namespace fluidem
