// The conservative non-contact forces in a run (noncontact/pair_forces.hpp through
// integrate/noncontact_source.hpp), against closed forms:
//  - Two equal like charges released at rest (no gravity, far from the walls): the relative
//    coordinate of the Coulomb two-body problem, mu r'' = k / r^2 (mu = m/2), has
//    t(r) = sqrt(mu r0^3 / (2 k)) (sqrt(x (x - 1)) + ln(sqrt(x) + sqrt(x - 1))), x = r / r0
//    (energy conservation, integrated; Landau & Lifshitz, Mechanics §15). The shifted force's
//    constant -k/r_c^2 is 1e-6 of the force at r = 3 r0 here; velocity Verlet with ~4000 steps
//    per r0: tolerance 1e-5 r0 on r at the time of x = 3. The momentum stays zero (Newton's third
//    law, exactly antisymmetric pair forces): 1e-18 kg m/s.
//  - Opposite charges attract along the same curve's mirror: the time to close from r0 to r is
//    that of free fall in -k/r^2, t = sqrt(mu r0^3/(2|k|)) (sqrt(x(1-x)) + acos(sqrt(x))), x = r/r0
//    (Landau & Lifshitz §15); at x = 1/2, tolerance 1e-5 r0.
//  - A charge near a grounded conducting wall is drawn to it by its image -q at 2 z (Jackson,
//    Classical Electrodynamics §2.1), with the shifted force; the fall time to the simulated
//    height from energy conservation (quadrature, 1e-10) matches the run's time to 1e-6 z0 of
//    position; the energy U(z) = half the charge-image energy keeps e_total constant (1e-6 of
//    the kinetic energy gained).
//  - van der Waals between two spheres, elastic (e = 1), frictionless: they meet, bounce and
//    separate again with the speed they came with (the attraction's potential is conservative,
//    shifted to zero at its range). With a step that resolves the steepest part (1/20 of h0 per
//    step) e_total stays within (1/20)^2 of the well depth A R*/(6 h0); the exit speed is v0 to
//    1e-3. (A step that jumps over h0 errs by up to the well depth: docs/noncontact.md.)
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"
#include "noncontact/kernels/coulomb.hpp"

