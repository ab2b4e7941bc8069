// [coupling.forces] in a run (integrate/fluid_forces.{hpp,cpp}), one sphere in a frozen or
// solved liquid, each against an independent reference:
//  - release from rest in quiescent liquid, Stokes regime, with added mass 0.5 and the Basset
//    force: v(t)/v_t against the closed-form Basset-Boussinesq-Oseen solution of
//    tools/bbo_reference.py (tests/models/fluid_forces/bbo_release.toml), within 1% of v_t over
//    0..10 time constants; with added mass alone the exponential 1 - exp(-t/tau),
//    tau = (m + m_a)/(3 pi mu d) (1%). The solution in t/tau depends only on the density ratio
//    (its Basset number is sqrt(4.5 rho_f/(pi (rho_p + rho_f/2)))), so the sphere here (3 mm,
//    16 Pa s: Re_t < 1e-4, Schiller-Naumann's correction < 0.1%) stands for the reference's.
//  - the first acceleration from rest (no drag yet, no history) is (m - rho V) g/(m + 0.5 rho V)
//    to 1e-9: the added-mass force is -0.5 rho V dv/dt; a bubble (rho_p = rho_f/1000) starts at
//    ~2 g upwards, stably (the added mass is implicit).
//  - a body-force field acts on the particle's own mass: the first acceleration is
//    m a/(m + 0.5 rho V) (1e-9).
//  - Saffman: a sphere at rest in the frozen shear u = (U_0 + G z, 0, 0) feels 6.46 mu a^2 U
//    sqrt(G/nu) f_Mei along +z (Saffman 1965/68; Mei 1992), f_Mei computed here, to 1e-9.
//  - Magnus: a spinning sphere moving through still liquid: pi a^3 rho (omega x v) (Rubinow &
//    Keller 1961) to 1e-9.
//  - fluid torque: spin-down in still liquid, omega(t) = omega_0 exp(-t/tau_r),
//    tau_r = I/(pi mu d^3) (Stokes), to 1e-9 (the held torque is the exact mean of each step).
//  - bad [coupling.forces] keys are input errors naming the key; virtual mass and Basset need
//    an incompressible fluid.
//  - two-way with every force on: the gas's explicit source (Model A: nothing else is in it)
//    sums to minus the particles' fluid impulses of the step before, over DT, to 1e-12.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <toml++/toml.h>

#include "core/error.hpp"
#include "integrate/gas_coupling.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

constexpr double kPi = std::numbers::pi;

struct Liquid {
  double rho = 1000.0, mu = 16.0;
};

std::string one_sphere(double d, double rho_p, const Liquid& l, double dt,
                       const std::string& forces, const std::string& mode = "frozen",
                       const std::string& gravity = "[0.0, 0.0, -9.81]",
                       const std::string& extra_coupling = "") {
  std::ostringstream s;
  // One sphere, no contact ever: the contact time-step limit does not apply.
  s << "[simulation]\nend_time = 1.0\nforce_time_step = true\ntime_step = " << dt
    << "\ngravity = " << gravity << "\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.1, 0.1, 0.1]\n"
    << "[[species]]\nname = \"s\"\ndiameter = " << d << "\ndensity = " << rho_p
    << "\n[[insert]]\nspecies = \"s\"\ncount = 1\n"
    << "[gas]\ncells = [5, 5, 5]\ntime_step = " << dt
    << "\neos = \"incompressible\"\ndensity = " << l.rho << "\nviscosity = " << l.mu
    << "\n[coupling]\ndrag = \"wen_yu\"\nmode = \"" << mode << "\"\n"
    << extra_coupling << "[coupling.forces]\n"
    << forces;
  return s.str();
}

Simulation make(const std::string& text) {
  return Simulation(read_case_string(text, "case.toml"));
}

void place(Simulation& sim, double x, double y, double z) {
  ParticleStore& p = sim.particles();
  p.x[0] = x, p.y[0] = y, p.z[0] = z;
  p.vx[0] = p.vy[0] = p.vz[0] = 0.0;
  p.wx[0] = p.wy[0] = p.wz[0] = 0.0;
}

