// [body_force] in a run (integrate/simulation.cpp).
// 1. One particle, no fluid, no gravity, at rest at x0 in the sinusoidal_cube field (A = 0.1 m/s2,
//    wavelength = L = 0.1 m, periodic box): its path follows the Taylor series of x'' = a(x)
//    from rest, x(t) = x0 + a0 t^2/2 + (J a0) t^4/24 + O(t^6) (J = da/dx at x0; the t^3 and t^5
//    terms carry the initial velocity and vanish). a and J are written out here from the formula
//    a = A (cos ky cos kz, cos kz cos kx, cos kx cos ky), not taken from the code. At t = 0.2 s:
//    a0 t^2/2 ~ 2 mm, the t^4 term ~ 40 um, the remainder ~ A^3 k^2 t^6 / 720 = 0.35 um; the
//    integrators' error is O(DT^2) (soft: velocity Verlet; hard: kick-drift-kick halves around
//    the flights, DT = 1e-3 s) ~ 1e-9 m. Tolerance 2 um: fails if the t^4 term were missing.
//    Both engines.
// 2. One 1 mm glass-like sphere (2700 kg/m3) settling under uniform gravity through water at rest
//    (1000 kg/m3, 1.78e-3 Pa s) in a closed box, hard-sphere engine coupled to the incompressible
//    fluid (Model A: buoyancy from -V grad p of the hydrostatic water), drag wen_yu (Schiller-
//    Naumann as eps -> 1; eps = 0.9995 in 10 mm cells): after 0.4 s (~17 relaxation times) the
//    settling speed equals coupling::drag::terminal_velocity (Schiller-Naumann, Re ~ 100) within
//    3% (the fluid the particle drags along in its cell, ~1%; no added mass in either).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "coupling/drag/terminal_velocity.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

constexpr double L = 0.1, A = 0.1;

std::string one_particle_case(const std::string& engine) {
  return "[simulation]\nengine = \"" + engine + "\"\nend_time = 1.0\ngravity = [0.0, 0.0, 0.0]\n" +
         (engine == "hard_sphere" ? "time_step = 1e-3\n" : "") +
         "[domain]\nlo = [0, 0, 0]\nhi = [0.1, 0.1, 0.1]\nperiodic = [true, true, true]\n"
         "[body_force]\ntype = \"sinusoidal_cube\"\namplitude = 0.1\nwavelength = 0.1\n"
         "[[species]]\nname = \"s\"\ndiameter = 0.005\ndensity = 2700\n"
         "[[insert]]\nspecies = \"s\"\ncount = 1\n";
}

TEST(BodyForceRun, SingleParticleFollowsTaylorSeries) {
  const double k = 2.0 * std::numbers::pi / L;
  const std::array<double, 3> x0{0.013, 0.031, 0.047};
  const double cx = std::cos(k * x0[0]), cy = std::cos(k * x0[1]), cz = std::cos(k * x0[2]);
  const double sx = std::sin(k * x0[0]), sy = std::sin(k * x0[1]), sz = std::sin(k * x0[2]);
  const std::array<double, 3> a0{A * cy * cz, A * cz * cx, A * cx * cy};
  // J[i][j] = d a_i / d x_j.
  const double J[3][3] = {{0.0, -A * k * sy * cz, -A * k * cy * sz},
                          {-A * k * cz * sx, 0.0, -A * k * sz * cx},
                          {-A * k * sx * cy, -A * k * cx * sy, 0.0}};
  for (const std::string engine : {"soft_sphere", "hard_sphere"}) {
    SCOPED_TRACE(engine);
    Simulation sim(read_case_string(one_particle_case(engine), "case.toml"));
    ParticleStore& p = sim.particles();
    p.x[0] = x0[0], p.y[0] = x0[1], p.z[0] = x0[2];
    p.vx[0] = p.vy[0] = p.vz[0] = 0.0;
    sim.advance(std::lround(0.2 / sim.time_step()));
    const double t = sim.time(); // 0.2 s to within a step
    const std::array<double, 3> x{p.x[0], p.y[0], p.z[0]};
    for (int i = 0; i < 3; ++i) {
      const auto u = static_cast<std::size_t>(i);
      double ja = 0.0;
      for (int j = 0; j < 3; ++j) ja += J[i][j] * a0[static_cast<std::size_t>(j)];
      const double ref = x0[u] + 0.5 * a0[u] * t * t + ja * std::pow(t, 4) / 24.0;
      EXPECT_NEAR(x[u], ref, 2e-6) << "axis " << i << ", t^4 term " << ja * std::pow(t, 4) / 24;
    }
  }
}

TEST(BodyForceRun, SettlingInWaterReachesTerminalVelocity) {
  const double d = 1e-3, rho_p = 2700.0, rho = 1000.0, mu = 1.78e-3, g = 9.81;
  const std::string text =
      "[simulation]\nengine = \"hard_sphere\"\nend_time = 0.4\ntime_step = 1e-4\n"
      "gravity = [0.0, 0.0, -9.81]\n"
      "[domain]\nlo = [0, 0, 0]\nhi = [0.02, 0.02, 0.2]\n"
      "[[species]]\nname = \"s\"\ndiameter = 0.001\ndensity = 2700\n"
      "[[insert]]\nspecies = \"s\"\ncount = 1\n"
      "[gas]\ncells = [2, 2, 20]\neos = \"incompressible\"\ndensity = 1000.0\n"
      "viscosity = 0.00178\nmodel = \"A\"\n[coupling]\ndrag = \"wen_yu\"\n";
  Simulation sim(read_case_string(text, "case.toml"));
  ParticleStore& p = sim.particles();
  p.x[0] = 0.0103, p.y[0] = 0.0098, p.z[0] = 0.19;
  p.vx[0] = p.vy[0] = p.vz[0] = 0.0;
  sim.advance(std::lround(0.4 / sim.time_step()));
  coupling::drag::TerminalVelocityInput in;
  in.d = d, in.rho_p = rho_p, in.rho = rho, in.mu = mu, in.g = g;
  const auto ref = coupling::drag::terminal_velocity(in);
  std::printf("settling speed %.5g m/s, Schiller-Naumann %.5g m/s (Re %.3g), z = %.4g m\n",
              -p.vz[0], ref.velocity, ref.reynolds, p.z[0]);
  EXPECT_GT(p.z[0], 0.01); // still falling freely, clear of the floor
  EXPECT_NEAR(-p.vz[0] / ref.velocity, 1.0, 0.03);
  EXPECT_NEAR(p.vx[0], 0.0, 1e-3 * ref.velocity);
}

} // namespace
} // namespace fluidem
