// Coupling across periodic boundaries (interpolation.hpp, porosity.hpp, exchange.hpp): a periodic
// axis has no wall, so
//  - a particle crossing the periodic face keeps all its solid volume: the part beyond the face
//    is counted in the image cells at the other end (sum over cells = pi d^3 / 6 to 1e-13
//    relative; cell method: exact volumes, porous cube [Deen07 eq. 37]); moving it by whole
//    cells moves its porosity footprint by the same cells, wrapped (to 1e-15);
//  - the porosity interpolated to a point is continuous across the periodic face (the cell
//    stencil reads the images in the ghost layer): at lo + delta and hi - delta the values agree
//    to 2 delta |grad eps| (delta = 1e-9 m, |grad eps| < 50 /m here: to 1e-7);
//  - Newton's third law of the exchange [Zhu07 §3.2] holds for particles anywhere, including
//    within a cell of the periodic faces: sum_i drag_i + sum_faces S V_cell = 0 to 1e-10
//    relative (schemes 3 and 2; gas Model A, and Model B whose buoyancy term the gas gets too),
//    because the weights of ghost nodes go to their images.
#include "core/error.hpp"
#include "coupling/exchange.hpp"
#include "coupling/interpolation.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <random>

using namespace fluidem;
using namespace fluidem::coupling;

namespace {
constexpr double pi = 3.14159265358979323846;

gas::GasSettings periodic_xy_settings() {
  gas::GasSettings s;
  s.cells = {6, 4, 8};
  s.hi = {0.03, 0.02, 0.04};
  s.eos = gas::EquationOfState::incompressible;
  for (int side = 0; side < 4; ++side) s.boundary[side].type = gas::BoundaryType::periodic;
  return s;
}

double total_solid_volume(const gas::GasGrid& g, const std::vector<double>& frac) {
  double v = 0.0;
  for (int k = 1; k <= g.n[2]; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i)
        v += frac[static_cast<std::size_t>(g.idx(i, j, k))] * g.cell_volume();
  return v;
}
} // namespace

TEST(PeriodicCoupling, SphereAcrossAPeriodicCornerKeepsItsVolume) {
  const gas::GasSettings s = periodic_xy_settings();
  gas::GasSolver gs(s);
  const gas::GasGrid& g = gs.grid();
  const std::array<bool, 3> per{true, true, false};
  const double R = 0.003; // larger than half a cell: it covers cells on both sides
  for (PorosityMethod method : {PorosityMethod::cell, PorosityMethod::porous_cube}) {
    PorositySettings ps;
    ps.method = method;
    ps.cube_factor = 3.0; // cube of 18 mm: 3.6 cells along x and y, crossing both faces
    ParticleStore p;
    p.add({0.3 * R, 0.02 - 0.2 * R, 0.02}, {0.0, 0.0, 0.0}, R, 2500.0, 0, 0);
    std::vector<double> frac;
    solid_fraction(g, p, ps, frac, per);
    const double v = total_solid_volume(g, frac);
    EXPECT_NEAR(v / (4.0 / 3.0 * pi * R * R * R), 1.0, 1e-13) << "method " << int(method);
    // Moved by one cell along x and one along y: the same footprint, shifted and wrapped.
    ParticleStore q;
    q.add({0.3 * R + g.h[0], 0.02 - 0.2 * R + g.h[1] - 0.02, 0.02}, {0.0, 0.0, 0.0}, R, 2500.0, 0,
          0);
    std::vector<double> frac_q;
    solid_fraction(g, q, ps, frac_q, per);
    for (int k = 1; k <= g.n[2]; ++k)
      for (int j = 1; j <= g.n[1]; ++j)
        for (int i = 1; i <= g.n[0]; ++i) {
          const int is = i % g.n[0] + 1, js = j % g.n[1] + 1;
          EXPECT_NEAR(frac_q[static_cast<std::size_t>(g.idx(is, js, k))],
                      frac[static_cast<std::size_t>(g.idx(i, j, k))], 1e-15)
              << "cell " << i << " " << j << " " << k;
        }
  }
  // The same sphere without periodic axes loses the parts beyond the walls (cell method).
  ParticleStore p;
  p.add({0.3 * R, 0.02 - 0.2 * R, 0.02}, {0.0, 0.0, 0.0}, R, 2500.0, 0, 0);
  std::vector<double> frac;
  solid_fraction(g, p, {}, frac);
  EXPECT_LT(total_solid_volume(g, frac) / (4.0 / 3.0 * pi * R * R * R), 0.5);
}

