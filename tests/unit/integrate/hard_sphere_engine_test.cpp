// The event-driven hard-sphere engine through the whole Simulation (case text -> insertion ->
// HardSphereEngine::advance, `[simulation] engine = "hard_sphere"`), against closed-form
// references:
//
// (a) Two spheres head-on in free space (no gravity, unequal sizes and densities): they meet at
//     t* = gap / closing speed, and leave with the textbook 1-D restitution result
//       v_a' = (m_a v_a + m_b v_b - m_b e (v_a - v_b)) / (m_a + m_b)   (a and b swapped for b)
//     losing 1/2 m_ab (1 - e^2) (v_a - v_b)^2 [Hoomans96 eq. 23 with v_t = 0]. The collision
//     time is read back from the positions at the end of the step (x = x0 + v t* + v' (T - t*)).
//     Tolerances: t* within 1e-12 s (1e-8 DT), velocities 1e-12 relative, energy 1e-10.
// (b) A sphere dropped from rest onto the floor under gravity, DT = 1e-4 s. The engine flies
//     particles on exact parabolas and finds the wall contact as the root of the gap's
//     quadratic, so each bounce happens at the true instant with the true impact velocity:
//     the apex height H = z - R + v_z^2 / (2g) after bounce k is e^(2k) H_0 exactly (Newton:
//     v' = -e v at the floor, energy conserved in flight). Tolerances: e = 1, 100 bounces
//     (~29 s simulated): every apex within 1e-9 relative of H_0 (round-off of ~3e5 steps);
//     e = 0.8: every ratio H_{k+1} / H_k = e^2 within 1e-9 relative; within a flight H is
//     constant to 1e-10.
// (c) An elastic, frictionless (e = 1, mu = 0) 3-D hard-sphere gas, 2000 spheres at packing 0.2
//     in a fully periodic box, no gravity: every collision conserves kinetic energy and linear
//     momentum exactly in exact arithmetic, so after 100 flow steps the kinetic energy is
//     conserved to 1e-10 relative and sum m v to round-off (1e-13 of sum m |v|); no pair
//     overlaps (all pairs, minimum image: distance >= (R_i + R_j)(1 - 1e-9)). Also checked: the
//     collision rate agrees with Enskog's collision frequency for hard spheres,
//     omega = 4 n sigma^2 g(sigma) sqrt(pi T / m) (T = m <|v - <v>|^2> / 3, Carnahan-Starling
//     g(sigma) = (1 - phi/2) / (1 - phi)^3) [Chapman & Cowling 1970, ch. 16, Enskog's dense
//     gas], measured over steps 51-100 after 50 steps of relaxation from uniform velocities and
//     random-sequential positions, within 5% (the counting noise of ~3500 events is 1.7%; a
//     missed event would also show up as an overlap).
// (d) Settled dense beds, e = 0.9, mu = 0.3 (particles and walls): 300 discs (2-D) and 1000
//     spheres (3-D) poured from rest and settled, then run for 1 s. The run must finish (no
//     InstabilityError: no overlap, no stall beyond max_events_per_particle) and the
//     collision rate must stay below 2e6 per particle per second of simulated time
//     (derivation at kRateBound; measured values printed). Settled means e_kin below 1e-3 of
//     the bed's potential energy: with exact gravity a bed never comes to rest in a
//     hard-sphere model; it rattles with impact speeds near hardsphere.elastic_below
//     (8.9 mm/s here), below which collisions are elastic, i.e. e_kin ~ N m v^2 / 2 ~ 2e-4
//     e_pot for these beds. The 2-D container is 16.5 diameters wide: a width of exactly 16
//     lets a row of discs span it with zero slack, a rigid jam in which hard spheres collide
//     infinitely often (the stall guard then stops the run).
// (e) The number of threads changes nothing: the per-step loops of the engine (list build,
//     first events, flight to the end of the step, overlap check) run in OpenMP above 4096
//     particles, and a run of 5000 spheres (inelastic, frictional, gravity, walls and one
//     periodic axis, so pairs, walls, the TC rules and list rebuilds all occur) gives bitwise
//     identical positions, velocities, spins and collision counts on 1 and 2 threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kD = 0.004; // m
constexpr double kR = 0.5 * kD;
constexpr double kRho = 2700.0; // kg/m^3
constexpr double kDT = 1.0e-4;  // s, flow time step
constexpr double kG = 9.81;     // m/s^2

