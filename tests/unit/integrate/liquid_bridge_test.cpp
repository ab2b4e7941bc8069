// Liquid bridges in a run (noncontact/liquid_bridges.hpp): a wet sphere pulled away from a fixed
// wet sphere it touches, heavy enough that the bridge barely slows it (quasi-static: the
// capillary force depends on the gap alone).
//  - The bridge forms at contact and ruptures at the rupture distance S_c = (1 + theta/2) V^(1/3)
//    (Lian et al. 1993) of the bridge volume V = V_i + V_j (one bridge each, Yang et al. 2003):
//    within one step's travel.
//  - The kinetic energy it takes is the bridge energy, the integral of Willett's force from
//    contact to rupture (noncontact/kernels/liquid_bridge.hpp, checked against an independent
//    mpmath quadrature in tests/unit/noncontact/kernels_test.cpp): the force switches on and
//    off within a step, so the work differs by at most (F(0) + F(S_c)) v dt / 2; e_dsp books
//    it (the work with the full-step velocities) within the same bound. Twice, at dt and dt/4:
//    the bound, and the error, shrink with the step.
//  - With a viscous liquid the extra loss is the viscous force's work (its closed form at constant
//    speed, 2%), and e_total still closes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"
#include "noncontact/kernels/liquid_bridge.hpp"
#include "noncontact/liquid_bridges.hpp"

