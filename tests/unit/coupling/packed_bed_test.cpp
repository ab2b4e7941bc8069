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
//
// Model B (exchange.hpp): the same beds with gas Model B and gravity g = -9.81 m/s^2 along z
// (so that the buoyancy term -V_i rho g of the Model B particle force and its gas counterpart
// are exercised), and, for comparison, Model A with the same gravity; cell porosity, U = 0.2,
// 0.5, 1.0 m/s. The particles are frozen (their forces are not fed back), so this checks the gas
// side. Steady uniform bed, both models (exchange.hpp): grad p = -F_A/eps + rho g, i.e.
//   -dp/dz - rho |g| = F_A,z / eps = Ergun   (-dp/dz now includes the hydrostatic rho |g|),
// checked against Ergun within 3% for Model B. Total force on the particles per bed volume:
//   Model A: (sum_i drag_i + sum_i -V_i grad p) / V_bed = F_A - eps_s grad p,
//   Model B: (sum_i drag_i / eps_i - V_i rho g) / V_bed = F_A / eps - eps_s rho g,
// which are equal when grad p = -F_A/eps + rho g, and both = -dp/dz - eps rho |g| (z): the
// pressure drop per length less the weight of the gas in the bed per volume (with g = 0: the
// pressure drop per length). Checked: Model B total / Model A total within 3%, and each total
// against -dp/dz - eps rho |g| (the measured gradient) within 3%. Measured: all within 1e-6
// (the steady solve is converged to 1e-10), so B/A is also checked to 1e-4: the gas weight is
// 0.5% of the force at U = 0.2 m/s, and a wrong buoyancy term b (missing: -0.28%, wrong sign:
// -0.56%) shifts the Model B pressure gradient by b + eps_s rho g, which the 3% checks would
// not see. Particles counted: those with
// their centre in the cells k = 3..7 (4 whole lattice layers each), V_bed = 5 cell layers.
#include "coupling/exchange.hpp"
#include <cmath>
#include <gtest/gtest.h>

using namespace fluidem;
using namespace fluidem::coupling;

namespace {
struct Result {
  double grad_drop = 0.0; ///< -dp/dz, Pa/m
  double ergun = 0.0;     ///< Ergun at the measured porosity, Pa/m
  double eps = 0.0;
  double force = 0.0; ///< sum of the z forces on the particles of cells 3..7 / their volume, N/m^3
};

Result run(PorosityMethod method, double U, gas::PressureModel model = gas::PressureModel::A,
           double gz = 0.0) {
  const double d = 1e-3, eps_target = 0.45;
  const double sz = d * (3.14159265358979323846 / 6.0) / (1.0 - eps_target);
  gas::GasSettings s;
  s.cells = {2, 2, 10};
  s.hi = {8 * d, 8 * d, 40 * sz};
  s.eos = gas::EquationOfState::incompressible;
  s.density = 1.2;
  s.viscosity = 1.8e-5;
  s.gravity = {0.0, 0.0, gz};
  s.model = model;
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
  c.drag = "ergun";
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
  const double frictional = -grad + rho * gz; // -dp/dz - rho |g|: Ergun in both models
  std::printf("%s porosity, Model %s, g_z = %.2f, U = %.2f m/s: eps = %.6f, -dp/dz = %.6g Pa/m, "
              "-dp/dz - rho |g| = %.6g Pa/m, Ergun %.6g Pa/m, rel. error %.2e\n",
              method == PorosityMethod::cell ? "cell" : "porous-cube",
              model == gas::PressureModel::A ? "A" : "B", gz, U, eps, -grad, frictional, ergun,
              frictional / ergun - 1.0);
  EXPECT_NEAR(eps, eps_target, 1e-3);
  EXPECT_NEAR(frictional / ergun, 1.0, 0.03);
  // Total z force on the particles with their centre in the cells k = 3..7, with the final gas
  // state (compute_particle_forces again: the forces of the last step are of the state before).
  compute_particle_forces(gs, p, c, f);
  double fz = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int k = g.cell_of(p.position(i))[2];
    if (k >= 3 && k <= 7) fz += f.drag_z[i] + f.pres_z[i];
  }
  Result r;
  r.grad_drop = -grad;
  r.ergun = ergun;
  r.eps = eps;
  r.force = fz / (5.0 * g.h[2] * (s.hi[0] - s.lo[0]) * (s.hi[1] - s.lo[1]));
  return r;
}
} // namespace

TEST(PackedBedErgun, CellPorosity) {
  for (double U : {0.2, 0.5, 1.0}) run(PorosityMethod::cell, U);
}
TEST(PackedBedErgun, PorousCubePorosity) {
  for (double U : {0.2, 0.5, 1.0}) run(PorosityMethod::porous_cube, U);
}

TEST(PackedBedErgun, ModelBWithGravityAndTheTotalParticleForce) {
  const double gz = -9.81, rho = 1.2;
  for (double U : {0.2, 0.5, 1.0}) {
    const Result a = run(PorosityMethod::cell, U, gas::PressureModel::A, gz);
    const Result b = run(PorosityMethod::cell, U, gas::PressureModel::B, gz);
    // Both totals = -dp/dz - eps rho |g| (the header).
    const double ref_a = a.grad_drop + a.eps * rho * gz, ref_b = b.grad_drop + b.eps * rho * gz;
    std::printf("U = %.2f m/s: particle force per bed volume Model A %.6g N/m^3 (-dp/dz - eps rho "
                "|g| = %.6g), Model B %.6g N/m^3 (%.6g); B/A = %.6f\n",
                U, a.force, ref_a, b.force, ref_b, b.force / a.force);
    EXPECT_NEAR(b.force / a.force, 1.0, 0.03);
    EXPECT_NEAR(b.force / a.force, 1.0, 1e-4);
    EXPECT_NEAR(a.force / ref_a, 1.0, 0.03);
    EXPECT_NEAR(b.force / ref_b, 1.0, 0.03);
  }
}
