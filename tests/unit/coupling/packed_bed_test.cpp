// Frozen packed bed against the Ergun equation [Hoomans96 eq. 45; Deen07 eq. 3]:
//   -dp/dz = 150 mu (1-eps)^2 U / (eps^3 d^2) + 1.75 rho (1-eps) U^2 / (eps^3 d).
// 2560 fixed spheres (d = 1 mm) on a lattice, spacing d across (x, y) and 0.952 d along z, so
// that eps = 1 - (pi/6) / 0.952 = 0.45 (neighbours along z overlap by 5% of d: a frozen test
// bed, the porosity counts each sphere's full volume). Column 8 x 8 x 38 mm, 2 x 2 x 10 cells
// (each cell holds a whole number of lattice periods, so every interior cell has eps = 0.45
// exactly); air (incompressible, rho = 1.2, mu = 1.8e-5), no gravity, Model A, drag = ergun,
// superficial inflow U = 0.2, 0.5, 1.0 m/s at the bottom (ghost porosity 0.45), pressure at
// the top, free-slip side walls. Coupled each DT = 1e-3 s (forces -> source -> gas step) for 30
// steps. Measured: dp/dz between the cell centres of the middle cells (k = 3..8) against Ergun
// with the cell porosity found there; tolerance 3% (the brief), cell and porous-cube porosity.
#include "coupling/exchange.hpp"
#include <cmath>
#include <gtest/gtest.h>

using namespace fluidem;
using namespace fluidem::coupling;

namespace {
void run(PorosityMethod method, double U) {
  const double d = 1e-3, eps_target = 0.45;
  const double sz = d * (3.14159265358979323846 / 6.0) / (1.0 - eps_target);
  gas::GasSettings s;
  s.cells = {2, 2, 10};
  s.hi = {8 * d, 8 * d, 40 * sz};
  s.eos = gas::EquationOfState::incompressible;
  s.density = 1.2;
  s.viscosity = 1.8e-5;
  s.gravity = {0.0, 0.0, 0.0};
  for (auto& b : s.boundary) b.type = gas::BoundaryType::wall_free_slip;
  s.boundary[gas::bottom].type = gas::BoundaryType::inflow;
  s.boundary[gas::bottom].inflow.velocity = U;
  s.boundary[gas::bottom].porosity = eps_target;
  s.boundary[gas::top].type = gas::BoundaryType::pressure;
  s.tolerance = 1e-10;
  s.velocity_tolerance = 1e-8;
  gas::GasSolver gs(s);
  const gas::GasGrid& g = gs.grid();
  ParticleStore p;
  for (int k = 0; k < 40; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i)
        p.add({(i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * sz}, {0, 0, 0}, 0.5 * d, 2500.0, 0,
              p.size());
  CouplingSettings c;
  c.drag = drag::DragModel::ergun;
  c.porosity.method = method;
  c.porosity.cube_factor = 3.0;
  validate(c, s);
  update_porosity(gs, p, c);
  gs.sync_old_porosity();
  ParticleGasForces f;
  double t = 0.0;
  const double dt = 1e-3;
  for (int n = 0; n < 30; ++n, t += dt) {
    compute_particle_forces(gs, p, c, f);
    deposit_momentum_source(gs, p, f);
    gs.step(t, dt);
  }
  double grad = 0.0, eps = 0.0;
  int m = 0;
  for (int k = 3; k < 8; ++k)
    for (int j = 1; j <= 2; ++j)
      for (int i = 1; i <= 2; ++i, ++m) {
        const auto q = static_cast<std::size_t>(g.idx(i, j, k));
        grad +=
            (gs.pressure()[q + static_cast<std::size_t>(g.stride[2])] - gs.pressure()[q]) / g.h[2];
        eps += gs.porosity()[q];
      }
  grad /= m;
  eps /= m;
  const double mu = s.viscosity, rho = s.density;
  const double ergun = 150.0 * mu * (1 - eps) * (1 - eps) * U / (eps * eps * eps * d * d) +
                       1.75 * rho * (1 - eps) * U * U / (eps * eps * eps * d);
  std::printf("%s porosity, U = %.2f m/s: eps = %.6f, -dp/dz = %.6g Pa/m, Ergun %.6g Pa/m, "
              "rel. error %.2e\n",
              method == PorosityMethod::cell ? "cell" : "porous-cube", U, eps, -grad, ergun,
              -grad / ergun - 1.0);
  EXPECT_NEAR(eps, eps_target, 1e-3);
  EXPECT_NEAR(-grad / ergun, 1.0, 0.03);
}
} // namespace

TEST(PackedBedErgun, CellPorosity) {
  for (double U : {0.2, 0.5, 1.0}) run(PorosityMethod::cell, U);
}
TEST(PackedBedErgun, PorousCubePorosity) {
  for (double U : {0.2, 0.5, 1.0}) run(PorosityMethod::porous_cube, U);
}
