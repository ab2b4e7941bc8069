// Plane Poiseuille flow, incompressible, eps = 1. Reference: u(x) = G/(2 mu) x (h - x).
// Tolerance: 1% of the centreline velocity (max norm); the discrete solution with reflected
// ghost velocities differs from the parabola by G dx^2 / (8 mu) = (dx/h)^2 of the centreline.
#include "gas/gas_solver.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

using namespace fluidem;
using namespace fluidem::gas;

namespace {
GasSettings channel(int dim) {
  GasSettings s;
  s.dimension = dim;
  s.cells = {20, dim == 3 ? 2 : 1, 4};
  s.lo = {0.0, 0.0, 0.0};
  s.hi = {0.01, 0.002, 0.004};
  s.depth = 0.002;
  s.viscosity = 1.8e-5;
  s.eos = EquationOfState::incompressible;
  s.density = 1.2;
  s.gravity = {0.0, 0.0, 0.0};
  for (auto& b : s.boundary) b.type = BoundaryType::wall_no_slip;
  s.boundary[front].type = s.boundary[back].type = BoundaryType::periodic;
  s.boundary[bottom].type = s.boundary[top].type = BoundaryType::periodic;
  s.tolerance = 1e-10;
  s.velocity_tolerance = 1e-9;
  return s;
}

double max_rel_error(const GasSolver& gs, double G, double mu, double h) {
  const GasGrid& g = gs.grid();
  const double uc = G * h * h / (8.0 * mu);
  double err = 0.0;
  for (int k = 1; k <= g.n[2]; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i) {
        const double x = g.cell_centre(i, j, k).x;
        const double ref = G / (2.0 * mu) * x * (h - x);
        err = std::max(err, std::abs(gs.velocity(2)[g.idx(i, j, k)] - ref) / uc);
      }
  return err;
}

void run_body_force(int dim) {
  GasSettings s = channel(dim);
  GasSolver gs(s);
  const double G = 0.5; // N/m^3, body force along +z
  for (auto& v : gs.explicit_source(2)) v = G;
  double t = 0.0;
  for (int n = 0; n < 20; ++n, t += 1.0) gs.step(t, 1.0); // backward Euler: steady quickly
  const double err = max_rel_error(gs, G, s.viscosity, 0.01);
  std::printf("body force %d-D: max error / centreline = %.5f\n", dim, err);
  EXPECT_LT(err, 0.01) << "max error relative to the centreline";
  EXPECT_NEAR(err, 1.0 / 400.0, 2e-4); // the expected (dx/h)^2 offset
  for (double v : gs.velocity(0)) EXPECT_NEAR(v, 0.0, 1e-12);
}
} // namespace

TEST(Poiseuille, BodyForcePeriodic2D) {
  run_body_force(2);
}
TEST(Poiseuille, BodyForcePeriodic3D) {
  run_body_force(3);
}

// Pressure-driven: prescribed pressure at the bottom and top faces (values on the faces).
TEST(Poiseuille, PressureDriven2D) {
  GasSettings s = channel(2);
  s.cells = {20, 1, 8};
  s.hi = {0.01, 0.002, 0.02};
  s.boundary[bottom].type = s.boundary[top].type = BoundaryType::pressure;
  const double H = 0.02, dp = 0.01; // Pa over the channel
  s.boundary[bottom].pressure = 101325.0 + dp;
  s.boundary[top].pressure = 101325.0;
  GasSolver gs(s);
  double t = 0.0;
  // dt = 0.05 s (SIMPLEC converges in ~3 iterations per step; at dt ~ the viscous time it
  // needs many); 6 s = 4 e-folding times of the slowest viscous mode nu pi^2 / h^2.
  const double dt = 0.05;
  for (int n = 0; n < 120; ++n, t += dt) gs.step(t, dt);
  const double err = max_rel_error(gs, dp / H, s.viscosity, 0.01);
  std::printf("pressure-driven 2-D: max error / centreline = %.5f\n", err);
  EXPECT_LT(err, 0.01);
}
