// coupling.mode and coupling.particle_force (integrate/gas_coupling.cpp, coupling/exchange.cpp;
// docs/coupling.md "Coupling modes", "Particle force forms").
//  - one_way: the gas is solved as in the empty domain, so its fields after 200 flow steps of a
//    bed blown from below are BITWISE those of the same run with other particles (2.5x denser,
//    elsewhere), and differ from the two_way run's (the test can fail).
//  - frozen: the prescribed field u = U + G x is what a particle sees (trilinear interpolation of
//    a linear field is exact: 1e-12), the hydrostatic pressure gives the buoyancy -V rho g in the
//    pressure-gradient form (1e-9), and the gas never changes (bitwise).
//  - a single sphere settling in frozen quiescent water reaches the terminal velocity of its
//    closure in each form, computed here from the published formulas (not the C++): "buoyancy"
//    with wen_yu, V K/eps v = (m - rho V) g [Zhu07 §3.1, Deen07 eq. 4]; "total" with
//    wen_yu_single, V K_single v = (m - rho V) g [Hoomans96 eq. 34-39 with buoyancy];
//    "pressure_gradient" with wen_yu, V K v = (m - rho V) g [Zhu07 eq. 5]; to 1e-6 relative
//    after 40 relaxation times.
//  - the forms that do not go with the gas model or the closure are input errors naming the keys.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "integrate/gas_coupling.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

std::string blown_bed(const std::string& mode, double density, double x_shift) {
  return "[simulation]\nend_time = 1.0\ngravity = [0.0, 0.0, -9.81]\n"
         "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.01, 0.01, 0.04]\n"
         "[[species]]\nname = \"s\"\ndiameter = 0.001\ndensity = " +
         std::to_string(density) +
         "\n[[insert]]\nspecies = \"s\"\ncount = 150\nseed = 7\n"
         "region = { lo = [" +
         std::to_string(x_shift) +
         ", 0.0, 0.0], hi = [0.01, 0.01, 0.02] }\n"
         "[gas]\ncells = [3, 3, 12]\ntime_step = 1e-4\neos = \"incompressible\"\ndensity = 1.2\n"
         "viscosity = 1.8e-5\n"
         "[gas.boundary.bottom]\ntype = \"inflow\"\nvelocity = 0.8\n"
         "[gas.boundary.top]\ntype = \"pressure\"\n"
         "[coupling]\ndrag = \"wen_yu\"\nmode = \"" +
         mode + "\"\n";
}

/// Every gas field after 200 flow steps.
std::vector<std::vector<double>> gas_after(const std::string& text) {
  Simulation sim(read_case_string(text, "case.toml"));
  sim.advance(static_cast<long>(std::llround(200 * 1e-4 / sim.time_step()))); // gas.time_step
  const gas::GasSolver& gs = sim.gas()->solver();
  return {gs.velocity(0), gs.velocity(1), gs.velocity(2), gs.pressure()};
}

TEST(CouplingModes, OneWayGasIsBitwiseThatOfTheEmptyDomain) {
  const auto a = gas_after(blown_bed("one_way", 2500.0, 0.0));
  const auto b = gas_after(blown_bed("one_way", 1000.0, 0.004));
  const auto c = gas_after(blown_bed("two_way", 2500.0, 0.0));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t f = 0; f < a.size(); ++f) EXPECT_EQ(a[f], b[f]) << "field " << f;
  bool differs = false;
  for (std::size_t f = 0; f < a.size(); ++f) differs = differs || a[f] != c[f];
  EXPECT_TRUE(differs) << "the two-way gas should feel the particles";
}

std::string frozen_case(const std::string& extra) {
  return "[simulation]\nend_time = 1.0\ngravity = [0.0, 0.0, -9.81]\n"
         "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.02, 0.02, 0.02]\n"
         "[[species]]\nname = \"s\"\ndiameter = 0.0002\ndensity = 2500\n"
         "[[insert]]\nspecies = \"s\"\ncount = 1\n"
         "[gas]\ncells = [4, 4, 4]\neos = \"incompressible\"\ndensity = 1000.0\n"
         "viscosity = 1e-3\n[coupling]\nmode = \"frozen\"\n" +
         extra;
}

TEST(CouplingModes, FrozenFieldIsWhatTheParticleSeesAndNeverChanges) {
  // u = (1e-3 + 0.5 z, 2e-3 - 0.3 x, 0): a linear field, exactly interpolated.
  Simulation sim(read_case_string(frozen_case("drag = \"wen_yu\"\n"
                                              "frozen_velocity = [1e-3, 2e-3, 0.0]\n"
                                              "frozen_velocity_gradient = [0, 0, 0.5, "
                                              "-0.3, 0, 0, 0, 0, 0]\n"),
                                  "case.toml"));
  ParticleStore& p = sim.particles();
  p.x[0] = 0.0091, p.y[0] = 0.0113, p.z[0] = 0.0087;
  const gas::GasSolver& gs = sim.gas()->solver();
  const auto u0 = gs.velocity(0), p0 = gs.pressure();
  sim.advance(10);
  EXPECT_EQ(gs.velocity(0), u0);
  EXPECT_EQ(gs.pressure(), p0);
  // The forces of the last flow step were computed at the particle's position then: the
  // particle moves by < 1e-7 m over it; the field changes by 0.5 * 1e-7 m/s over that.
  const coupling::ParticleGasForces& f = sim.gas()->exchange();
  EXPECT_NEAR(f.ux[0], 1e-3 + 0.5 * p.z[0], 1e-7);
  EXPECT_NEAR(f.uy[0], 2e-3 - 0.3 * p.x[0], 1e-7);
  EXPECT_NEAR(f.uz[0], 0.0, 1e-15);
  // Hydrostatic pressure: -V grad p = -V rho g exactly (linear field), here +z.
  const double vol = std::numbers::pi * std::pow(2e-4, 3) / 6.0;
  EXPECT_NEAR(f.pres_z[0], vol * 1000.0 * 9.81, 1e-9 * vol * 1000.0 * 9.81);
  EXPECT_NEAR(f.pres_x[0], 0.0, 1e-12 * vol * 1000.0 * 9.81);
}