double sphere_mass_of(double r, double rho) {
  return 4.0 / 3.0 * kPi * r * r * r * rho;
}

/// [[insert]] of one particle centred at `x` with velocity `v`: a lattice region exactly one
/// diameter wide holds exactly one site.
std::string one_particle(const std::string& species, double r, const std::array<double, 3>& x,
                         const std::array<double, 3>& v) {
  return fmt::format("[[insert]]\nspecies = \"{}\"\ncount = 1\nplacement = \"lattice\"\n"
                     "region = {{ lo = [{:.17g}, {:.17g}, {:.17g}], hi = [{:.17g}, {:.17g}, "
                     "{:.17g}] }}\nvelocity = [{:.17g}, {:.17g}, {:.17g}]\n\n",
                     species, x[0] - r, x[1] - r, x[2] - r, x[0] + r, x[1] + r, x[2] + r, v[0],
                     v[1], v[2]);
}

std::string header(int dimension, double gz, const std::array<double, 3>& hi,
                   const std::string& periodic = "[false, false, false]", double dt = kDT) {
  return fmt::format("[simulation]\nengine = \"hard_sphere\"\ndimension = {}\nend_time = 100.0\n"
                     "time_step = {:.17g}\ngravity = [0.0, 0.0, {:.17g}]\n\n"
                     "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [{:.17g}, {:.17g}, {:.17g}]\n"
                     "periodic = {}\n\n",
                     dimension, dt, gz, hi[0], hi[1], hi[2], periodic);
}

std::string walls(double e, double mu) {
  return fmt::format("[walls]\nrestitution = {:.17g}\nfriction = {:.17g}\n\n", e, mu);
}

std::string species(const std::string& name, double d, double rho, double e, double mu) {
  return fmt::format("[[species]]\nname = \"{}\"\ndiameter = {:.17g}\ndensity = {:.17g}\n"
                     "restitution = {:.17g}\nfriction = {:.17g}\n\n",
                     name, d, rho, e, mu);
}

// ---- (a) head-on pair -----------------------------------------------------------------------

