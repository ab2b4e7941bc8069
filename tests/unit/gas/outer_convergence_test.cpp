// The pressure-correction (outer) iterations stop when the mass residual is below
// gas.solver.tolerance and the velocity's estimated distance from the converged solution,
// r / (1 - r) times the last change (r the observed contraction per iteration, the
// a-posteriori bound of a contraction), is below gas.solver.velocity_tolerance (gas_solver.cpp).
// Check of that promise on a bubbling-bed-like flow step (the 2-D Tsuji grid, 15 x 25 cells,
// ideal gas, a distributor at 2.6 m/s superficial with a 10 mm jet at 10x, a bed of porosity
// 0.45 with semi-implicit drag K = 3e4 kg m^-3 s^-1 and a void of porosity 0.9 in it, the
// void moving one cell per step): from the same state, one step with the default tolerances
// and one converged to round-off (tolerance 1e-14, velocity_tolerance 1e-12 m/s) differ by
// at most velocity_tolerance (1e-6 m/s) on every face, over 8 consecutive steps.
#include "gas/gas_solver.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

using namespace fluidem;
using namespace fluidem::gas;

namespace {
GasSettings bed(double tol, double vtol) {
  GasSettings s;
  s.dimension = 2;
  s.cells = {15, 1, 25};
  s.hi = {0.15, 0.0, 0.5};
  s.depth = 0.004;
  s.viscosity = 1.8e-5;
  s.eos = EquationOfState::ideal_gas;
  s.gravity = {0.0, 0.0, -9.81};
  for (auto& b : s.boundary) b.type = BoundaryType::wall_no_slip;
  s.boundary[bottom].type = BoundaryType::inflow;
  s.boundary[bottom].inflow.velocity = 2.6;
  s.boundary[bottom].porosity = 0.4;
  BoundaryRegion jet;
  jet.type = BoundaryType::inflow;
  jet.lo = {0.07, 0.0};
  jet.hi = {0.08, 0.004};
  jet.inflow.velocity = 26.0;
  jet.porosity = 0.4;
  s.boundary[bottom].regions.push_back(jet);
  s.boundary[top].type = BoundaryType::pressure;
  s.tolerance = tol;
  s.velocity_tolerance = vtol;
  return s;
}

// Porosity and drag of step n: the bed up to 0.25 m, the void 3 x 3 cells rising from z = 0.05 m.
void load_bed(GasSolver& gs, int n) {
  const GasGrid& g = gs.grid();
  for (int k = 1; k <= g.n[2]; ++k)
    for (int i = 1; i <= g.n[0]; ++i) {
      const long q = g.idx(i, 1, k);
      const double z = g.lo[2] + (k - 0.5) * g.h[2];
      const bool in_bed = z < 0.25;
      const bool in_void = std::abs(i - 8) <= 1 && k >= 3 + n && k <= 5 + n;
      gs.porosity()[static_cast<std::size_t>(q)] = !in_bed ? 1.0 : (in_void ? 0.9 : 0.45);
    }
  for (int d : {0, 2}) {
    std::vector<double>& K = gs.drag_coefficient(d);
    std::fill(K.begin(), K.end(), 0.0);
    for (int k = 1; k <= g.n[2]; ++k)
      for (int i = 0; i <= g.n[0]; ++i) {
        const long q = g.idx(i, 1, k);
        if (g.lo[2] + (k - 0.5) * g.h[2] < 0.25) K[static_cast<std::size_t>(q)] = 3e4;
      }
  }
}
} // namespace

TEST(OuterIterations, StopWithinTheVelocityToleranceOfTheConvergedStep) {
  const GasSettings loose = bed(1e-8, 1e-6), tight = bed(1e-14, 1e-12);
  GasSolver gs(loose), ref(tight);
  load_bed(gs, 0);
  gs.sync_old_porosity();
  const double dt = 1e-4;
  double worst = 0.0;
  int it_loose = 0, it_tight = 0;
  for (int n = 0; n < 8; ++n) {
    load_bed(gs, n);
    ref.restore(gs.state());
    load_bed(ref, n);
    gs.step(n * dt, dt);
    ref.step(n * dt, dt);
    it_loose += gs.last_iterations();
    it_tight += ref.last_iterations();
    for (int d : {0, 2})
      for (std::size_t q = 0; q < gs.velocity(d).size(); ++q)
        worst = std::max(worst, std::abs(gs.velocity(d)[q] - ref.velocity(d)[q]));
  }
  std::printf("8 steps: %d outer iterations (converged to round-off: %d); max |u - u_converged| "
              "= %.2e m/s (velocity_tolerance %.0e)\n",
              it_loose, it_tight, worst, loose.velocity_tolerance);
  EXPECT_LE(worst, loose.velocity_tolerance);
  EXPECT_LT(it_loose, it_tight); // the test is not vacuous: the default stops earlier
}