TEST(FluidForcesRun, ReleaseFromRestFollowsTheBassetBoussinesqOseenSolution) {
  const toml::table ref = toml::parse_file(std::string(FLUIDEM_SOURCE_DIR) +
                                           "/tests/models/fluid_forces/bbo_release.toml");
  const toml::array* cases = ref["case"].as_array();
  ASSERT_NE(cases, nullptr);
  ASSERT_EQ(cases->size(), 3u);
  for (const toml::node& node : *cases) {
    const toml::table& c = *node.as_table();
    const double ratio = c["rho_p"].value_or(0.0) / c["rho_f"].value_or(1.0);
    const double tau_ref = c["tau"].value_or(0.0);
    const toml::array& times = *c["times"].as_array();
    // Our sphere, with the reference's density ratio: 3 mm in a liquid of 1000 kg/m3 viscous
    // enough for Re_t = 5e-5 (Schiller-Naumann's correction 1.7e-4), in a 0.2 m box of 0.1 m
    // cells (the porosity at it is 1 - 1e-5).
    const double d = 3e-3;
    Liquid l;
    const double rho_p = ratio * l.rho;
    l.mu = std::sqrt(l.rho * (rho_p - l.rho) * 9.81 * d * d * d / (18.0 * 5e-5));
    const double tau = (rho_p + 0.5 * l.rho) * d * d / (18.0 * l.mu);
    const double vt = (rho_p - l.rho) * 9.81 * d * d / (18.0 * l.mu);
    ASSERT_LT(l.rho * vt * d / l.mu, 1e-4) << "Stokes regime";
    for (const bool basset : {true, false}) {
      const double dt = tau / 500.0;
      std::string text = one_sphere(d, rho_p, l, dt,
                                    std::string("virtual_mass = true\nbasset = ") +
                                        (basset ? "true\nbasset_window = 20\n" : "false\n"));
      text.replace(text.find("hi = [0.1, 0.1, 0.1]"), 20, "hi = [0.2, 0.2, 0.2]");
      text.replace(text.find("cells = [5, 5, 5]"), 17, "cells = [2, 2, 2]");
      Simulation sim = make(text);
      place(sim, 0.1, 0.1, 0.1);
      const toml::array& values = *c[basset ? "v_over_vt" : "v_over_vt_no_basset"].as_array();
      double worst = 0.0;
      for (std::size_t k = 0; k < times.size(); ++k) {
        const double t_over_tau = times.get(k)->value_or(0.0) / tau_ref;
        if (t_over_tau > 10.0) break;
        // The reference times are multiples of tau/4: whole numbers of steps of tau/500.
        const long steps = std::lround(t_over_tau * tau / dt);
        sim.advance(steps - sim.step_count());
        const double v = -sim.particles().vz[0] / vt;
        worst = std::max(worst, std::abs(v - values.get(k)->value_or(0.0)));
      }
      EXPECT_LT(worst, 0.01) << c["name"].value_or("?") << (basset ? " with" : " without")
                             << " Basset";
      std::printf("%s %s Basset: max |v - v_ref|/v_t = %.2e\n", c["name"].value_or("?"),
                  basset ? "with" : "without", worst);
    }
  }
}

TEST(FluidForcesRun, FirstAccelerationCarriesTheAddedMass) {
  const Liquid l{1000.0, 1e-3};
  for (const double rho_p : {2700.0, 1.0}) { // glass; a "bubble" of 1/1000 the liquid's density
    const double d = 1e-3, dt = 1e-6;
    Simulation sim = make(one_sphere(d, rho_p, l, dt, "virtual_mass = true\n"));
    place(sim, 0.05, 0.05, 0.05);
    sim.advance(1);
    const double vol = kPi * d * d * d / 6.0, m = rho_p * vol;
    const double a = (m - l.rho * vol) * -9.81 / (m + 0.5 * l.rho * vol);
    EXPECT_NEAR(sim.particles().vz[0] / dt, a, 1e-9 * std::abs(a)) << rho_p;
    sim.advance(20000); // 20 ms: settles (or rises) at its terminal velocity, stably
    EXPECT_TRUE(std::isfinite(sim.particles().vz[0]));
    EXPECT_EQ(std::signbit(sim.particles().vz[0]), rho_p > l.rho);
  }
}