TEST(HardSphereEngine, HeadOnPairCollidesAtThePredictedTimeWithTheERule) {
  // a: 4 mm glass moving +x; b: 6 mm, lighter material, moving -x; e = 0.8 for both (the pair
  // takes the mean). The collision falls inside step 34 (t* = 3.37e-3 s), not on a step end.
  const double ra = kR, rb = 0.003, rho_b = 1000.0, e = 0.8;
  const double va = 0.5, vb = -0.3, t_star = 3.37e-3;
  const double gap = (va - vb) * t_star;
  const double xa = 0.04, xb = xa + ra + rb + gap, c = 0.05;
  const std::string text =
      header(3, 0.0, {0.1, 0.1, 0.1}) + walls(0.5, 0.3) + species("a", 2 * ra, kRho, e, 0.3) +
      species("b", 2 * rb, rho_b, e, 0.3) + one_particle("a", ra, {xa, c, c}, {va, 0, 0}) +
      one_particle("b", rb, {xb, c, c}, {vb, 0, 0});
  Simulation sim(read_case_string(text, "pair.toml"));
  ASSERT_NE(sim.hard_sphere(), nullptr);
  auto& p = sim.particles();
  ASSERT_EQ(p.size(), 2u);
  ASSERT_EQ(p.radius[0], ra);
  const double x0a = p.x[0], x0b = p.x[1];
  const double t_pred = (x0b - x0a - ra - rb) / (va - vb); // from the actual insert positions
  const long k_pred = static_cast<long>(std::floor(t_pred / kDT)) + 1;
  ASSERT_EQ(k_pred, 34);

  const double ma = sphere_mass_of(ra, kRho), mb = sphere_mass_of(rb, rho_b);
  const Energies e0 = sim.energies();
  sim.advance(k_pred - 1);
  EXPECT_EQ(sim.hard_sphere()->stats().collisions, 0) << "collided before the predicted step";
  EXPECT_EQ(p.vx[0], va);
  sim.advance(1);
  EXPECT_EQ(sim.hard_sphere()->stats().collisions, 1) << "no collision in the predicted step";
  EXPECT_EQ(sim.hard_sphere()->stats().wall_collisions, 0);

  const double va1 = (ma * va + mb * vb - mb * e * (va - vb)) / (ma + mb);
  const double vb1 = (ma * va + mb * vb - ma * e * (vb - va)) / (ma + mb);
  EXPECT_NEAR(p.vx[0], va1, 1e-12 * std::abs(va));
  EXPECT_NEAR(p.vx[1], vb1, 1e-12 * std::abs(va));
  EXPECT_NEAR((p.vx[1] - p.vx[0]) / (va - vb), e, 1e-12) << "separation = e x approach";
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(p.vy[i], 0.0);
    EXPECT_EQ(p.vz[i], 0.0);
    EXPECT_EQ(p.wx[i] * p.wx[i] + p.wy[i] * p.wy[i] + p.wz[i] * p.wz[i], 0.0);
  }
  // Collision time from the end-of-step positions: x(T) = x0 + v t* + v' (T - t*).
  const double T = sim.time();
  const double ta = (p.x[0] - x0a - va1 * T) / (va - va1);
  const double tb = (p.x[1] - x0b - vb1 * T) / (vb - vb1);
  std::cout << fmt::format("head-on: predicted t* = {:.15e} s, from positions {:.15e} s (a), "
                           "{:.15e} s (b)\n",
                           t_pred, ta, tb);
  EXPECT_NEAR(ta, t_pred, 1e-12);
  EXPECT_NEAR(tb, t_pred, 1e-12);
  EXPECT_NEAR(p.x[1] - p.x[0] - ra - rb, (vb1 - va1) * (T - t_pred), 1e-12)
      << "in contact at t*, separating at (1 - e) less than the approach speed since";

  const double mab = ma * mb / (ma + mb);
  const double lost = 0.5 * mab * (1.0 - e * e) * (va - vb) * (va - vb);
  EXPECT_NEAR(sim.dissipated_energy(), lost, 1e-10 * lost);
  EXPECT_NEAR(e0.kinetic - sim.energies().kinetic, lost, 1e-10 * lost);

  // Nothing else happens: they fly apart (walls 3-4 cm away need > 40 ms).
  const double after_a = p.vx[0], after_b = p.vx[1];
  sim.advance(50);
  EXPECT_EQ(sim.hard_sphere()->stats().collisions, 1);
  EXPECT_EQ(p.vx[0], after_a);
  EXPECT_EQ(p.vx[1], after_b);
}

// ---- (b) bouncing on the floor --------------------------------------------------------------

struct Bounces {
  std::vector<double> apex;         // H of each flight, m above the floor contact (z - R)
  double max_drift_in_flight = 0.0; // relative variation of H within a flight
};

