// A 3-D box one cell deep between free-slip walls in y carries the 2-D flow. With no velocity
// across y and no shear at the y walls, the y links of the 3-D momentum rows cancel (the
// diffusion and convection coefficients added for them are taken back by the ghost factor +1),
// so the 3-D solution equals the 2-D one to round-off. Two code paths: the 3-D rows interior in
// x and z are the assembly's pseudo-2-D rows (gas_equations.cpp, Kind 2: both y links at the
// wall), the 2-D rows skip y altogether.
// Case: the Tsuji grid (15 x 1 x 25 cells, 0.15 x 0.004 x 0.5 m), ideal gas, bottom inflow of
// 1.8 m/s superficial with a 10 mm jet of 10 m/s, distributor porosity 0.4, pressure top,
// gravity; a porosity and a drag field over the lower half; 20 flow steps of 1e-4 s.
// Tolerance: 1e-12 of the largest value of each field (measured: 0, bitwise equal). Linking the
// 3-D rows' y neighbours to the ghost cells instead of treating them as walls differs by
// 3.2e-10 (checked): free-slip ghosts copy the interior, so only a tight tolerance sees it.
#include "gas/gas_solver.hpp"
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

using namespace fluidem;
using namespace fluidem::gas;

namespace {

struct Fields {
  std::vector<double> ux, uz, p; // interior faces / cells, in the same order in 2-D and 3-D
};

Fields run(int dimension) {
  GasSettings s;
  s.dimension = dimension;
  s.cells = {15, 1, 25};
  s.hi = {0.15, 0.004, 0.5};
  s.depth = 0.004;
  s.gravity = {0.0, 0.0, -9.81};
  for (auto& b : s.boundary) b.type = BoundaryType::wall_free_slip;
  s.boundary[bottom].type = BoundaryType::inflow;
  s.boundary[bottom].inflow.velocity = 1.8;
  s.boundary[bottom].porosity = 0.4;
  s.boundary[bottom].regions.push_back(
      {BoundaryType::inflow, {0.07, 0.0}, {0.08, 0.004}, {InflowMode::constant, 10.0}, 0.4, 0.0});
  s.boundary[top].type = BoundaryType::pressure;
  s.boundary[top].pressure = 101325.0;
  GasSolver gs(s);
  const GasGrid& g = gs.grid();
  for (int k = 1; k <= g.n[2]; ++k)
    for (int i = 1; i <= g.n[0]; ++i) {
      const auto q = static_cast<std::size_t>(g.idx(i, 1, k));
      if (k <= 12) gs.porosity()[q] = 0.45 + 0.1 * std::sin(0.7 * i) * std::cos(0.3 * k);
      for (int d : {0, 2})
        if (k <= 12) gs.drag_coefficient(d)[q] = 2e3 * (1.0 + 0.5 * std::cos(0.5 * i + k));
    }
  gs.sync_old_porosity();
  for (int n = 0; n < 20; ++n) gs.step(n * 1e-4, 1e-4);
  Fields f;
  for (int k = 1; k <= g.n[2]; ++k)
    for (int i = 0; i <= g.n[0]; ++i) {
      const auto q = static_cast<std::size_t>(g.idx(i, 1, k));
      f.ux.push_back(gs.velocity(0)[q]);
      if (i >= 1) f.p.push_back(gs.pressure()[q]);
    }
  for (int k = 0; k <= g.n[2]; ++k)
    for (int i = 1; i <= g.n[0]; ++i)
      f.uz.push_back(gs.velocity(2)[static_cast<std::size_t>(g.idx(i, 1, k))]);
  return f;
}

double max_rel_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double scale = 0.0, diff = 0.0;
  for (std::size_t n = 0; n < a.size(); ++n) {
    scale = std::max(scale, std::abs(a[n]));
    diff = std::max(diff, std::abs(a[n] - b[n]));
  }
  return diff / scale;
}

} // namespace

TEST(OneCellDeepBox, FreeSlipWallsInYCarryThe2DFlow) {
  const Fields two = run(2), three = run(3);
  ASSERT_EQ(two.ux.size(), three.ux.size());
  const double dux = max_rel_diff(two.ux, three.ux), duz = max_rel_diff(two.uz, three.uz);
  std::vector<double> p2 = two.p, p3 = three.p; // pressure relative to the top pressure
  for (double& v : p2) v -= 101325.0;
  for (double& v : p3) v -= 101325.0;
  const double dp = max_rel_diff(p2, p3);
  std::printf("3-D one cell deep against 2-D: max rel. difference u_x %.2e, u_z %.2e, p %.2e\n",
              dux, duz, dp);
  // The flow is 2-D and not trivial: the jet makes a horizontal velocity.
  double ux_max = 0.0;
  for (double v : two.ux) ux_max = std::max(ux_max, std::abs(v));
  EXPECT_GT(ux_max, 0.01);
  EXPECT_LT(dux, 1e-12);
  EXPECT_LT(duz, 1e-12);
  EXPECT_LT(dp, 1e-12);
}
