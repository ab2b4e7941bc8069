// Discrete mass balance of the compressible solver: 2-D column, inflow at the bottom (ghost
// porosity 0.4), prescribed pressure at the top, porosity changing in time and space, gravity
// on. Per step: (sum eps rho V)_new - (sum eps rho V)_old + dt * (net outflow) = sum of the
// cell imbalances, bounded by gas.solver.tolerance * gas mass. Tolerance: 1e-9 of the mass.
#include "gas/gas_solver.hpp"
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>

using namespace fluidem;
using namespace fluidem::gas;

TEST(MassConservation, CompressibleInflowOutflowVaryingPorosity) {
  GasSettings s;
  s.dimension = 2;
  s.cells = {6, 1, 16};
  s.hi = {0.06, 0.0, 0.16};
  s.depth = 0.01;
  s.eos = EquationOfState::ideal_gas;
  for (auto& b : s.boundary) b.type = BoundaryType::wall_no_slip;
  s.boundary[bottom].type = BoundaryType::inflow;
  s.boundary[bottom].inflow.velocity = 0.5;
  s.boundary[bottom].regions.push_back(
      {BoundaryType::inflow, {0.02, 0.0}, {0.04, 1.0}, {InflowMode::constant, 3.0}, 0.4, 0.0});
  s.boundary[top].type = BoundaryType::pressure;
  s.tolerance = 1e-9;
  GasSolver gs(s);
  const GasGrid& g = gs.grid();
  const double dt = 1e-4;
  double t = 0.0, worst = 0.0;
  for (int n = 0; n < 40; ++n, t += dt) {
    const double m_old = gs.gas_mass();
    for (int k = 1; k <= g.n[2]; ++k)
      for (int i = 1; i <= g.n[0]; ++i) {
        const Vec3 c = g.cell_centre(i, 1, k);
        gs.porosity()[g.idx(i, 1, k)] =
            0.6 +
            0.2 * std::sin(2.0 * std::numbers::pi * (200.0 * (t + dt) + c.z / 0.16 + c.x / 0.06));
      }
    gs.step(t, dt);
    const double imbalance = gs.gas_mass() - m_old + dt * gs.boundary_outflow();
    worst = std::max(worst, std::abs(imbalance) / gs.gas_mass());
    ASSERT_LE(std::abs(imbalance), s.tolerance * gs.gas_mass()) << "step " << n;
  }
  std::printf("worst |mass imbalance| / mass per step = %.2e (tolerance %.0e), last step: %d "
              "iterations, outflow %.4e kg/s\n",
              worst, s.tolerance, gs.last_iterations(), gs.boundary_outflow());
}
