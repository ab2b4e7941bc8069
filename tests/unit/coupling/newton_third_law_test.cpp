// Newton's third law of the scheme-3 exchange [Zhu07 §3.2]: 300 random particles (d = 1-3 mm,
// random velocities) inside a 3-D grid of 8 x 6 x 10 cells of 5 mm, nonuniform gas velocity,
// drag closure ergun_wen_yu (and beetstra). With the gas velocity used for the particles:
//   sum_i drag_i + sum_faces applied_source * V_cell = 0,
// to 1e-10 relative to sum_i |drag_i| (per component), before and after a change of the gas
// velocity (the drag after the gas step, update_particle_forces). Particles are kept one cell away
// from the domain boundary so every stencil face is a solved face (near walls the weights on
// boundary faces are handed to the solved faces; see exchange.hpp). Schemes 1/2 are accepted
// (tested in exchange_schemes_test), and so is gas Model B.
// Model B (exchange.hpp: the particle gets f_pf,i = V_i K_i/eps_i (u_i - v_i) - V_i rho_i g, the
// gas -sum f_pf,i / V_cell, the buoyancy part through explicit_source), scheme 3 and scheme 2,
// gravity (1, -2, -9.81) m/s^2 (all three components used):
//   sum_i (drag_i + pres_i) + sum_faces applied_source V_cell = 0, 1e-10 relative to
//   sum_i (|drag_i| + |pres_i|), before and after the change of u; the buoyancy part alone,
//   sum_i pres_i + sum_faces explicit_source V_cell = 0, 1e-10 relative to sum_i |pres_i| (it is
//   ~1e-4 of the drag, so the first check alone would not see it); and Archimedes,
//   sum_i pres_i = -rho g sum_i V_i (uniform rho), 1e-12 relative.
#include "core/error.hpp"
#include "coupling/exchange.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <random>

using namespace fluidem;
using namespace fluidem::coupling;