/// Schiller-Naumann C_d Re [Hoomans96 eq. 38].
double cd_re(double re) {
  return 24.0 * (1.0 + 0.15 * std::pow(re, 0.687));
}

/// The slip v at which coeff(v) v = net weight, by bisection (coeff increasing with v).
template <class F>
double terminal(F coeff, double net) {
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (coeff(mid) * mid < net ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(CouplingModes, SettlingSphereReachesItsFormsTerminalVelocity) {
  const double d = 2e-4, rho_p = 2500.0, rho = 1000.0, mu = 1e-3, g = 9.81;
  const double vol = std::numbers::pi * d * d * d / 6.0;
  const double net = (rho_p - rho) * vol * g;
  struct Form {
    const char* keys;
    int kind; // 0: wen_yu / eps (buoyancy), 1: wen_yu_single (total), 2: wen_yu (Model A)
  };
  for (const Form form : {Form{"drag = \"wen_yu\"\n", 0},
                          Form{"drag = \"wen_yu_single\"\nparticle_force = \"total\"\n", 1},
                          Form{"drag = \"wen_yu\"\n", 2}}) {
    std::string text = frozen_case(form.keys);
    if (form.kind != 2)
      text.replace(text.find("viscosity = 1e-3\n"), 17, "viscosity = 1e-3\nmodel = \"B\"\n");
    Simulation sim(read_case_string(text, "case.toml"));
    ParticleStore& p = sim.particles();
    p.x[0] = 0.0101, p.y[0] = 0.0099, p.z[0] = 0.0150;
    p.vx[0] = p.vy[0] = p.vz[0] = 0.0;
    // Relaxation time m / (3 pi mu d) = 5.6 ms; 0.25 s = 45 of them (the particle falls ~2 mm).
    sim.advance(static_cast<long>(std::llround(0.25 / sim.time_step())));
    const double eps = sim.gas()->exchange().eps[0];
    ASSERT_GT(eps, 0.999);
    const auto coeff = [&](double v) {
      const double re = eps * rho * v * d / mu;
      switch (form.kind) {
      case 0:
        return vol * 0.75 * cd_re(re) * mu * std::pow(eps, -2.65) / (d * d) / eps;
      case 1:
        return vol * 0.75 * cd_re(re) * mu * std::pow(eps, -3.7) / (d * d);
      default:
        return vol * 0.75 * cd_re(re) * mu * std::pow(eps, -2.65) / (d * d);
      }
    };
    const double vt = terminal(coeff, net);
    EXPECT_NEAR(-p.vz[0], vt, 1e-6 * vt) << form.keys;
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

TEST(CouplingModes, FormsThatDoNotFitAreInputErrorsNamingTheKeys) {
  // Model A takes only the pressure-gradient form.
  std::string msg = setup_error(frozen_case("particle_force = \"buoyancy\"\n"));
  EXPECT_NE(msg.find("coupling.particle_force: \"buoyancy\" does not go with gas.model = \"A\""),
            std::string::npos)
      << msg;
  // A total-force closure outside "total", a drag coefficient in "total".
  msg = setup_error(frozen_case("drag = \"wen_yu_single\"\n"));
  EXPECT_NE(msg.find("coupling.drag = \"wen_yu_single\" does not go with "
                     "coupling.particle_force = \"pressure_gradient\""),
            std::string::npos)
      << msg;
  std::string b = frozen_case("drag = \"wen_yu\"\nparticle_force = \"total\"\n");
  b.replace(b.find("viscosity = 1e-3\n"), 17, "viscosity = 1e-3\nmodel = \"B\"\n");
  msg = setup_error(b);
  EXPECT_NE(msg.find("coupling.drag = \"wen_yu\" does not go with coupling.particle_force = "
                     "\"total\""),
            std::string::npos)
      << msg;
  // The frozen field's keys belong to the frozen mode; hold_gas_at_rest to two_way.
  std::string c = frozen_case("frozen_velocity = [0, 0, 0]\n");
  c.replace(c.find("mode = \"frozen\""), 15, "mode = \"one_way\"");
  msg = setup_error(c);
  EXPECT_NE(msg.find("coupling.frozen_velocity: only with mode = \"frozen\""), std::string::npos)
      << msg;
  std::string m = frozen_case("");
  m.replace(m.find("mode = \"frozen\""), 15, "mode = \"three_way\"");
  msg = setup_error(m);
  EXPECT_NE(msg.find("coupling.mode"), std::string::npos) << msg;
}

} // namespace
} // namespace fluidem
