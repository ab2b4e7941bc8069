// Coupling schemes 1 and 2 of [Zhu07 §3.2] (exchange.hpp), against scheme 3:
// (1) scheme 2, 300 random particles (d = 1-3 mm, random velocities) in a 3-D grid of
//     8 x 6 x 10 cells of 5 mm, nonuniform gas velocity, ergun_wen_yu: Newton's third law
//     [Zhu07 §3.2, "Scheme 2 can satisfy Newton's third law"], sum_i drag_i + sum_faces
//     applied_source V_cell = 0 to 1e-10 relative to sum_i |drag_i| per component, before and
//     after a change of the gas velocity (update_particle_forces); the share of each particle
//     in its cell's drag is d_i^2 / sum_j d_j^2 [Chang08 eq. 2.11] to 1e-12. Particles are kept
//     one cell away from the domain boundary (every face of their cells is solved).
// (2) identical particles with one velocity in a uniform gas field and a uniform porosity:
//     the cell averages equal the particles' own state, so schemes 1, 2 and 3 give the same
//     total particle drag and the same total gas source to 1e-10 relative [Zhu07 §3.2]; for
//     scheme 1 this is the case where its "local-average" gas force and the per-particle forces
//     agree (third law; in general it holds only on average), checked also cell by cell.
// (3) validate() accepts schemes 1, 2 and 3.
#include "core/error.hpp"
#include "coupling/exchange.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <random>

using namespace fluidem;
using namespace fluidem::coupling;

namespace {
gas::GasSettings grid_settings() {
  gas::GasSettings s;
  s.cells = {8, 6, 10};
  s.hi = {0.04, 0.03, 0.05};
  s.eos = gas::EquationOfState::incompressible;
  return s;
}

const std::vector<double>& drag_of(const ParticleGasForces& f, int d) {
  return d == 0 ? f.drag_x : (d == 1 ? f.drag_y : f.drag_z);
}
} // namespace

// (1) [Zhu07 §3.2] scheme 2 conserves momentum; [Chang08 eq. 2.11] shares by surface area.
TEST(ExchangeSchemes, Scheme2ThirdLawAndSurfaceAreaShares) {
  const gas::GasSettings s = grid_settings();
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
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(0.005, 0.035), uy(0.005, 0.025), uz(0.005, 0.045),
      rad(0.0005, 0.0015), vel(-1.0, 1.0);
  ParticleStore p;
  for (int n = 0; n < 300; ++n)
    p.add({ux(rng), uy(rng), uz(rng)}, {vel(rng), vel(rng), vel(rng)}, rad(rng), 2500.0, 0, n);
  CouplingSettings c;
  c.scheme = ExchangeScheme::scheme2;
  c.d_mean = 0.002;
  validate(c, s);
  update_porosity(gs, p, c);
  ParticleGasForces f;
  compute_particle_forces(gs, p, c, f);
  deposit_momentum_source(gs, p, f);
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) { // the gas step changes u; the particles then get s_i C_c (u_c,new - v_c)
      for (int d = 0; d < 3; ++d)
        for (double& u : gs.velocity(d)) u = 0.7 * u + 0.3;
      update_particle_forces(gs, p, f);
    }
    for (int d = 0; d < 3; ++d) {
      double sum_p = 0.0, abs_p = 0.0, sum_g = 0.0;
      for (double x : drag_of(f, d)) {
        sum_p += x;
        abs_p += std::abs(x);
      }
      for (double x : gs.applied_source(d)) sum_g += x * g.cell_volume();
      const double rel = std::abs(sum_p + sum_g) / abs_p;
      std::printf("scheme 2, pass %d, component %d: sum drag %.6e N, gas %.6e N, rel %.2e\n", pass,
                  d, sum_p, sum_g, rel);
      EXPECT_LT(rel, 1e-10);
    }
    // Shares: drag_i / (sum of the drags in i's cell) = d_i^2 / sum_j d_j^2, per component.
    std::map<long, double> sd2;
    std::map<long, std::array<double, 3>> cell_sum;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto cc = g.cell_of(p.position(i));
      const long q = g.idx(cc[0], cc[1], cc[2]);
      ASSERT_EQ(q, f.cell[i]);
      sd2[q] += 4.0 * p.radius[i] * p.radius[i];
      for (int d = 0; d < 3; ++d) cell_sum[q][static_cast<std::size_t>(d)] += drag_of(f, d)[i];
    }
    double worst = 0.0;
    int shared = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const long q = f.cell[i];
      const double share = 4.0 * p.radius[i] * p.radius[i] / sd2[q];
      if (share < 1.0) ++shared;
      for (int d = 0; d < 3; ++d) {
        const double e =
            std::abs(drag_of(f, d)[i] / cell_sum[q][static_cast<std::size_t>(d)] - share);
        worst = std::max(worst, e);
        EXPECT_LT(e, 1e-12) << "particle " << i << " component " << d;
      }
    }
    std::printf("pass %d: %d particles share a cell, worst share error %.2e\n", pass, shared,
                worst);
    EXPECT_GT(shared, 50); // the test must exercise cells with several particles
  }
}