namespace fluidem {
namespace {

constexpr double kD = 0.001, kRho = 1e7, kGamma = 0.0728, kFraction = 1e-3, kV0 = 0.01;
constexpr double kC = 0.05;

std::string case_text(double viscosity) {
  const double h = 0.5 * kD, overlap = 1e-9;
  const double xb = kC + kD - overlap;
  std::string s = fmt::format(
      "[simulation]\nend_time = 1.0\ngravity = [0.0, 0.0, 0.0]\n\n[domain]\nlo = [0.0, 0.0, 0.0]\n"
      "hi = [0.1, 0.1, 0.1]\n\n[[species]]\nname = \"wet\"\ndiameter = {d}\ndensity = {rho}\n"
      "friction = 0.0\nliquid_fraction = {phi}\n\n"
      "[[insert]]\nspecies = \"wet\"\ncount = 1\nplacement = \"lattice\"\nfixed = true\n"
      "region = {{ lo = [{a0:.17g}, {c0:.17g}, {c0:.17g}], hi = [{a1:.17g}, {c1:.17g}, {c1:.17g}] "
      "}}\n\n"
      "[[insert]]\nspecies = \"wet\"\ncount = 1\nplacement = \"lattice\"\n"
      "region = {{ lo = [{b0:.17g}, {c0:.17g}, {c0:.17g}], hi = [{b1:.17g}, {c1:.17g}, {c1:.17g}] "
      "}}\n"
      "velocity = [{v0}, 0.0, 0.0]\n\n[contact]\nnormal = \"hertz\"\n\n"
      "[liquid_bridge]\nsurface_tension = {g}\nviscosity = {mu}\nwalls = false\n",
      fmt::arg("d", kD), fmt::arg("rho", kRho), fmt::arg("phi", kFraction), fmt::arg("a0", kC - h),
      fmt::arg("a1", kC + h), fmt::arg("b0", xb - h), fmt::arg("b1", xb + h),
      fmt::arg("c0", kC - h), fmt::arg("c1", kC + h), fmt::arg("v0", kV0), fmt::arg("g", kGamma),
      fmt::arg("mu", viscosity));
  if (viscosity > 0.0) s += "min_gap = 1e-6\n";
  return s;
}

double total_energy(const Simulation& sim) {
  const Energies e = sim.energies();
  return e.kinetic + e.rotational + e.potential + sim.contact_stats().elastic_energy +
         sim.dissipated_energy();
}

const double kR = 0.5 * kD;
const double kLiquid = kFraction * 4.0 / 3.0 * std::numbers::pi * kR * kR * kR;
const double kVolume = 2.0 * kLiquid; // one bridge on each sphere: V_i / 1 + V_j / 1

TEST(LiquidBridges, PulledApartQuasiStaticallyTheBridgeTakesItsEnergyAndRupturesAtSc) {
  for (const double refine : {1.0, 4.0}) {
    CaseSpec spec = read_case_string(case_text(0.0), "bridge.toml");
    const double dt = Simulation(spec).time_step() / refine;
    spec.simulation.time_step = dt;
    Simulation sim(spec);
    const ParticleStore& p = sim.particles();
    ASSERT_EQ(p.size(), 2u);
    ASSERT_NE(sim.liquid_bridges(), nullptr);
    EXPECT_EQ(sim.liquid_bridges()->bridge_count(), 1) << "formed at contact";
    const double s_c = kernels::liquid_bridge_rupture_distance(kVolume, 0.0);
    const double energy = kernels::liquid_bridge_energy(kR, kR, kVolume, 0.0, kGamma);
    const double e0 = total_energy(sim), k0 = sim.energies().kinetic;
    double rupture_gap = -1.0;
    for (long step = 0; step < 10000000; ++step) {
      sim.advance(1);
      if (sim.liquid_bridges()->bridge_count() == 0) {
        rupture_gap = p.x[1] - p.x[0] - kD;
        break;
      }
    }
    ASSERT_GE(rupture_gap, 0.0) << "the bridge ruptured";
    EXPECT_NEAR(rupture_gap, s_c, kV0 * dt * 1.01) << "at S_c, within one step's travel";
    // The force acts from the step it forms at to the step it ruptures at, half a step short
    // or long at each end: the work differs from the integral by at most
    // (F(0) + F(S_c)) v dt / 2, as does the work booked with the full-step velocities.
    const double f0 = -kernels::liquid_bridge_capillary(kR, kR, kVolume, 0.0, kGamma, 0.0).force;
    const double fc =
        -kernels::liquid_bridge_capillary(kR, kR, kVolume, 0.0, kGamma, 0.999999 * s_c).force;
    const double bound = 0.5 * (f0 + fc) * kV0 * dt;
    const double taken = k0 - sim.energies().kinetic;
    EXPECT_NEAR(taken, energy, bound) << "the work of the bridge is its energy; dt = " << dt;
    EXPECT_NEAR(total_energy(sim), e0, bound) << "e_dsp books it";
    EXPECT_LT(bound, 0.02 * energy) << "a tight bound";
  }
}

TEST(LiquidBridges, AViscousBridgeTakesMoreAndTheBalanceStillCloses) {
  Simulation wet(read_case_string(case_text(1e-3), "viscous.toml"));
  const double e0 = total_energy(wet), k0 = wet.energies().kinetic;
  const double energy = kernels::liquid_bridge_energy(kR, kR, kVolume, 0.0, kGamma);
  long steps = 0;
  while (wet.liquid_bridges()->bridge_count() > 0 && steps < 10000000) wet.advance(1), ++steps;
  const double taken = k0 - wet.energies().kinetic;
  // The viscous work at the (nearly constant) speed v0: the integral of 6 pi mu R*^2 v /
  // max(S, S_min) from 0 to S_c, 6 pi mu R*^2 v (1 + ln(S_c / S_min)); v falls by 1.4% on the
  // way (the bridge takes 2.7% of e_kin): 2% of it, plus the capillary part's bound.
  const double s_c = kernels::liquid_bridge_rupture_distance(kVolume, 0.0), s_min = 1e-6;
  const double r_eff = 0.5 * kR;
  const double viscous =
      6.0 * std::numbers::pi * 1e-3 * r_eff * r_eff * kV0 * (1.0 + std::log(s_c / s_min));
  const double f0 = -kernels::liquid_bridge_capillary(kR, kR, kVolume, 0.0, kGamma, 0.0).force;
  EXPECT_NEAR(taken - energy, viscous, 0.02 * viscous + f0 * kV0 * wet.time_step())
      << "the viscous force takes its share";
  EXPECT_NEAR(total_energy(wet), e0, f0 * kV0 * wet.time_step()) << "e_dsp books both";
}

} // namespace
} // namespace fluidem