TEST(PeriodicCoupling, PorosityIsContinuousAcrossThePeriodicFace) {
  const gas::GasSettings s = periodic_xy_settings();
  gas::GasSolver gs(s);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(0.0, 0.03), uy(0.0, 0.02), uz(0.0, 0.04);
  ParticleStore p;
  for (int n = 0; n < 60; ++n) p.add({ux(rng), uy(rng), uz(rng)}, {}, 0.001, 2500.0, 0, n);
  CouplingSettings c;
  update_porosity(gs, p, c);
  const double delta = 1e-9;
  double largest_jump = 0.0;
  for (double y : {0.003, 0.011, 0.017})
    for (double z : {0.004, 0.021, 0.033}) {
      const double a = porosity_at(gs, {delta, y, z}), b = porosity_at(gs, {0.03 - delta, y, z});
      EXPECT_NEAR(a, b, 1e-7) << "across x at y " << y << ", z " << z;
      const double e = porosity_at(gs, {y, delta, z}), f = porosity_at(gs, {y, 0.02 - delta, z});
      EXPECT_NEAR(e, f, 1e-7) << "across y at x " << y << ", z " << z;
      largest_jump = std::max(largest_jump, std::abs(a - porosity_at(gs, {0.03 - 0.005, y, z})));
    }
  // The field is not uniform (else the check above could not fail).
  EXPECT_GT(largest_jump, 1e-3);
}

namespace {
void third_law(ExchangeScheme scheme, int number, gas::PressureModel model) {
  gas::GasSettings s = periodic_xy_settings();
  s.model = model;
  s.gravity = {0.5, -1.0, -9.81}; // Model B: the buoyancy term goes to the gas too
  gas::GasSolver gs(s);
  const gas::GasGrid& g = gs.grid();
  // A smooth periodic gas velocity (x period 0.03 m, y period 0.02 m), ghosts included.
  for (int k = 0; k < g.padded[2]; ++k)
    for (int j = 0; j < g.padded[1]; ++j)
      for (int i = 0; i < g.padded[0]; ++i)
        for (int d = 0; d < 3; ++d) {
          const Vec3 x = g.face_centre(d, i, j, k);
          gs.velocity(d)[static_cast<std::size_t>(g.idx(i, j, k))] =
              std::sin(2.0 * pi * x[0] / 0.03 + d) * std::cos(70.0 * x[2]) +
              0.5 * std::sin(2.0 * pi * x[1] / 0.02);
        }
  std::mt19937_64 rng(11);
  // Anywhere across the periodic axes (half the particles within a cell of a periodic face);
  // a cell away from the walls at z.
  std::uniform_real_distribution<double> edge(-0.004, 0.004), uz(0.006, 0.034), rad(0.0005, 0.001),
      vel(-1.0, 1.0);
  ParticleStore p;
  for (int n = 0; n < 200; ++n) {
    double x = edge(rng), y = edge(rng);
    if (n % 2) {
      x = std::fmod(x + 0.015 + 0.03, 0.03);
      y = std::fmod(y + 0.01 + 0.02, 0.02);
    }
    x = std::fmod(x + 0.03, 0.03);
    y = std::fmod(y + 0.02, 0.02);
    p.add({x, y, uz(rng)}, {vel(rng), vel(rng), vel(rng)}, rad(rng), 2500.0, 0, n);
  }
  CouplingSettings c;
  c.scheme = scheme;
  validate(c, s);
  update_porosity(gs, p, c);
  ParticleGasForces f;
  compute_particle_forces(gs, p, c, f);
  deposit_momentum_source(gs, p, f);
  for (int d = 0; d < 3; ++d) {
    const std::vector<double>& dr = d == 0 ? f.drag_x : (d == 1 ? f.drag_y : f.drag_z);
    const std::vector<double>& pr = d == 0 ? f.pres_x : (d == 1 ? f.pres_y : f.pres_z);
    const bool b = model == gas::PressureModel::B; // the gas also gets minus pres (buoyancy)
    double sum_p = 0.0, abs_p = 0.0, sum_g = 0.0;
    for (std::size_t i = 0; i < dr.size(); ++i) {
      const double x = dr[i] + (b ? pr[i] : 0.0);
      sum_p += x;
      abs_p += std::abs(x);
    }
    for (double x : gs.applied_source(d)) sum_g += x * g.cell_volume();
    const double rel = std::abs(sum_p + sum_g) / abs_p;
    std::printf(
        "model %s, scheme %d, component %d: sum drag %.6e N, gas %.6e N, rel. imbalance %.2e\n",
        b ? "B" : "A", number, d, sum_p, sum_g, rel);
    EXPECT_LT(rel, 1e-10);
  }
}
} // namespace

TEST(PeriodicCoupling, NewtonThirdLawScheme3) {
  third_law(ExchangeScheme::scheme3, 3, gas::PressureModel::A);
  third_law(ExchangeScheme::scheme3, 3, gas::PressureModel::B);
}
TEST(PeriodicCoupling, NewtonThirdLawScheme2) {
  third_law(ExchangeScheme::scheme2, 2, gas::PressureModel::A);
  third_law(ExchangeScheme::scheme2, 2, gas::PressureModel::B);
}