TEST(FluidForcesRun, ABodyForceFieldActsOnTheParticlesOwnMassOnly) {
  // [body_force] (the [Chang08] field): a(x) per unit of the particle's mass; with the added
  // inertia the first acceleration is m a / (m + 0.5 rho V) (no gravity, no buoyancy: the liquid
  // does not feel the field). At the box centre with wavelength 0.1 m, a = (A, A, A).
  const Liquid l{1000.0, 1e-3};
  const double d = 1e-3, rho_p = 2500.0, dt = 1e-6, A = 2.0;
  std::string text =
      one_sphere(d, rho_p, l, dt, "virtual_mass = true\n", "frozen", "[0.0, 0.0, 0.0]");
  text += "[body_force]\ntype = \"sinusoidal_cube\"\namplitude = 2.0\nwavelength = 0.1\n";
  Simulation sim = make(text);
  place(sim, 0.05, 0.05, 0.05);
  sim.advance(1);
  const double vol = kPi * d * d * d / 6.0, m = rho_p * vol;
  const double a = m * A / (m + 0.5 * l.rho * vol);
  const ParticleStore& p = sim.particles();
  for (const double v : {p.vx[0], p.vy[0], p.vz[0]}) EXPECT_NEAR(v / dt, a, 1e-9 * a);
}

TEST(FluidForcesRun, SaffmanLiftInALinearShearIsSaffmansTimesMeis) {
  const Liquid l{1000.0, 1e-3};
  const double d = 2e-4, G = 20.0, z0 = 0.05;
  Simulation sim =
      make(one_sphere(d, 2500.0, l, 1e-5, "saffman = true\n", "frozen", "[0.0, 0.0, 0.0]",
                      "frozen_velocity = [-0.99, 0.0, 0.0]\n"
                      "frozen_velocity_gradient = [0, 0, 20, 0, 0, 0, 0, 0, 0]\n"));
  place(sim, 0.05, 0.05, z0);
  sim.advance(1);
  // u = -0.99 + G z: the slip at the sphere (at rest) is U = 0.01 m/s (Re_p = 2, Re_s = 0.8).
  const double U = -0.99 + G * z0, a = 0.5 * d, nu = l.mu / l.rho;
  // Mei (1992): f = (1 - 0.3314 sqrt(b)) exp(-Re_p/10) + 0.3314 sqrt(b), b = Re_s/(2 Re_p).
  const double re_p = l.rho * U * d / l.mu, re_s = l.rho * d * d * G / l.mu;
  const double b = 0.5 * re_s / re_p;
  ASSERT_LE(re_p, 40.0);
  const double f = (1.0 - 0.3314 * std::sqrt(b)) * std::exp(-0.1 * re_p) + 0.3314 * std::sqrt(b);
  const double lift = 6.46 * l.mu * a * a * U * std::sqrt(G / nu) * f;
  const auto& F = sim.gas()->fluid_forces()->force();
  EXPECT_NEAR(F[2][0], lift, 1e-9 * lift);
  EXPECT_NEAR(F[0][0], 0.0, 1e-12 * lift);
  EXPECT_NEAR(F[1][0], 0.0, 1e-12 * lift);
}

TEST(FluidForcesRun, MagnusLiftOfASpinningSphereAtLowRe) {
  const Liquid l{1000.0, 1e-3};
  const double d = 1e-4;
  Simulation sim = make(
      one_sphere(d, 2500.0, l, 1e-5, "magnus = \"rubinow_keller\"\n", "frozen", "[0.0, 0.0, 0.0]"));
  place(sim, 0.05, 0.05, 0.05);
  ParticleStore& p = sim.particles();
  p.vx[0] = 1e-3; // Re = 0.1
  p.wy[0] = 20.0; // omega x v = (0, 20, 0) x (1e-3, 0, 0) = (0, 0, -0.02)
  sim.advance(1);
  const double a = 0.5 * d;
  const double lift = kPi * a * a * a * l.rho * -0.02;
  const auto& F = sim.gas()->fluid_forces()->force();
  EXPECT_NEAR(F[2][0], lift, 1e-9 * std::abs(lift));
  EXPECT_NEAR(F[0][0], 0.0, 1e-12 * std::abs(lift));
}

TEST(FluidForcesRun, SpinDownInStillLiquidIsExponential) {
  const Liquid l{1000.0, 1e-3};
  const double d = 1e-3, rho_p = 2500.0, dt = 1e-4;
  Simulation sim =
      make(one_sphere(d, rho_p, l, dt, "torque = \"stokes\"\n", "frozen", "[0.0, 0.0, 0.0]"));
  place(sim, 0.05, 0.05, 0.05);
  sim.particles().wz[0] = 10.0;
  const double m = rho_p * kPi * d * d * d / 6.0, inertia = 0.1 * m * d * d;
  const double tau_r = inertia / (kPi * l.mu * d * d * d);
  const long steps = std::lround(2.0 * tau_r / dt);
  sim.advance(steps);
  const double expected = 10.0 * std::exp(-static_cast<double>(steps) * dt / tau_r);
  EXPECT_NEAR(sim.particles().wz[0], expected, 1e-9 * 10.0);
}