namespace {
void run(const std::string& model, gas::PressureModel gas_model = gas::PressureModel::A,
         ExchangeScheme scheme = ExchangeScheme::scheme3) {
  const bool model_b = gas_model == gas::PressureModel::B;
  gas::GasSettings s;
  s.model = gas_model;
  if (model_b) s.gravity = {1.0, -2.0, -9.81};
  s.cells = {8, 6, 10};
  s.hi = {0.04, 0.03, 0.05};
  s.eos = gas::EquationOfState::incompressible;
  gas::GasSolver gs(s);
  const gas::GasGrid& g = gs.grid();
  for (int k = 0; k < g.padded[2]; ++k)
    for (int j = 0; j < g.padded[1]; ++j)
      for (int i = 0; i < g.padded[0]; ++i)
        for (int d = 0; d < 3; ++d) {
          const Vec3 x = g.face_centre(d, i, j, k);
          gs.velocity(d)[static_cast<std::size_t>(g.idx(i, j, k))] =
              std::sin(100.0 * x[0] + d) * std::cos(70.0 * x[2]) + 0.5 * std::sin(130.0 * x[1]);
        }
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> ux(0.005, 0.035), uy(0.005, 0.025), uz(0.005, 0.045),
      rad(0.0005, 0.0015), vel(-1.0, 1.0);
  ParticleStore p;
  for (int n = 0; n < 300; ++n)
    p.add({ux(rng), uy(rng), uz(rng)}, {vel(rng), vel(rng), vel(rng)}, rad(rng), 2500.0, 0, n);
  CouplingSettings c;
  c.drag = model;
  c.d_mean = 0.002;
  c.scheme = scheme;
  validate(c, s);
  update_porosity(gs, p, c);
  ParticleGasForces f;
  compute_particle_forces(gs, p, c, f);
  deposit_momentum_source(gs, p, f);
  if (model_b) { // the buoyancy terms: Archimedes, and the gas gets their exact opposite
    double vol = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
      vol += 4.0 / 3.0 * std::numbers::pi * std::pow(p.radius[i], 3);
    for (int d = 0; d < 3; ++d) {
      const std::vector<double>& pr = d == 0 ? f.pres_x : (d == 1 ? f.pres_y : f.pres_z);
      double sum_p = 0.0, abs_p = 0.0, sum_g = 0.0;
      for (double x : pr) {
        sum_p += x;
        abs_p += std::abs(x);
      }
      for (double x : gs.explicit_source(d)) sum_g += x * g.cell_volume();
      const double archimedes = -s.density * s.gravity[d] * vol;
      std::printf("Model B, scheme %d, component %d: sum buoyancy %.6e N (rho g V: %.6e N), gas "
                  "%.6e N, rel. imbalance %.2e\n",
                  static_cast<int>(scheme) + 1, d, sum_p, archimedes, sum_g,
                  std::abs(sum_p + sum_g) / abs_p);
      EXPECT_LT(std::abs(sum_p + sum_g) / abs_p, 1e-10);
      EXPECT_NEAR(sum_p / archimedes, 1.0, 1e-12);
    }
  }
  // The gas step changes u; the particles then get c_i (u_new - v_i) (update_particle_forces),
  // and applied_source uses u_new too: the balance must hold for the new field as well.
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      for (int d = 0; d < 3; ++d)
        for (double& u : gs.velocity(d)) u = 0.7 * u + 0.3;
      update_particle_forces(gs, p, f);
    }
    for (int d = 0; d < 3; ++d) {
      const std::vector<double>& dr = d == 0 ? f.drag_x : (d == 1 ? f.drag_y : f.drag_z);
      const std::vector<double>& pr = d == 0 ? f.pres_x : (d == 1 ? f.pres_y : f.pres_z);
      double sum_p = 0.0, abs_p = 0.0, sum_g = 0.0;
      for (std::size_t i = 0; i < dr.size(); ++i) { // Model A: the gas gets minus the drag only
        const double x = model_b ? dr[i] + pr[i] : dr[i];
        sum_p += x;
        abs_p += std::abs(dr[i]) + (model_b ? std::abs(pr[i]) : 0.0);
      }
      for (double x : gs.applied_source(d)) sum_g += x * g.cell_volume();
      const double rel = std::abs(sum_p + sum_g) / abs_p;
      std::printf("%s, Model %s, scheme %d, component %d: sum particle force %.6e N, sum gas "
                  "source %.6e N, rel. imbalance %.2e\n",
                  model.c_str(), model_b ? "B" : "A", static_cast<int>(scheme) + 1, d, sum_p, sum_g,
                  rel);
      EXPECT_LT(rel, 1e-10);
    }
  }
}
} // namespace

TEST(NewtonThirdLaw, Scheme3ErgunWenYu) {
  run("ergun_wen_yu");
}
TEST(NewtonThirdLaw, Scheme3Beetstra) {
  run("beetstra");
}

TEST(NewtonThirdLaw, ModelBScheme3ErgunWenYu) {
  run("ergun_wen_yu", gas::PressureModel::B, ExchangeScheme::scheme3);
}
TEST(NewtonThirdLaw, ModelBScheme2ErgunWenYu) {
  run("ergun_wen_yu", gas::PressureModel::B, ExchangeScheme::scheme2);
}

TEST(NewtonThirdLaw, SchemesAndModelBAreAccepted) {
  gas::GasSettings s;
  CouplingSettings c;
  c.scheme = ExchangeScheme::scheme1; // implemented [Zhu07 §3.2]: accepted
  EXPECT_NO_THROW(validate(c, s));
  c.scheme = ExchangeScheme::scheme2;
  EXPECT_NO_THROW(validate(c, s));
  c.scheme = ExchangeScheme::scheme3;
  s.model = gas::PressureModel::B; // implemented (exchange.hpp): accepted
  EXPECT_NO_THROW(validate(c, s));
}