// (2) [Zhu07 §3.2]: with uniform particle velocity, uniform gas and porosity, the three schemes
// give the same total force (and scheme 1's gas force is minus its particle forces).
TEST(ExchangeSchemes, UniformStateAllSchemesAgree) {
  const gas::GasSettings s = grid_settings();
  ParticleStore p;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> ux(0.005, 0.035), uy(0.005, 0.025), uz(0.005, 0.045);
  for (int n = 0; n < 200; ++n)
    p.add({ux(rng), uy(rng), uz(rng)}, {0.1, -0.2, 0.3}, 0.001, 2500.0, 0, n);
  const double u0[3] = {0.4, -0.1, 1.2};
  double tot_p[3][3] = {}, tot_g[3][3] = {};
  const ExchangeScheme schemes[3] = {ExchangeScheme::scheme1, ExchangeScheme::scheme2,
                                     ExchangeScheme::scheme3};
  for (int sc = 0; sc < 3; ++sc) {
    gas::GasSolver gs(s);
    const gas::GasGrid& g = gs.grid();
    for (int d = 0; d < 3; ++d)
      for (double& u : gs.velocity(d)) u = u0[d];
    for (double& e : gs.porosity()) e = 0.6;
    CouplingSettings c;
    c.scheme = schemes[sc];
    c.drag = "ergun_wen_yu";
    validate(c, s);
    ParticleGasForces f;
    compute_particle_forces(gs, p, c, f);
    deposit_momentum_source(gs, p, f);
    for (int d = 0; d < 3; ++d) {
      for (double x : drag_of(f, d)) tot_p[sc][d] += x;
      for (double x : gs.applied_source(d)) tot_g[sc][d] += x * g.cell_volume();
    }
    if (schemes[sc] == ExchangeScheme::scheme1) { // cell by cell: gas source = -particle drag
      for (int d = 0; d < 3; ++d) {
        std::vector<double> cell_p(g.size(), 0.0);
        for (std::size_t i = 0; i < p.size(); ++i)
          cell_p[static_cast<std::size_t>(f.cell[i])] += drag_of(f, d)[i];
        for (std::size_t q = 0; q < g.size(); ++q) {
          if (cell_p[q] == 0.0) continue;
          // F_c = C_c (u_c - v_c), the cell's force on the gas (with the opposite sign).
          const double vc = d == 0 ? f.cell_vx[q] : (d == 1 ? f.cell_vy[q] : f.cell_vz[q]);
          const double gas_cell = -f.cell_coeff[q] * (u0[d] - vc);
          EXPECT_NEAR(gas_cell, -cell_p[q], 1e-10 * std::abs(cell_p[q])) << "cell " << q;
        }
      }
    }
  }
  for (int d = 0; d < 3; ++d) {
    const double ref = tot_p[2][d];
    std::printf("component %d: drag scheme 1/2/3 %.12e %.12e %.12e N, gas %.12e %.12e %.12e N\n", d,
                tot_p[0][d], tot_p[1][d], tot_p[2][d], tot_g[0][d], tot_g[1][d], tot_g[2][d]);
    for (int sc = 0; sc < 3; ++sc) {
      EXPECT_NEAR(tot_p[sc][d], ref, 1e-10 * std::abs(ref)) << "scheme " << sc + 1;
      EXPECT_NEAR(tot_g[sc][d], -ref, 1e-10 * std::abs(ref)) << "scheme " << sc + 1;
    }
  }
}

// (3) [Zhu07 §3.2]: the three schemes are all valid input.
TEST(ExchangeSchemes, ValidateAcceptsAllSchemes) {
  const gas::GasSettings s;
  CouplingSettings c;
  for (ExchangeScheme e :
       {ExchangeScheme::scheme1, ExchangeScheme::scheme2, ExchangeScheme::scheme3}) {
    c.scheme = e;
    EXPECT_NO_THROW(validate(c, s));
  }
}