/// Drop one sphere from rest at centre height z0 onto the floor and record the apex height of
/// each flight, until `flights` flights were seen or `max_steps` steps ran.
Bounces drop(double e, double z0, std::size_t flights, long max_steps) {
  const double box = 0.04;
  const std::string text = header(3, -kG, {box, box, z0 + 0.05}) + walls(e, 0.3) +
                           species("s", kD, kRho, 0.5, 0.3) +
                           one_particle("s", kR, {0.5 * box, 0.5 * box, z0}, {0, 0, 0});
  Simulation sim(read_case_string(text, "drop.toml"));
  const auto& p = sim.particles();
  EXPECT_EQ(p.size(), 1u);
  Bounces b;
  const double g = -sim.spec().simulation.gravity[2];
  EXPECT_EQ(g, kG);
  auto apex = [&] { return p.z[0] - p.radius[0] + p.vz[0] * p.vz[0] / (2.0 * g); };
  b.apex.push_back(apex());
  long seen = 0;
  bool new_flight = false;
  for (long step = 0; step < max_steps && b.apex.size() < flights; ++step) {
    sim.advance(1);
    const long c = sim.hard_sphere()->stats().collisions;
    if (c != seen) { // a bounce within this step
      EXPECT_EQ(c, seen + 1) << "two bounces in one step";
      seen = c;
      new_flight = true;
      continue;
    }
    if (new_flight) {
      b.apex.push_back(apex());
      new_flight = false;
    } else {
      b.max_drift_in_flight =
          std::max(b.max_drift_in_flight, std::abs(apex() / b.apex.back() - 1.0));
    }
  }
  EXPECT_EQ(sim.hard_sphere()->stats().wall_collisions, seen);
  EXPECT_EQ(p.vx[0], 0.0);
  EXPECT_EQ(p.vy[0], 0.0);
  return b;
}

TEST(HardSphereEngine, ElasticBounceKeepsTheApexHeight) {
  // 10 cm drop, e = 1, 100 bounces (~29 s of simulated time).
  const double z0 = 0.1 + kR;
  const Bounces b = drop(1.0, z0, 101, 400000);
  ASSERT_EQ(b.apex.size(), 101u);
  const double h0 = b.apex[0];
  EXPECT_NEAR(h0, 0.1, 1e-15);
  double worst = 0.0;
  for (std::size_t k = 1; k < b.apex.size(); ++k) {
    const double dev = b.apex[k] / h0 - 1.0;
    worst = std::max(worst, std::abs(dev));
    EXPECT_NEAR(dev, 0.0, 1e-9) << "apex " << k;
  }
  std::cout << fmt::format("elastic bounce, 100 bounces from {} m: largest apex deviation "
                           "{:.3e}; within a flight {:.3e}\n",
                           h0, worst, b.max_drift_in_flight);
  EXPECT_LE(b.max_drift_in_flight, 1e-10) << "free flight is exact";
}

TEST(HardSphereEngine, InelasticBounceApexRatioIsESquared) {
  const double e = 0.8;
  const Bounces b = drop(e, 0.2 + kR, 9, 200000);
  ASSERT_EQ(b.apex.size(), 9u);
  std::string line;
  for (std::size_t k = 0; k + 1 < b.apex.size(); ++k) {
    const double ratio = b.apex[k + 1] / b.apex[k];
    line += fmt::format(" {:.12f}", ratio / (e * e));
    EXPECT_NEAR(ratio / (e * e), 1.0, 1e-9) << "bounce " << k;
  }
  std::cout << "inelastic bounce e = 0.8: H_{k+1} / (e^2 H_k) =" << line << "\n";
  EXPECT_LE(b.max_drift_in_flight, 1e-10);
}

// ---- (c) elastic gas ------------------------------------------------------------------------

