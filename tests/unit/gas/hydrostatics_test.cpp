// Ideal gas at rest in a closed column (no-slip walls), eps = 1, T = 293 K, M = 28.8e-3.
// Reference: p(z) = p0 exp(-M g z / (R T)). The discrete equilibrium of the implemented
// momentum equation, -(p_k+1 - p_k) A + V g (rho_k + rho_k+1) / 2 = 0 with rho = p M / (R T),
// is p_k+1 / p_k = (1 - a) / (1 + a), a = M g dz / (2 R T): checked to 1e-10 relative; it
// agrees with the exponential to O(a^3) per cell (checked to 1e-9 relative over the column).
// Velocity after settling from uniform pressure: |w| < 1e-7 m/s. Gas mass conserved to 1e-10.
#include "gas/gas_solver.hpp"
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

using namespace fluidem;
using namespace fluidem::gas;

TEST(Hydrostatics, IdealGasColumn) {
  GasSettings s;
  s.dimension = 3;
  s.cells = {1, 1, 40};
  s.hi = {0.1, 0.1, 10.0};
  s.eos = EquationOfState::ideal_gas;
  s.gravity = {0.0, 0.0, -9.81};
  for (auto& b : s.boundary) b.type = BoundaryType::wall_no_slip;
  s.tolerance = 1e-12;
  s.velocity_tolerance = 1e-10;
  GasSolver gs(s);
  const GasGrid& g = gs.grid();
  const double m0 = gs.gas_mass();
  double t = 0.0;
  for (int n = 0; n < 300; ++n, t += 0.01) gs.step(t, 0.01);
  double wmax = 0.0;
  for (int k = 0; k <= g.n[2]; ++k) wmax = std::max(wmax, std::abs(gs.velocity(2)[g.idx(1, 1, k)]));
  const double a = s.molar_mass * 9.81 * g.h[2] / (2.0 * gas_constant * s.temperature);
  const double p1 = gs.pressure()[g.idx(1, 1, 1)];
  double err_discrete = 0.0, err_exp = 0.0;
  for (int k = 1; k < g.n[2]; ++k) {
    const double pk = gs.pressure()[g.idx(1, 1, k)], pk1 = gs.pressure()[g.idx(1, 1, k + 1)];
    err_discrete = std::max(err_discrete, std::abs((pk1 / pk) / ((1.0 - a) / (1.0 + a)) - 1.0));
    const double z = k * g.h[2]; // height of cell k + 1 above cell 1
    const double ref = p1 * std::exp(-s.molar_mass * 9.81 * z / (gas_constant * s.temperature));
    err_exp = std::max(err_exp, std::abs(pk1 / ref - 1.0));
  }
  std::printf("max |w| = %.2e m/s, discrete ratio error %.2e, vs exponential %.2e, mass change "
              "%.2e, p_bottom - p_top = %.4f Pa\n",
              wmax, err_discrete, err_exp, std::abs(gs.gas_mass() / m0 - 1.0),
              p1 - gs.pressure()[g.idx(1, 1, g.n[2])]);
  EXPECT_LT(wmax, 1e-7);
  EXPECT_LT(err_discrete, 1e-10);
  EXPECT_LT(err_exp, 1e-9);
  EXPECT_LT(std::abs(gs.gas_mass() / m0 - 1.0), 1e-10);
  // pressure_at: trilinear between cell centres.
  const Vec3 mid = g.cell_centre(1, 1, 10) + Vec3(0.0, 0.0, 0.25 * g.h[2]);
  EXPECT_NEAR(gs.pressure_at(mid),
              0.75 * gs.pressure()[g.idx(1, 1, 10)] + 0.25 * gs.pressure()[g.idx(1, 1, 11)], 1e-8);
}