namespace fluidem {
namespace {

constexpr double kD = 0.001, kRho = 2500.0, kBox = 0.2;
const double kMass = kRho * std::numbers::pi * kD * kD * kD / 6.0;

/// One particle of the test: centre (x, y, z), velocity along x, charge.
struct Placed {
  double x, y, z, vx, q;
};

std::string insert(const Placed& p) {
  const double h = 0.5 * kD;
  return fmt::format("\n[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\n"
                     "region = {{ lo = [{:.17g}, {:.17g}, {:.17g}], hi = [{:.17g}, {:.17g}, "
                     "{:.17g}] }}\nvelocity = [{:.17g}, 0.0, 0.0]\ncharge = {:.17g}\n",
                     p.x - h, p.y - h, p.z - h, p.x + h, p.y + h, p.z + h, p.vx, p.q);
}

std::string case_text(const std::vector<Placed>& particles, const std::string& extra,
                      const std::string& contact = "normal = \"hertz\"") {
  std::string s = fmt::format(
      "[simulation]\nend_time = 10.0\ngravity = [0.0, 0.0, 0.0]\n\n[domain]\nlo = [0.0, 0.0, "
      "0.0]\nhi = [{L}, {L}, {L}]\n\n[walls]\nfriction = 0.0\nrestitution = 1.0\n\n"
      "[[species]]\nname = \"s\"\ndiameter = {d}\ndensity = {rho}\nfriction = 0.0\n"
      "restitution = 1.0\n",
      fmt::arg("L", kBox), fmt::arg("d", kD), fmt::arg("rho", kRho));
  for (const Placed& p : particles) s += insert(p);
  return s + "\n[contact]\n" + contact + "\n" + extra;
}

double total_energy(const Simulation& sim) {
  const Energies e = sim.energies();
  return e.kinetic + e.rotational + e.potential + sim.contact_stats().elastic_energy +
         sim.dissipated_energy();
}

/// The centre distance of the two particles, m.
double separation(const Simulation& sim) {
  const ParticleStore& p = sim.particles();
  return std::hypot(p.x[1] - p.x[0], p.y[1] - p.y[0], p.z[1] - p.z[0]);
}

TEST(NonContactForces, LikeChargesFollowTheCoulombTwoBodySolution) {
  const double q = 1e-9, r0 = 0.005, c = 0.5 * kBox;
  Simulation sim(
      read_case_string(case_text({{c - 0.5 * r0, c, c, 0.0, q}, {c + 0.5 * r0, c, c, 0.0, q}},
                                 "[electrostatics]\ncutoff = 5.0\n"),
                       "coulomb.toml"));
  const double k = kernels::coulomb_constant(q, q, 1.0), mu = 0.5 * kMass;
  const double x = 3.0;
  const double t = std::sqrt(mu * r0 * r0 * r0 / (2.0 * k)) *
                   (std::sqrt(x * (x - 1.0)) + std::log(std::sqrt(x) + std::sqrt(x - 1.0)));
  const long steps = std::lround(t / sim.time_step());
  ASSERT_GT(steps, 1000) << "the time step resolves the motion";
  const double e0 = total_energy(sim);
  sim.advance(steps);
  const double t_run = static_cast<double>(steps) * sim.time_step();
  // The separation at t_run from the closed form t(r), inverted by Newton's method.
  double xr = x;
  for (int it = 0; it < 50; ++it) {
    const double tx = std::sqrt(mu * r0 * r0 * r0 / (2.0 * k)) *
                      (std::sqrt(xr * (xr - 1.0)) + std::log(std::sqrt(xr) + std::sqrt(xr - 1.0)));
    const double v = std::sqrt(2.0 * k / mu * (1.0 / r0 - 1.0 / (xr * r0))); // dr/dt
    xr -= (tx - t_run) * (v / r0);
  }
  EXPECT_NEAR(separation(sim), xr * r0, 1e-5 * r0);
  const ParticleStore& p = sim.particles();
  EXPECT_NEAR(kMass * (p.vx[0] + p.vx[1]), 0.0, 1e-18) << "momentum: Newton's third law";
  EXPECT_NEAR(total_energy(sim), e0, 1e-6 * e0) << "e_pot holds the Coulomb energy";
}

TEST(NonContactForces, OppositeChargesFallTogetherAsTheClosedFormSays) {
  const double q = 1e-9, r0 = 0.01, c = 0.5 * kBox;
  Simulation sim(
      read_case_string(case_text({{c - 0.5 * r0, c, c, 0.0, q}, {c + 0.5 * r0, c, c, 0.0, -q}},
                                 "[electrostatics]\ncutoff = 5.0\n"),
                       "attract.toml"));
  const double k = std::abs(kernels::coulomb_constant(q, -q, 1.0)), mu = 0.5 * kMass;
  const double x = 0.5;
  const double t = std::sqrt(mu * r0 * r0 * r0 / (2.0 * k)) *
                   (std::sqrt(x * (1.0 - x)) + std::acos(std::sqrt(x)));
  const long steps = std::lround(t / sim.time_step());
  sim.advance(steps);
  const double t_run = static_cast<double>(steps) * sim.time_step();
  double xr = x;
  for (int it = 0; it < 50; ++it) {
    const double tx = std::sqrt(mu * r0 * r0 * r0 / (2.0 * k)) *
                      (std::sqrt(xr * (1.0 - xr)) + std::acos(std::sqrt(xr)));
    const double v = -std::sqrt(2.0 * k / mu * (1.0 / (xr * r0) - 1.0 / r0)); // dr/dt < 0
    xr -= (tx - t_run) * (v / r0);
  }
  EXPECT_NEAR(separation(sim), xr * r0, 1e-5 * r0);
}

TEST(NonContactForces, AChargeIsDrawnToItsImageInAConductingWall) {
  const double q = 1e-9, z0 = 0.01, rc = 0.09, c = 0.5 * kBox;
  Simulation sim(read_case_string(
      case_text({{c, c, z0, 0.0, q}}, fmt::format("[electrostatics]\ncutoff = {}\n"
                                                  "conducting_walls = [\"z_lo\"]\n",
                                                  rc)),
      "image.toml"));
  const double e0 = total_energy(sim);
  // The image -q at 2 z with the shifted force; the energy is half the charge-image
  // interaction: U(z) = -k/2 (1/(2z) - 1/rc + (2z - rc)/rc^2), k = q^2/(4 pi eps0).
  const double k = kernels::coulomb_constant(q, q, 1.0);
  auto u = [&](double z) { return -0.5 * k * (0.5 / z - 1.0 / rc + (2.0 * z - rc) / (rc * rc)); };
  // The time to fall from z0 to z: integral of dz / v(z), v = sqrt(2 (U(z0) - U(z)) / m), with
  // z = z0 - s^2 (the start's 1/sqrt singularity removed), Simpson's rule on 4000 intervals.
  auto fall_time = [&](double z) {
    const int n = 4000;
    const double top = std::sqrt(z0 - z), h = top / n;
    auto f = [&](double s) {
      if (s == 0.0) { // the limit 2 s / v -> 2 / sqrt(2 F(z0) / m)
        const double f0 = k * (0.25 / (z0 * z0) - 1.0 / (rc * rc));
        return 2.0 / std::sqrt(2.0 * f0 / kMass);
      }
      const double zs = z0 - s * s;
      return 2.0 * s / std::sqrt(2.0 * (u(z0) - u(zs)) / kMass);
    };
    double sum = f(0.0) + f(top);
    for (int m = 1; m < n; ++m) sum += (m % 2 == 1 ? 4.0 : 2.0) * f(m * h);
    return sum * h / 3.0;
  };
  const long steps = std::lround(fall_time(0.5 * z0) / sim.time_step());
  sim.advance(steps);
  const double t_run = static_cast<double>(steps) * sim.time_step();
  const double z = sim.particles().z[0], v = -sim.particles().vz[0];
  // The fall's time to the simulated height against the run's time: 1e-6 z0 of position.
  EXPECT_NEAR(fall_time(z), t_run, 1e-6 * z0 / v) << "z = " << z;
  const double gained = sim.energies().kinetic;
  EXPECT_NEAR(gained, u(z0) - u(z), 1e-6 * gained) << "the kinetic energy from the image";
  EXPECT_NEAR(total_energy(sim), e0, 1e-6 * gained) << "e_pot holds the image energy";
}

TEST(NonContactForces, VanDerWaalsPairBouncesElasticallyAndKeepsItsEnergy) {
  // A step that resolves the attraction's steepest part: the pair closes by 1/20 of h0 per step.
  const double a = 1e-19, h0 = 4e-10, range = 1e-7, v0 = 0.05, c = 0.5 * kBox;
  const double gap0 = 2e-7, dt = 0.05 * h0 / (2.0 * v0);
  Simulation sim(read_case_string(
      case_text({{c - 0.5 * (kD + gap0), c, c, v0, 0.0}, {c + 0.5 * (kD + gap0), c, c, -v0, 0.0}},
                fmt::format("[van_der_waals]\nhamaker = {}\nmin_separation = {}\nrange = {}\n", a,
                            h0, range),
                "normal = \"hertz\"") +
          fmt::format("\n[output]\nframe_interval = 1.0\n"),
      "vdw.toml",
      {fmt::format("simulation.time_step={:.17g}", dt), "simulation.force_time_step=true"}));
  const double e0 = total_energy(sim);
  const double well = a * 0.25 * kD / 6.0 * (1.0 / h0 - 1.0 / range);
  double deepest = 0.0, worst = 0.0;
  long steps = 0;
  double closest = separation(sim);
  while ((closest > kD || separation(sim) < kD + gap0) && steps < 2000000) {
    sim.advance(1);
    ++steps;
    deepest = std::min(deepest, sim.energies().potential);
    worst = std::max(worst, std::abs(total_energy(sim) - e0));
    closest = std::min(closest, separation(sim));
  }
  ASSERT_LT(steps, 2000000) << "the pair separates again";
  EXPECT_LT(deepest, -well) << "it went through the well (and into contact)";
  // Velocity Verlet's energy error is of order (step / length of the force's change)^2 of the
  // well, (v dt / h0)^2 = 1/400 here.
  EXPECT_LT(worst, 2.5e-3 * well) << "e_total constant to the integration error";
  EXPECT_NEAR(sim.particles().vx[0], -v0, 1e-3 * v0) << "it leaves as fast as it came";
}

// Set-up: the time-step rule counts the stiffest non-contact force as a contact of half-period
// pi sqrt(m*/k) (k = A R*/(3 h0^3) for van der Waals at h0; m* = m/2 between two of the
// lightest); the hard-sphere engine refuses non-contact forces, naming the table; a Coulomb
// cut-off that cannot reach past contact is refused.
TEST(NonContactForces, SetUpChecks) {
  const double c = 0.5 * kBox;
  const std::vector<Placed> two = {{c - kD, c, c, 0.0, 1e-12}, {c + kD, c, c, 0.0, 1e-12}};
  const double a = 1e-19, h0 = 4e-10;
  const std::string vdw =
      fmt::format("[van_der_waals]\nhamaker = {}\nmin_separation = {}\nrange = 1e-6\n", a, h0);
  Simulation dry(read_case_string(case_text(two, ""), "dry.toml"));
  Simulation sticky(read_case_string(case_text(two, vdw), "sticky.toml"));
  const double k = a * 0.25 * kD / (3.0 * h0 * h0 * h0);
  const double period = std::numbers::pi * std::sqrt(0.5 * kMass / k);
  EXPECT_LT(sticky.time_step(), dry.time_step());
  EXPECT_NEAR(sticky.time_step(), 0.02 * period, 1e-6 * period) // time_step_fraction 0.02
      << "the auto step is a fraction of the van der Waals half-period";
  const std::string hard = "[simulation]\nengine = \"hard_sphere\"\ntime_step = 1e-4\n";
  std::string text = case_text(two, vdw);
  text.replace(text.find("[simulation]\n"), 13, hard);
  try {
    Simulation refused(read_case_string(text, "hard.toml"));
    ADD_FAILURE() << "hard spheres took van der Waals";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("van_der_waals: the hard-sphere engine has no non-contact forces"),
              std::string::npos)
        << m;
  }
  try {
    Simulation refused(
        read_case_string(case_text(two, "[electrostatics]\ncutoff = 0.0005\n"), "short.toml"));
    ADD_FAILURE() << "a cut-off inside contact was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("electrostatics: electrostatics.cutoff"),
              std::string::npos)
        << e.what();
  }
}