TEST(HardSphereEngine, ElasticGasConservesEnergyAndMomentum) {
  const long n = 2000;
  const double phi = 0.2;
  const double box = std::cbrt(static_cast<double>(n) * kPi / 6.0 * kD * kD * kD / phi);
  const std::string text = header(3, 0.0, {box, box, box}, "[true, true, true]") + walls(1.0, 0.0) +
                           species("s", kD, kRho, 1.0, 0.0) +
                           fmt::format("[[insert]]\nspecies = \"s\"\ncount = {}\n"
                                       "placement = \"random\"\nvelocity_spread = 1.0\n"
                                       "seed = 11\n",
                                       n);
  Simulation sim(read_case_string(text, "gas.toml"));
  const auto& p = sim.particles();
  ASSERT_EQ(p.size(), static_cast<std::size_t>(n));
  const double m = p.mass[0];
  auto momentum = [&](double* scale) {
    Vec3 sum;
    *scale = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      sum += p.velocity(i) * p.mass[i];
      *scale += p.mass[i] * norm(p.velocity(i));
    }
    return sum;
  };
  double scale = 0.0;
  const Vec3 p0 = momentum(&scale);
  const double k0 = sim.energies().kinetic;
  ASSERT_EQ(sim.energies().rotational, 0.0);

  // First 50 steps: relaxation. Last 50: collision rate against Enskog.
  sim.advance(50);
  const long c50 = sim.hard_sphere()->stats().collisions;
  double t_sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) t_sum += norm2(p.velocity(i) - p0 / (m * n));
  const double kT = m * t_sum / (3.0 * static_cast<double>(n)); // m <|v - <v>|^2> / 3
  sim.advance(50);
  const long c100 = sim.hard_sphere()->stats().collisions;

  const double k1 = sim.energies().kinetic;
  double scale1 = 0.0;
  const Vec3 p1 = momentum(&scale1);
  EXPECT_NEAR(k1 / k0, 1.0, 1e-10) << "kinetic energy";
  // mu = 0: no spin beyond round-off (n x J_n n is not exactly 0 in floating point).
  EXPECT_LE(sim.energies().rotational, 1e-24 * k0) << "mu = 0: no spin";
  EXPECT_LE(norm(p1 - p0), 1e-13 * scale) << "linear momentum";
  EXPECT_NEAR(sim.hard_sphere()->stats().dissipated, 0.0, 1e-10 * k0);

  // No overlaps, all pairs with the minimum image.
  double min_ratio = 1e300;
  auto img = [&](double d) { return d - box * std::round(d / box); };
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double dx = img(p.x[i] - p.x[j]), dy = img(p.y[i] - p.y[j]), dz = img(p.z[i] - p.z[j]);
      min_ratio =
          std::min(min_ratio, std::sqrt(dx * dx + dy * dy + dz * dz) / (p.radius[i] + p.radius[j]));
    }
  EXPECT_GE(min_ratio, 1.0 - 1e-9) << "overlap";

  // Enskog collision frequency per particle (collisions counted once per pair: 2 per event).
  const double number_density = static_cast<double>(n) / (box * box * box);
  const double g_sigma = (1.0 - 0.5 * phi) / std::pow(1.0 - phi, 3);
  const double omega = 4.0 * number_density * kD * kD * g_sigma * std::sqrt(kPi * kT / m);
  const double measured = 2.0 * static_cast<double>(c100 - c50) / (50.0 * kDT * n);
  std::cout << fmt::format("elastic gas: {} collisions in 100 steps; K drift {:+.3e}; momentum "
                           "error {:.3e} of sum m|v|; min distance / sigma - 1 = {:+.3e}; "
                           "collision frequency {:.1f} /s vs Enskog {:.1f} /s ({:+.2f}%)\n",
                           c100, k1 / k0 - 1.0, norm(p1 - p0) / scale, min_ratio - 1.0, measured,
                           omega, 100.0 * (measured / omega - 1.0));
  EXPECT_EQ(sim.hard_sphere()->stats().wall_collisions, 0) << "fully periodic";
  EXPECT_NEAR(measured, omega, 0.05 * omega);
}

// ---- (d) settled dense beds -----------------------------------------------------------------

struct BedRun {
  double rate = 0.0;                   // collisions per particle per second of simulated time
  double tc_fraction = 0.0;            // share made elastic (TC model or low impact speed)
  double seconds = 0.0;                // wall-clock time of the measured interval
  double kinetic_over_potential = 0.0; // e_kin / e_pot (above z = 0) at the end of settling
  double heating = 0.0;                // d(e_dsp)/dt per unit mass over the measured interval, W/kg
};

// The measured interval after settling, s: 0.25 s holds ~2e7 collisions of the 2-D bed and
// ~1e7 of the 3-D bed (rates below), plenty for a rate bound (1 s until 2026-12-06: 79 s and
// 53 s of the CI's test time).
constexpr double kMeasured = 0.25;