TEST(FluidForcesRun, TheGasReceivesMinusTheParticlesFluidImpulse) {
  const Liquid l{1000.0, 1e-3};
  const double d = 2e-3, dt = 1e-4;
  Simulation sim = make(one_sphere(d, 2500.0, l, dt,
                                   "virtual_mass = true\nbasset = true\nsaffman = true\n"
                                   "magnus = \"oesterle_bui_dinh\"\ntorque = \"dennis\"\n",
                                   "two_way"));
  place(sim, 0.043, 0.051, 0.062);
  ParticleStore& p = sim.particles();
  p.vx[0] = 0.02, p.wy[0] = 30.0;
  sim.advance(5);
  const FluidForces& ff = *sim.gas()->fluid_forces();
  // The impulse rate of the step before, J/DT, as the fluid forces know it; the gas's explicit
  // source of this step, integrated over the grid.
  const std::vector<double> v_before{p.vx[0], p.vy[0], p.vz[0]};
  const auto state = ff.state();
  std::array<double, 3> physical{}, held_before{};
  for (const auto& [name, v] : state)
    for (int a = 0; a < 3; ++a) {
      if (name == std::string("physical_") + "xyz"[a]) physical[static_cast<std::size_t>(a)] = v[0];
      if (name == std::string("held_") + "xyz"[a]) held_before[static_cast<std::size_t>(a)] = v[0];
    }
  (void)held_before;
  const double mx = sim.gas()->added_inertia(d);
  const std::array<double, 3> v_start = [&] {
    std::array<double, 3> s{};
    for (const auto& [name, v] : state)
      for (int a = 0; a < 3; ++a)
        if (name == std::string("v_start_") + "xyz"[a]) s[static_cast<std::size_t>(a)] = v[0];
    return s;
  }();
  sim.advance(1); // the flow step that deposits the reaction
  const gas::GasSolver& gs = sim.gas()->solver();
  for (int a = 0; a < 3; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    const double rate = physical[ua] - mx * (v_before[ua] - v_start[ua]) / dt;
    double sum = 0.0;
    for (const double s : gs.explicit_source(a)) sum += s * gs.grid().cell_volume();
    EXPECT_NEAR(sum, -rate, 1e-12 * std::max(1e-12, std::abs(rate))) << "axis " << a;
  }
}

std::string setup_error(const std::string& text) {
  try {
    Simulation sim(read_case_string(text, "case.toml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FluidForcesRun, BadKeysAreInputErrorsNamingTheKey) {
  const Liquid l{1000.0, 1e-3};
  const auto msg = [&](const std::string& forces) {
    return setup_error(one_sphere(1e-3, 2500.0, l, 1e-5, forces));
  };
  EXPECT_NE(msg("virtual_mass_coefficient = 0.5\n")
                .find("coupling.forces.virtual_mass_coefficient: only with virtual_mass = true"),
            std::string::npos);
  EXPECT_NE(msg("virtual_mass = true\nvirtual_mass_coefficient = -1\n")
                .find("coupling.forces.virtual_mass_coefficient"),
            std::string::npos);
  EXPECT_NE(msg("basset = true\nbasset_window = 0\n").find("coupling.forces.basset_window"),
            std::string::npos);
  EXPECT_NE(msg("magnus = \"fast\"\n").find("coupling.forces.magnus: unknown value \"fast\""),
            std::string::npos);
  EXPECT_NE(msg("lift = true\n").find("coupling.forces.lift"), std::string::npos);
  // The added inertia needs a fluid of fixed density.
  std::string ideal = one_sphere(1e-3, 2500.0, l, 1e-5, "basset = true\n");
  ideal.replace(ideal.find("eos = \"incompressible\""), 22, "eos = \"ideal_gas\"");
  ideal.replace(ideal.find("density = 1000"), 14, "temperature = 293");
  const std::string m = setup_error(ideal);
  EXPECT_NE(m.find("coupling.forces: basset = true needs gas.eos = \"incompressible\""),
            std::string::npos)
      << m;
  EXPECT_EQ(msg("virtual_mass = true\nbasset = true\nsaffman = true\nmagnus = "
                "\"rubinow_keller\"\ntorque = \"stokes\"\n"),
            "");
}

} // namespace
} // namespace fluidem
