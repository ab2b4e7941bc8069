// The deferred second half kick (Simulation::step, integrate/simulation.cpp): between steps
// whose velocities nobody reads, a step's second half kick of velocity Verlet is done in the
// next step's first pass over the particles (v + dv, its dissipation term, + dv, drift) instead
// of in a pass of its own. The reference is the undeferred integrator itself: N steps taken as
// advance(N) (every step but the last deferred) must leave the particles' positions,
// velocities and angular velocities, the dissipated energy and the contact forces bitwise those
// of N calls advance(1) (no step deferred), on
//  (a) a granular bed with a floor, gravity, Hertz contacts with tangential history and
//      rolling springs, periodic x and y;
//  (b) the same bed in a body force field (the kicks read the field at the particle);
//  (c) a coupled bed (gas forces; every 5th step a flow step, before which the pending kick
//      must be done: the gas step reads the full-step velocities);
//  (d) continuum averages sampled every 3rd step (those steps are not deferred: the averager
//      takes their full-step velocities).
// Inside advance(N) the positions and velocities live in the contact loop's view between steps
// (p_'s arrays are brought up to date before anything reads them); advance(1) starts each step
// from p_, so the same comparisons cover both sources of a step. And (e): a velocity changed
// through particles() between two advance() calls is taken by the next step (the run differs
// from one without the change, and equals the change followed by single steps).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "analysis/continuum_averaging.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

const std::string kBed = R"(
[simulation]
dimension = 3
end_time = 1.0
time_step = 2e-5
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.04, 0.04, 0.04]
periodic = [true, true, false]
[[species]]
name = "glass"
diameter = 0.003
density = 2500.0
youngs_modulus = 1e7
restitution = 0.8
friction = 0.4
rolling_friction = 0.05
[[insert]]
species = "glass"
count = 600
placement = "random"
velocity_spread = 0.8
seed = 3
[contact]
normal = "hertz"
tangential = "history"
rolling = "spring_dashpot"
)";

const std::string kField = R"(
[body_force]
type = "sinusoidal_cube"
amplitude = 2.0
wavelength = 0.04
)";

const std::string kContinuum = R"(
[output.continuum]
cells = [2, 2, 2]
stride = 3
)";

const std::string kCoupled = R"(
[simulation]
dimension = 3
end_time = 1.0
time_step = 2e-5
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.03, 0.004, 0.06]
[[species]]
name = "s"
diameter = 0.004
density = 2700.0
youngs_modulus = 1e7
[[insert]]
species = "s"
count = 40
placement = "lattice"
[gas]
cells = [3, 1, 6]
time_step = 1e-4
[gas.boundary.bottom]
type = "inflow"
velocity = 2.0
[gas.boundary.top]
type = "pressure"
pressure = 101325.0
)";

struct State {
  std::vector<double> q; // x y z vx vy vz wx wy wz per particle, then the contact forces
  double dissipated = 0.0;
};

State advance(const std::string& text, long steps, bool one_at_a_time) {
  Simulation sim(read_case_string(text, "deferred.toml"));
  // The deferral alone: a deferred step may also be folded into the contact loop, whose
  // dissipation sum runs per slab instead of per chunk (folded_step_test.cpp compares the two).
  sim.set_folded_integration(false);
  if (one_at_a_time)
    for (long k = 0; k < steps; ++k) sim.advance(1);
  else
    sim.advance(steps);
  const ParticleStore& p = sim.particles();
  State s;
  for (std::size_t i = 0; i < p.size(); ++i)
    s.q.insert(s.q.end(),
               {p.x[i], p.y[i], p.z[i], p.vx[i], p.vy[i], p.vz[i], p.wx[i], p.wy[i], p.wz[i]});
  s.q.insert(s.q.end(), sim.contact_sums().begin(), sim.contact_sums().end());
  if (sim.continuum() != nullptr) { // the averages of the sampled steps
    const ContinuumFields f = sim.continuum()->result();
    for (const auto& c : f.velocity) s.q.insert(s.q.end(), c.begin(), c.end());
    for (const auto& c : f.kinetic_stress) s.q.insert(s.q.end(), c.begin(), c.end());
    s.q.insert(s.q.end(), f.granular_temperature.begin(), f.granular_temperature.end());
  }
  s.dissipated = sim.dissipated_energy();
  return s;
}

void expect_same(const std::string& text, long steps) {
  const State deferred = advance(text, steps, false);
  const State reference = advance(text, steps, true);
  ASSERT_EQ(deferred.q.size(), reference.q.size());
  ASSERT_GT(reference.dissipated, 0.0); // contacts dissipated: the deferred terms were summed
  // Bitwise: operator== on doubles, no tolerance.
  EXPECT_TRUE(deferred.q == reference.q);
  EXPECT_EQ(deferred.dissipated, reference.dissipated);
}

TEST(DeferredKick, GranularBedIsBitwiseTheUndeferredOne) {
  expect_same(kBed, 200);
}

TEST(DeferredKick, BodyForceFieldIsBitwiseTheUndeferredOne) {
  expect_same(kBed + kField, 200);
}

TEST(DeferredKick, CoupledBedIsBitwiseTheUndeferredOne) {
  expect_same(kCoupled, 101);
}

std::vector<double> velocities_after_a_push(bool push, bool one_at_a_time) {
  Simulation sim(read_case_string(kBed, "deferred.toml"));
  sim.advance(50);
  if (push) sim.particles().vx[7] += 0.5; // m/s, between two advance() calls
  if (one_at_a_time)
    for (int k = 0; k < 50; ++k) sim.advance(1);
  else
    sim.advance(50);
  const ParticleStore& p = sim.particles();
  std::vector<double> v(p.vx.begin(), p.vx.end());
  v.insert(v.end(), p.x.begin(), p.x.end());
  return v;
}

TEST(DeferredKick, ParticlesChangedBetweenAdvancesAreTaken) {
  const std::vector<double> pushed = velocities_after_a_push(true, false);
  EXPECT_FALSE(pushed == velocities_after_a_push(false, false)); // the push was not lost
  EXPECT_TRUE(pushed == velocities_after_a_push(true, true));
}

TEST(DeferredKick, ContinuumSampledStepsAreBitwiseTheUndeferredOnes) {
  expect_same(kBed + kContinuum, 200);
}

} // namespace
} // namespace fluidem