/// Pour `count` particles from rest (random positions below z_fill), let them settle for
/// `settle` s, then run kMeasured s and measure.
BedRun bed(int dimension, long count, const std::array<double, 3>& hi, double z_fill,
           double settle) {
  const std::string text =
      header(dimension, -kG, hi) + walls(0.9, 0.3) + species("s", kD, kRho, 0.9, 0.3) +
      fmt::format("[[insert]]\nspecies = \"s\"\ncount = {}\nplacement = \"random\"\n"
                  "region = {{ hi = [{:.17g}, {:.17g}, {:.17g}] }}\nseed = 5\n",
                  count, hi[0], hi[1], z_fill);
  Simulation sim(read_case_string(text, "bed.toml"));
  EXPECT_EQ(sim.particles().size(), static_cast<std::size_t>(count));
  double mass = 0.0;
  for (std::size_t i = 0; i < sim.particles().size(); ++i) mass += sim.particles().mass[i];
  BedRun r;
  EXPECT_NO_THROW(sim.advance(std::lround(settle / kDT))) << "settling";
  r.kinetic_over_potential = sim.energies().kinetic / sim.energies().potential;
  const auto& st = sim.hard_sphere()->stats();
  const long c0 = st.collisions, tc0 = st.tc_elastic + st.slow_elastic;
  const double d0 = st.dissipated;
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_NO_THROW(sim.advance(std::lround(kMeasured / kDT))) << "measured interval";
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.rate = static_cast<double>(st.collisions - c0) / static_cast<double>(count) / kMeasured;
  r.tc_fraction = static_cast<double>(st.tc_elastic + st.slow_elastic - tc0) /
                  static_cast<double>(st.collisions - c0);
  r.heating = (st.dissipated - d0) / mass / kMeasured;
  EXPECT_NEAR(sim.time(), settle + kMeasured, 1e-9);
  return r;
}

void report_bed(const std::string& name, const BedRun& r) {
  std::cout << fmt::format("settled bed {}: e_kin/e_pot at the end of settling {:.2e}; {:.4g} "
                           "collisions per particle per second ({:.3g} per particle per step, "
                           "{:.1f}% made elastic by the TC model or the low-speed rule); e_dsp "
                           "grows by {:.3g} W/kg; {:.1f} s wall-clock for {} s\n",
                           name, r.kinetic_over_potential, r.rate, r.rate * kDT,
                           100.0 * r.tc_fraction, r.heating, r.seconds, kMeasured);
}

// Bound on the collision rate. A bed "at rest" still rattles: its particles hop on their
// supports with impact speeds near elastic_below (v = 8.9 mm/s here), a contact being hit about
// g / v ~ 1e3 times per second. Measured (DT = 1e-4 s, 2026-12-06): see the printed rates
// (3.2e5 per particle per second in the 2-D bed over 1 s, 3.0e5 over 0.25 s; 4.5e4 and 3.7e4 in
// the 3-D bed). The bound, 2e6 per particle per second = 200 per particle per step, is a fifth
// of the stall guard (max_events_per_particle = 1000 per step): it fails on a sixfold rise of the
// 2-D bed's rate and a fiftyfold rise of the 3-D bed's (e.g. repeated zero-time events), long
// before the run would stall.
// Settled: e_kin below 1e-3 of the bed's potential energy at the end of settling (see (d)).
constexpr double kRateBound = 2.0e6;

TEST(HardSphereEngine, Settled2DBedRunsWithABoundedCollisionRate) {
  // 300 discs in a 16.5 d wide container (Hoomans96 §5.1 set-up, smaller): ~18 layers.
  const BedRun r = bed(2, 300, {0.066, kD, 0.2}, 0.2, 0.6);
  report_bed("2-D, 300 discs", r);
  EXPECT_LT(r.kinetic_over_potential, 1e-3) << "not settled";
  EXPECT_GT(r.rate, 0.0);
  EXPECT_LT(r.rate, kRateBound);
}

TEST(HardSphereEngine, Settled3DBedRunsWithABoundedCollisionRate) {
  // 1000 spheres on a 10 d x 10 d floor: ~9 layers. Poured from below 8 cm to shorten the fall.
  const BedRun r = bed(3, 1000, {0.04, 0.04, 0.2}, 0.08, 0.5);
  report_bed("3-D, 1000 spheres", r);
  EXPECT_LT(r.kinetic_over_potential, 1e-3) << "not settled";
  EXPECT_GT(r.rate, 0.0);
  EXPECT_LT(r.rate, kRateBound);
}