// Sticking: two equal spheres with van der Waals meet head-on in a Walton-Braun contact (the
// hysteretic spring, restitution e = sqrt(k1/k2) [Zhu07 Table 1]), frictionless. Closed form
// (derived in docs/noncontact.md, "Sticking"), for relative coordinate with m* = m/2 and the
// attraction F0 = A R*/(6 h0^2) inside h0 and in contact (DMT), W = F0 h0 + A R*/6 (1/h0 - 1/h_c)
// its work from h_c to contact:
//   loading to delta_m:   1/2 m* v_c^2 + F0 delta_m = 1/2 k1 delta_m^2, v_c^2 = v0^2 + 2 W / m*
//   back at contact:      E(0) = 1/2 k1 e^2 delta_m^2 - F0 delta_m    (unloading on k2 to
//                         delta0 = delta_m (1 - e^2), then F0 alone)
//   the pair separates iff E(0) > W, so the critical approach speed follows from
//   delta_m* = (F0 + sqrt(F0^2 + 2 k1 e^2 W)) / (k1 e^2). Below it they stick, above they part:
// at 0.95 and 1.05 of it. The step resolves h0 (1/20 of it per step at the critical speed), so
// the integration error of the well is (1/20)^2 of its depth, far below the 5% margin.
TEST(NonContactForces, WaltonBraunPairWithVanDerWaalsSticksBelowTheCriticalSpeed) {
  const double a = 1e-19, h0 = 4e-9, h_c = 4e-8, k1 = 100.0, e = 0.5, c = 0.5 * kBox;
  const double r_eff = 0.25 * kD, m_eff = 0.5 * kMass;
  const double f0 = a * r_eff / (6.0 * h0 * h0);
  const double w = f0 * h0 + a * r_eff / 6.0 * (1.0 / h0 - 1.0 / h_c);
  const double dm = (f0 + std::sqrt(f0 * f0 + 2.0 * k1 * e * e * w)) / (k1 * e * e);
  const double vc2 = (k1 * dm * dm - 2.0 * f0 * dm) / m_eff;
  const double v_crit = std::sqrt(vc2 - 2.0 * w / m_eff);          // relative approach speed
  const double contact = std::numbers::pi * std::sqrt(m_eff / k1); // ~ the contact's duration
  for (const double factor : {0.95, 1.05}) {
    const double v = factor * v_crit, gap0 = 1.01 * h_c;
    std::string text = case_text(
        {{c - 0.5 * (kD + gap0), c, c, 0.5 * v, 0.0}, {c + 0.5 * (kD + gap0), c, c, -0.5 * v, 0.0}},
        fmt::format("[van_der_waals]\nhamaker = {}\nmin_separation = {}\nrange = {}\n", a, h0, h_c),
        fmt::format("normal = \"walton_braun\"\nstiffness = {}", k1));
    for (const char* key : {"restitution = 1.0\n", "restitution = 1.0\n"})
      text.replace(text.find(key), std::string(key).size(), fmt::format("restitution = {}\n", e));
    const double dt = 0.05 * h0 / v_crit;
    Simulation sim(
        read_case_string(text, "stick.toml", {fmt::format("simulation.time_step={:.17g}", dt)}));
    const ParticleStore& p = sim.particles();
    bool touched = false, parted = false;
    const long steps = std::lround((gap0 / v + 10.0 * contact) / dt);
    for (long s = 0; s < steps && !parted; ++s) {
      sim.advance(1);
      const double gap = separation(sim) - kD;
      touched = touched || gap < 0.0;
      parted = touched && gap > h_c && p.vx[1] - p.vx[0] > 0.0;
    }
    EXPECT_TRUE(touched) << factor;
    EXPECT_EQ(parted, factor > 1.0)
        << "at " << factor << " of the critical speed " << v_crit << " m/s";
  }
}

} // namespace
} // namespace fluidem
