// Pouring of 500 discs into a container [Hoomans96 §5.1] with the event-driven hard-sphere
// engine: cases/hoomans96/pouring_hard.toml run to its end_time (0.5 s; the bed has settled).
//
// Checks and tolerances:
// * Energy housekeeping [Hoomans96 §5.1]: e_kin + e_rot + e_pot + e_dsp (dissipated in
//   collisions, cumulative) equals its initial value within 5e-5 relative (the paper reached
//   0.005%). The engine flies particles on exact parabolas and books each collision's loss
//   exactly, so what remains is round-off (measured ~1e-14).
// * Settled area fraction ("area under the upper layers of particles") in [0.80, 0.85]:
//   Hoomans et al. report 0.832 +- 0.010 for their hard-sphere model.
// * Settled: kinetic energy at the end below 1e-5 of the initial potential energy (the bed
//   rattles at impact speeds below hardsphere.elastic_below; see hard_sphere_engine_test (d)).
// * Dissipation happened: e_dsp is more than 30% of the initial potential energy (the discs
//   fall through ~half the container and come to rest).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "analysis/energies.hpp"
#include "hardsphere/hard_sphere_engine.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

double energy_sum(const Simulation& sim) {
  const Energies e = sim.energies();
  return e.kinetic + e.rotational + e.potential + sim.dissipated_energy();
}

TEST(PouringHard, Hoomans96EnergyHousekeepingAndSettledBed) {
  const CaseSpec spec =
      read_case_file(std::string(FLUIDEM_SOURCE_DIR) + "/cases/hoomans96/pouring_hard.toml");
  Simulation sim(spec);
  ASSERT_NE(sim.hard_sphere(), nullptr);
  ASSERT_EQ(sim.particles().size(), 500u);
  const double e0 = energy_sum(sim);
  const double epot0 = sim.energies().potential;
  ASSERT_GT(epot0, 0.0);

  const long steps = std::lround(spec.simulation.end_time / sim.time_step());
  sim.advance(steps);

  const Energies end = sim.energies();
  const double drift = (energy_sum(sim) - e0) / e0;
  const double phi = settled_area_fraction(sim.particles(), 0.0, 0.096, 0.0);
  const double settled = end.kinetic / epot0;
  const auto& st = sim.hard_sphere()->stats();
  std::cout << fmt::format(
      "pouring_hard: {} steps of {:.1e} s; {} collisions ({} wall, {} TC-elastic, {} "
      "slow-elastic); area fraction {:.4f} (published 0.832 +- 0.010); energy sum drift "
      "{:+.3e} of E0 (limit 5e-5); e_kin(end)/e_pot(0) = {:.3e}; e_dsp/e_pot(0) = {:.4f}; "
      "energy kept by TC/slow rules {:.3e} of e_pot(0)\n",
      steps, sim.time_step(), st.collisions, st.wall_collisions, st.tc_elastic, st.slow_elastic,
      phi, drift, settled, sim.dissipated_energy() / epot0, st.tc_energy_kept / epot0);
  RecordProperty("area_fraction", fmt::format("{:.5f}", phi));
  RecordProperty("energy_drift", fmt::format("{:.4e}", drift));
  RecordProperty("collisions", std::to_string(st.collisions));

  EXPECT_LT(std::abs(drift), 5e-5);
  EXPECT_GE(phi, 0.80);
  EXPECT_LE(phi, 0.85);
  EXPECT_LT(settled, 1e-5);
  EXPECT_GT(sim.dissipated_energy() / epot0, 0.3);
}

} // namespace
} // namespace fluidem