// ---- (e) thread count ------------------------------------------------------------------------

/// x, y, z, v, w of every particle, in id order (the store is sorted in space at every 20th
/// list build, neighbour.sort_interval, and runs with other skins build at other steps).
std::vector<double> kinematic_state(const Simulation& sim) {
  const auto& p = sim.particles();
  std::vector<std::size_t> by_id(p.size());
  std::iota(by_id.begin(), by_id.end(), std::size_t{0});
  std::sort(by_id.begin(), by_id.end(),
            [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
  std::vector<double> state;
  for (const auto* a : {&p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.wx, &p.wy, &p.wz})
    for (const std::size_t i : by_id) state.push_back((*a)[i]);
  return state;
}

/// How many values of two states of the same size differ in any bit.
std::size_t bitwise_differences(const std::vector<double>& a, const std::vector<double>& b) {
  std::size_t differ = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    differ += std::memcmp(&a[k], &b[k], sizeof(double)) != 0;
  return differ;
}

struct ThreadRun {
  std::vector<double> state; // x, y, z, v, w of every particle
  long collisions = 0, wall_collisions = 0, tc = 0, builds = 0;
};

ThreadRun run_on(int threads) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  const std::string text = header(3, -kG, {0.1, 0.1, 0.16}, "[true, false, false]") +
                           walls(0.9, 0.3) + species("s", kD, kRho, 0.9, 0.3) +
                           "[[insert]]\nspecies = \"s\"\ncount = 5000\nplacement = \"random\"\n"
                           "velocity_spread = 0.5\nseed = 3\n";
  Simulation sim(read_case_string(text, "threads.toml"));
  sim.advance(200);
  omp_set_num_threads(saved);
  ThreadRun r;
  r.state = kinematic_state(sim);
  const auto& st = sim.hard_sphere()->stats();
  r.collisions = st.collisions;
  r.wall_collisions = st.wall_collisions;
  r.tc = st.tc_elastic + st.slow_elastic;
  r.builds = sim.hard_sphere()->list_builds();
  return r;
}

TEST(HardSphereEngine, OneAndTwoThreadsGiveBitwiseIdenticalRuns) {
  const ThreadRun one = run_on(1), two = run_on(2);
  std::cout << fmt::format("5000 spheres, 200 steps: {} collisions ({} with walls, {} elastic "
                           "by the TC rules), {} list builds\n",
                           one.collisions, one.wall_collisions, one.tc, one.builds);
  ASSERT_GT(one.collisions, 1000) << "the case must collide";
  ASSERT_GT(one.wall_collisions, 0);
  ASSERT_GT(one.builds, 1) << "the list must be rebuilt";
  EXPECT_EQ(one.collisions, two.collisions);
  EXPECT_EQ(one.wall_collisions, two.wall_collisions);
  EXPECT_EQ(one.tc, two.tc);
  EXPECT_EQ(one.builds, two.builds);
  ASSERT_EQ(one.state.size(), two.state.size());
  EXPECT_EQ(bitwise_differences(one.state, two.state), 0u)
      << "values differing bitwise between 1 and 2 threads";
}

// ---- (f) the neighbour skin ------------------------------------------------------------------
// hardsphere/skin_policy.hpp chooses, at each list build, a skin of 8 or 2 maximal one-step
// displacements s = 1.5 (v_max + g DT) DT. A granular gas of 1000 spheres (velocity spread
// 1 m/s, v_max 1.6 m/s) with DT = 1e-3 s: s is 2.5 mm, so the long list reaches 20 mm (5
// diameters) past contact and the short one 5 mm; the policy must take the short skin.
// (a) The first build is a probe: its counts are checked against a brute-force count over all
//     pairs (entries per particle = 2 x pairs / N) of the pairs closer than R_i + R_j + 8 s and
//     + 2 s at the initial state.
// (b) The particles are the same bit for bit with the policy, the long skin and the short skin
//     (the list only has to hold every pair that can meet in its life), and the policy made
//     more builds than the long skin (it took the short one) but fewer than the short skin
//     (it probed with the long one).

std::string gas_case() {
  return header(3, -kG, {0.1, 0.1, 0.1}, "[false, false, false]", 1e-3) + walls(0.9, 0.3) +
         species("s", kD, kRho, 0.9, 0.3) +
         "[[insert]]\nspecies = \"s\"\ncount = 1000\nplacement = \"random\"\n"
         "velocity_spread = 1.0\nseed = 11\n";
}

struct SkinRun {
  std::vector<double> state;
  long builds = 0;
};

SkinRun run_gas(double skin_steps, long steps) {
  Simulation sim(read_case_string(gas_case(), "gas.toml"));
  sim.hard_sphere()->set_skin_steps(skin_steps);
  sim.advance(steps);
  return {kinematic_state(sim), sim.hard_sphere()->list_builds()};
}

TEST(HardSphereEngine, TheSkinProbeCountsThePairsWithinBothSkins) {
  Simulation sim(read_case_string(gas_case(), "gas.toml"));
  const auto& p = sim.particles();
  const std::size_t n = p.size();
  ASSERT_EQ(n, 1000u);
  double vmax = 0.0, rmin = 1e300;
  for (std::size_t i = 0; i < n; ++i) {
    vmax = std::max(vmax, std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]));
    rmin = std::min(rmin, p.radius[i]);
  }
  const double dt = 1e-3, s = 1.5 * (vmax + kG * dt) * dt;
  const double long_skin = std::max(8.0 * s, 1e-3 * rmin),
               short_skin = std::max(2.0 * s, 1e-3 * rmin);
  long within_long = 0, within_short = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const double d =
          std::sqrt((p.x[i] - p.x[j]) * (p.x[i] - p.x[j]) + (p.y[i] - p.y[j]) * (p.y[i] - p.y[j]) +
                    (p.z[i] - p.z[j]) * (p.z[i] - p.z[j])) -
          p.radius[i] - p.radius[j];
      within_long += d < long_skin;
      within_short += d < short_skin;
    }
  sim.advance(1);
  const auto& probe = sim.hard_sphere()->skin_probe();
  std::cout << fmt::format("granular gas: s = {:.3g} mm; pairs within 8 s {}, within 2 s {}\n",
                           1e3 * s, within_long, within_short);
  ASSERT_GT(within_long, 3 * within_short) << "the case must make the long list larger";
  EXPECT_EQ(probe.build, 0);
  // (a pair at exactly the cut, counted by one side and not the other, would show as 1/N)
  const auto count = static_cast<double>(n);
  EXPECT_NEAR(probe.long_entries, 2.0 * static_cast<double>(within_long) / count, 0.5 / count);
  EXPECT_NEAR(probe.short_entries, 2.0 * static_cast<double>(within_short) / count, 0.5 / count);
}

TEST(HardSphereEngine, TheSkinPolicyLeavesTheParticlesUnchanged) {
  const long steps = 150; // probes at builds 0, 64 and 128
  const SkinRun policy = run_gas(0.0, steps), longer = run_gas(8.0, steps),
                shorter = run_gas(2.0, steps);
  std::cout << fmt::format("{} steps: {} list builds with the policy, {} with the long skin, {} "
                           "with the short one\n",
                           steps, policy.builds, longer.builds, shorter.builds);
  EXPECT_GT(policy.builds, longer.builds) << "the short skin was never taken";
  EXPECT_LT(policy.builds, shorter.builds) << "the long skin never probed";
  ASSERT_EQ(policy.state.size(), longer.state.size());
  ASSERT_EQ(policy.state.size(), shorter.state.size());
  EXPECT_EQ(bitwise_differences(policy.state, longer.state), 0u);
  EXPECT_EQ(bitwise_differences(policy.state, shorter.state), 0u);
}

} // namespace
} // namespace fluidem
