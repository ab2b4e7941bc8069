// One particle settling through still air, coupled to the running gas solver each DT, reaches
// the Schiller-Naumann terminal velocity of coupling::drag::terminal_velocity within 2% (the
// brief's tolerance). Case: glass bead d = 100 um, rho_p = 2500 kg/m3, air rho = 1.2 kg/m3
// (incompressible), mu = 1.8e-5 Pa s, g = 9.81: v_t = 0.553 m/s at Re = 3.7 (intermediate regime,
// the Schiller-Naumann correction is 1 + 0.15 Re^0.687 = 1.37). Closed no-slip box 4 x 4 x 40 cm,
// 4 x 4 x 40 cells of 1 cm, Model A (the pressure force -V grad p in the hydrostatic gas gives
// the buoyancy), drag closure wen_yu (its limit eps -> 1 is Schiller-Naumann; the particle's cell
// has eps = 1 - 5e-7). Per DT = 5e-4 s: forces from the gas, particle velocity updated
// semi-implicitly v' = (v + DT (g + (c u + F_p)/m)) / (1 + DT c/m), x += v' DT, porosity and
// momentum source to the gas, gas step. 0.4 s = 8 relaxation times (measured: -2.3e-4 relative,
// the remaining transient). The particle's own source (~5e-12 N in a 1e-6 m3 cell) and the
// start-up of the hydrostatic gas move the gas at the particle by ~2e-5 m/s (printed; 4e-5 of
// v_t), negligible here; with many particles or small cells it is not.
#include "coupling/drag/terminal_velocity.hpp"
#include "coupling/exchange.hpp"
#include "coupling/interpolation.hpp"
#include <cmath>
#include <gtest/gtest.h>

using namespace fluidem;
using namespace fluidem::coupling;

TEST(TerminalVelocity, SingleBeadInStillAir) {
  const double d = 100e-6, rho_p = 2500.0, rho = 1.2, mu = 1.8e-5, gz = -9.81;
  gas::GasSettings s;
  s.cells = {4, 4, 40};
  s.hi = {0.04, 0.04, 0.4};
  s.eos = gas::EquationOfState::incompressible;
  s.density = rho;
  s.viscosity = mu;
  s.gravity = {0.0, 0.0, gz};
  for (auto& b : s.boundary) b.type = gas::BoundaryType::wall_no_slip;
  gas::GasSolver gs(s);
  ParticleStore p;
  p.add({0.0213, 0.0187, 0.38}, {0, 0, 0}, 0.5 * d, rho_p, 0, 0);
  CouplingSettings c;
  c.drag = "wen_yu";
  validate(c, s);
  update_porosity(gs, p, c);
  gs.sync_old_porosity();
  ParticleGasForces f;
  const double dt = 5e-4;
  double t = 0.0;
  for (int n = 0; n < 800; ++n, t += dt) {
    compute_particle_forces(gs, p, c, f);
    const double m = p.mass[0], ci = f.coeff[0];
    const std::array<double, 3> g{0.0, 0.0, gz};
    std::array<double*, 3> v{&p.vx[0], &p.vy[0], &p.vz[0]};
    std::array<double*, 3> x{&p.x[0], &p.y[0], &p.z[0]};
    const std::array<double, 3> u{f.ux[0], f.uy[0], f.uz[0]};
    const std::array<double, 3> fp{f.pres_x[0], f.pres_y[0], f.pres_z[0]};
    for (int a = 0; a < 3; ++a) {
      const auto k = static_cast<std::size_t>(a);
      *v[k] = (*v[k] + dt * (g[k] + (ci * u[k] + fp[k]) / m)) / (1.0 + dt * ci / m);
      *x[k] += *v[k] * dt;
    }
    update_porosity(gs, p, c);
    deposit_momentum_source(gs, p, f);
    gs.step(t, dt);
  }
  drag::TerminalVelocityInput in;
  in.d = d;
  in.rho_p = rho_p;
  in.rho = rho;
  in.mu = mu;
  in.g = -gz;
  const drag::TerminalVelocity ref = drag::terminal_velocity(in);
  double umax = 0.0;
  for (int a = 0; a < 3; ++a)
    for (double x : gs.velocity(a)) umax = std::max(umax, std::abs(x));
  const double vz = -p.vz[0];
  std::printf("settling speed %.6f m/s (z = %.4f m), Schiller-Naumann terminal %.6f m/s at Re = "
              "%.3f, rel. error %.2e; gas at the particle %.2e m/s, max gas speed %.2e m/s\n",
              vz, p.z[0], ref.velocity, ref.reynolds, vz / ref.velocity - 1.0, std::abs(f.uz[0]),
              umax);
  EXPECT_NEAR(vz / ref.velocity, 1.0, 0.02);
}
