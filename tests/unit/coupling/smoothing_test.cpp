// Diffusion smoothing of the coupling fields (coupling/smoothing.hpp, docs/smoothing.md).
//  1. Heat kernel: a unit amount in one cell, smoothed to D T = sigma^2/2 with k backward-Euler
//     steps, keeps its sum (1e-13) and its centre (1e-10 h: round-off of sum v x) and has the
//     variance sigma^2 per axis, EXACTLY for the discrete Laplacian on an infinite grid for any k
//     (derivation in docs/smoothing.md; the Gaussian's variance). Reference: sigma^2. Tolerance:
//     1-D line of 81 cells (40 either side), sigma = 2 h: k = 4, 16: 1e-13 relative (tail at the
//     walls < 1e-20; measured 4e-16, 1.3e-15), k = 1: 1e-10 (its kernel 0.5^|i| leaves 1e-12 at the
//     walls; measured 3.7e-11); 3-D 41^3 cells with h = 1, 1.25, 0.8 mm, and 2-D
//     41 x 1 x 41: 1e-8 relative per axis (the tail reaching the walls 20 cells away, ~1e-11 of
//     the amount). 2-D: no spreading along y. The fourth moment against its exact value for k
//     steps, 3 sigma^4 (1 + 1/k) + sigma^2 h^2 (excess kurtosis 3/k + h^2/sigma^2; derivation in
//     docs/smoothing.md), to 100 x the variance's tolerance (measured 9.7e-13, 1.8e-13 for
//     k = 4, 16 on the line; 4.9e-9 for k = 1; <= 1.4e-9 in 3-D/2-D).
//  2. Conservation: random fields (0..1 with spikes of 100) on 12 x 9 x 10 cells, sigma = 3 cells,
//     walls, periodic x and z, all periodic, and 2-D: sum kept to 1e-13 relative; ghosts
//     untouched (bitwise); the maximum principle (min not lower, max not higher, 1e-14 of the
//     max). Faces (the momentum source of a gas solver with walls, an inflow floor and a
//     pressure top; and periodic x): the sum of every array of every component kept to 1e-13,
//     faces the solver does not solve bitwise unchanged.
//  3. A uniform field stays uniform: bitwise for the smoothing; the porosity 1 - (1 - eps) to
//     1e-15. (And CouplingSmoother refuses a negative or nan length: InputError.)
//  5. Newton's third law with smoothing on (mirror of newton_third_law_test.cpp: 300 random
//     particles, nonuniform gas velocity, ergun_wen_yu, Models A and B, a periodic x axis): the
//     particles reading the gas velocity through the smoothing (with_smoothed_velocity, the
//     adjoint), sum_i drag_i (+ pres_i, B) + sum_faces applied_source V_cell = 0 to 1e-10
//     relative, before and after a change of u. The same with the particles reading the
//     unsmoothed velocity is NOT balanced (> 1e-6 measured: the check can fail).
#include "core/error.hpp"
#include "coupling/exchange.hpp"
#include "coupling/smoothing.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <random>

using namespace fluidem;
using namespace fluidem::coupling;

namespace {

struct Moments {
  double sum = 0.0;
  std::array<double, 3> mean{}, var{}, m4{};
};

void heat_kernel(const gas::GasGrid& g, std::array<int, 3> centre, double sigma, int steps,
                 double tol) {
  std::vector<double> a(g.size(), 0.0);
  const long c = g.idx(centre[0], centre[1], centre[2]);
  a[static_cast<std::size_t>(c)] = 1.0;
  DiffusionScratch s;
  diffuse(cell_domain(g, {}), g.h, sigma, steps, a, s);
  // Moments (two passes: the mean first).
  Moments m;
  for (int k = 1; k <= g.n[2]; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i) {
        const double v = a[static_cast<std::size_t>(g.idx(i, j, k))];
        const Vec3 x = g.cell_centre(i, j, k);
        m.sum += v;
        for (int d = 0; d < 3; ++d) m.mean[static_cast<std::size_t>(d)] += v * x[d];
      }
  for (int k = 1; k <= g.n[2]; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i) {
        const double v = a[static_cast<std::size_t>(g.idx(i, j, k))];
        const Vec3 x = g.cell_centre(i, j, k);
        for (int d = 0; d < 3; ++d) {
          const double dx = x[d] - m.mean[static_cast<std::size_t>(d)];
          m.var[static_cast<std::size_t>(d)] += v * dx * dx;
          m.m4[static_cast<std::size_t>(d)] += v * dx * dx * dx * dx;
        }
      }
  const Vec3 xc = g.cell_centre(centre[0], centre[1], centre[2]);
  EXPECT_NEAR(m.sum, 1.0, 1e-13); // (41^3: 4.8e-14 measured)
  for (int d = 0; d < 3; ++d) {
    const auto ud = static_cast<std::size_t>(d);
    const bool spread = g.n[ud] > 1;
    const double want = spread ? sigma * sigma : 0.0;
    std::printf("steps %d axis %d: variance %.15e m^2, sigma^2 %.15e, rel. error %.2e; mean - "
                "centre %.2e h\n",
                steps, d, m.var[ud], want, spread ? std::abs(m.var[ud] / want - 1.0) : m.var[ud],
                (m.mean[ud] - xc[d]) / g.h[ud]);
    EXPECT_NEAR(m.mean[ud], xc[d], 1e-10 * g.h[ud]); // (round-off of sum v x, x ~ 40 h)
    if (spread) {
      EXPECT_NEAR(m.var[ud] / want, 1.0, tol);
      // Fourth moment, exact for k backward-Euler steps on an infinite grid (docs/smoothing.md):
      // 3 sigma^4 (1 + 1/k) + sigma^2 h^2, i.e. excess kurtosis 3/k + h^2/sigma^2 (Gaussian: 0).
      const double s2 = sigma * sigma, h2 = g.h[ud] * g.h[ud];
      const double m4 = 3.0 * s2 * s2 * (1.0 + 1.0 / steps) + s2 * h2;
      std::printf("   fourth moment %.15e, exact %.15e, rel. error %.2e; excess kurtosis %.4f\n",
                  m.m4[ud], m4, std::abs(m.m4[ud] / m4 - 1.0), m.m4[ud] / (s2 * s2) - 3.0);
      EXPECT_NEAR(m.m4[ud] / m4, 1.0, 100.0 * tol);
    } else {
      EXPECT_LT(m.var[ud], 1e-30); // (the mean's round-off squared)
    }
  }
}

} // namespace

TEST(Smoothing, HeatKernelVarianceOneDimension) {
  const gas::GasGrid g(3, {81, 1, 1}, {0.0, 0.0, 0.0}, {0.081, 0.001, 0.001});
  // One step: kernel ~ 0.5^|i| (alpha = 2), 1e-12 of the amount at the walls 40 cells away
  // (variance error 4e-11 measured); four and more: < 1e-20.
  heat_kernel(g, {41, 1, 1}, 0.002, 1, 1e-10);
  for (int steps : {4, 16}) heat_kernel(g, {41, 1, 1}, 0.002, steps, 1e-13);
}

TEST(Smoothing, HeatKernelVarianceThreeAndTwoDimensions) {
  const gas::GasGrid g3(3, {41, 41, 41}, {0.0, 0.0, 0.0}, {0.041, 0.05125, 0.0328});
  heat_kernel(g3, {21, 21, 21}, 0.0012, smoothing_steps, 1e-8);
  const gas::GasGrid g2(2, {41, 1, 41}, {0.0, 0.0, 0.0}, {0.041, 0.01, 0.0328});
  heat_kernel(g2, {21, 1, 21}, 0.0012, smoothing_steps, 1e-8);
}

namespace {

/// Random field with spikes on the interior cells; ghosts hold 7.0 (must stay untouched).
std::vector<double> random_field(const gas::GasGrid& g, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> a(g.size(), 7.0);
  for (int k = 1; k <= g.n[2]; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i) {
        const double v = u(rng);
        a[static_cast<std::size_t>(g.idx(i, j, k))] = v < 0.05 ? 100.0 * v / 0.05 : v;
      }
  return a;
}

bool interior(const gas::GasGrid& g, std::size_t q) {
  const long l = static_cast<long>(q);
  const int i = static_cast<int>(l % g.padded[0]);
  const int j = static_cast<int>((l / g.padded[0]) % g.padded[1]);
  const int k = static_cast<int>(l / (static_cast<long>(g.padded[0]) * g.padded[1]));
  return i >= 1 && i <= g.n[0] && j >= 1 && j <= g.n[1] && k >= 1 && k <= g.n[2];
}

} // namespace

TEST(Smoothing, CellsConserveTheSumWithWallsAndPeriodicAxes) {
  const gas::GasGrid g3(3, {12, 9, 10}, {0.0, 0.0, 0.0}, {0.012, 0.009, 0.01});
  const gas::GasGrid g2(2, {12, 1, 10}, {0.0, 0.0, 0.0}, {0.012, 0.003, 0.01});
  const std::array<std::array<bool, 3>, 4> cases{
      {{false, false, false}, {true, false, true}, {true, true, true}, {false, true, false}}};
  unsigned seed = 1;
  for (const gas::GasGrid* g : {&g3, &g2})
    for (const auto& per : cases) {
      std::vector<double> a = random_field(*g, seed++);
      const std::vector<double> a0 = a;
      double s0 = 0.0, abs0 = 0.0, mn = 1e300, mx = -1e300;
      for (std::size_t q = 0; q < a.size(); ++q)
        if (interior(*g, q)) {
          s0 += a[q];
          abs0 += std::abs(a[q]);
          mn = std::min(mn, a[q]);
          mx = std::max(mx, a[q]);
        }
      DiffusionScratch s;
      std::array<bool, 3> p = per;
      if (g->dimension == 2) p[1] = false;
      diffuse(cell_domain(*g, p), g->h, 0.003, smoothing_steps, a, s);
      double s1 = 0.0, mn1 = 1e300, mx1 = -1e300;
      bool changed = false;
      for (std::size_t q = 0; q < a.size(); ++q) {
        if (!interior(*g, q)) {
          EXPECT_EQ(a[q], a0[q]) << "ghost " << q;
          continue;
        }
        s1 += a[q];
        mn1 = std::min(mn1, a[q]);
        mx1 = std::max(mx1, a[q]);
        changed = changed || a[q] != a0[q];
      }
      std::printf("dim %d periodic %d%d%d: sum %.17g -> %.17g, rel. change %.2e; min %.4f -> "
                  "%.4f, max %.4f -> %.4f\n",
                  g->dimension, per[0], per[1], per[2], s0, s1, std::abs(s1 - s0) / abs0, mn, mn1,
                  mx, mx1);
      EXPECT_TRUE(changed);
      EXPECT_LT(std::abs(s1 - s0) / abs0, 1e-13);
      EXPECT_GE(mn1, mn - 1e-14 * mx);
      EXPECT_LE(mx1, mx + 1e-14 * mx);
      EXPECT_LT(mx1, 0.5 * mx); // the spikes were spread
    }
}

TEST(Smoothing, UniformFieldStaysUniform) {
  const gas::GasGrid g(3, {12, 9, 10}, {0.0, 0.0, 0.0}, {0.012, 0.009, 0.01});
  for (const std::array<bool, 3> per :
       {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, true, false}}) {
    std::vector<double> a(g.size(), 0.0);
    for (std::size_t q = 0; q < a.size(); ++q)
      if (interior(g, q)) a[q] = 0.37;
    const std::vector<double> a0 = a;
    DiffusionScratch s;
    diffuse(cell_domain(g, per), g.h, 0.004, smoothing_steps, a, s);
    for (std::size_t q = 0; q < a.size(); ++q) EXPECT_EQ(a[q], a0[q]) << q;
  }
  // The porosity through the solid fraction: 1 - (1 - eps), to 1e-15.
  gas::GasSettings st;
  st.cells = {12, 9, 10};
  st.hi = {0.012, 0.009, 0.01};
  st.eos = gas::EquationOfState::incompressible;
  gas::GasSolver gs(st);
  CouplingSmoother sm;
  sm.configure(gs, 0.004);
  std::vector<double> eps(g.size(), 0.0);
  for (std::size_t q = 0; q < eps.size(); ++q)
    if (interior(g, q)) eps[q] = 0.4137;
  sm.smooth_porosity(eps, min_porosity);
  EXPECT_THROW(CouplingSmoother().configure(gs, -1e-3), InputError);
  EXPECT_THROW(CouplingSmoother().configure(gs, std::nan("")), InputError);
  for (std::size_t q = 0; q < eps.size(); ++q)
    if (interior(g, q)) {
      EXPECT_NEAR(eps[q], 0.4137, 1e-15) << q;
    }
}

namespace {

bool carries_source(unsigned char r) {
  return r == gas::GasSolver::solved || r == gas::GasSolver::pressure_face ||
         r == gas::GasSolver::inflow;
}

gas::GasSettings bed_settings(bool periodic_x, int dim = 3) {
  gas::GasSettings s;
  s.dimension = dim;
  s.cells = {8, dim == 2 ? 1 : 6, 10};
  s.hi = {0.04, 0.03, 0.05};
  if (dim == 2) s.depth = 0.03;
  s.eos = gas::EquationOfState::incompressible;
  s.boundary[4].type = gas::BoundaryType::inflow; // floor
  s.boundary[4].inflow.velocity = 0.3;
  s.boundary[5].type = gas::BoundaryType::pressure; // top
  if (periodic_x) s.boundary[0].type = s.boundary[1].type = gas::BoundaryType::periodic;
  return s;
}

} // namespace

TEST(Smoothing, FacesConserveTheSumAndKeepUnsolvedFaces) {
  for (const int dim : {3, 2})
    for (const bool px : {false, true}) {
      gas::GasSolver gs(bed_settings(px, dim));
      const gas::GasGrid& g = gs.grid();
      std::mt19937_64 rng(7);
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      std::array<std::array<std::vector<double>, 3>, 3> before;
      for (int d = 0; d < 3; ++d) {
        const std::vector<unsigned char>& role = gs.face_role(d);
        std::array<std::vector<double>*, 3> arr{&gs.drag_coefficient(d), &gs.drag_velocity_term(d),
                                                &gs.explicit_source(d)};
        for (std::size_t a = 0; a < 3; ++a) {
          arr[a]->assign(g.size(), 0.0);
          for (std::size_t q = 0; q < g.size(); ++q)
            if (carries_source(role[q])) (*arr[a])[q] = a == 0 ? 1.0 + u(rng) : u(rng);
          before[static_cast<std::size_t>(d)][a] = *arr[a];
        }
      }
      CouplingSmoother sm;
      sm.configure(gs, 0.012);
      sm.smooth_momentum_source(gs);
      for (int d = 0; d < 3; ++d) {
        const std::vector<unsigned char>& role = gs.face_role(d);
        std::array<const std::vector<double>*, 3> arr{
            &gs.drag_coefficient(d), &gs.drag_velocity_term(d), &gs.explicit_source(d)};
        for (std::size_t a = 0; a < 3; ++a) {
          const std::vector<double>& b = before[static_cast<std::size_t>(d)][a];
          double s0 = 0.0, s1 = 0.0, abs0 = 0.0;
          bool changed = false;
          for (std::size_t q = 0; q < g.size(); ++q) {
            s0 += b[q];
            s1 += (*arr[a])[q];
            abs0 += std::abs(b[q]);
            if (role[q] != gas::GasSolver::solved) {
              EXPECT_EQ((*arr[a])[q], b[q]) << "unsolved face " << q;
            }
            changed = changed || (*arr[a])[q] != b[q];
          }
          if (abs0 == 0.0) continue; // (v_y in 2-D)
          std::printf("dim %d periodic x %d component %d array %zu: rel. change of the sum "
                      "%.2e\n",
                      dim, px, d, a, std::abs(s1 - s0) / abs0);
          EXPECT_TRUE(changed);
          EXPECT_LT(std::abs(s1 - s0) / abs0, 1e-13);
          if (a == 0) { // K stays >= 0 (a weighted mean of K >= 0)
            EXPECT_GE(*std::min_element(arr[a]->begin(), arr[a]->end()), -1e-14);
          }
        }
      }
    }
}

namespace {

/// The newton_third_law_test flow with smoothing: relative imbalance, max over components and
/// the two passes (before and after the change of u). adjoint = false: the particles read the
/// unsmoothed velocity (the negative control).
double third_law(gas::PressureModel model, bool periodic_x, bool adjoint) {
  const bool model_b = model == gas::PressureModel::B;
  gas::GasSettings s;
  s.model = model;
  if (model_b) s.gravity = {1.0, -2.0, -9.81};
  s.cells = {8, 6, 10};
  s.hi = {0.04, 0.03, 0.05};
  s.eos = gas::EquationOfState::incompressible;
  if (periodic_x) s.boundary[0].type = s.boundary[1].type = gas::BoundaryType::periodic;
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
  if (periodic_x)
    for (int d = 0; d < 3; ++d) gas::fill_periodic_ghosts(g, {true, false, false}, gs.velocity(d));
  std::mt19937_64 rng(42);
  // Away from the walls (one cell), as newton_third_law_test; along a periodic x anywhere.
  std::uniform_real_distribution<double> ux(periodic_x ? 0.0 : 0.005, periodic_x ? 0.04 : 0.035),
      uy(0.005, 0.025), uz(0.005, 0.045), rad(0.0005, 0.0015), vel(-1.0, 1.0);
  ParticleStore p;
  for (int n = 0; n < 300; ++n)
    p.add({ux(rng), uy(rng), uz(rng)}, {vel(rng), vel(rng), vel(rng)}, rad(rng), 2500.0, 0, n);
  CouplingSettings c;
  c.drag = "ergun_wen_yu";
  c.d_mean = 0.002;
  c.smoothing_length = 0.0075; // 1.5 cells
  validate(c, s);
  CouplingSmoother sm;
  sm.configure(gs, c.smoothing_length);
  update_porosity(gs, p, c);
  sm.smooth_porosity(gs.porosity(), min_porosity);
  ParticleGasForces f;
  sm.with_smoothed_velocity(gs, [&] { compute_particle_forces(gs, p, c, f); });
  deposit_momentum_source(gs, p, f);
  sm.smooth_momentum_source(gs);
  double worst = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      for (int d = 0; d < 3; ++d)
        for (double& u : gs.velocity(d)) u = 0.7 * u + 0.3;
    }
    if (adjoint)
      sm.with_smoothed_velocity(gs, [&] { update_particle_forces(gs, p, f); });
    else
      update_particle_forces(gs, p, f);
    for (int d = 0; d < 3; ++d) {
      const std::vector<double>& dr = d == 0 ? f.drag_x : (d == 1 ? f.drag_y : f.drag_z);
      const std::vector<double>& pr = d == 0 ? f.pres_x : (d == 1 ? f.pres_y : f.pres_z);
      double sum_p = 0.0, abs_p = 0.0, sum_g = 0.0;
      for (std::size_t i = 0; i < dr.size(); ++i) {
        sum_p += model_b ? dr[i] + pr[i] : dr[i];
        abs_p += std::abs(dr[i]) + (model_b ? std::abs(pr[i]) : 0.0);
      }
      for (double x : gs.applied_source(d)) sum_g += x * g.cell_volume();
      worst = std::max(worst, std::abs(sum_p + sum_g) / abs_p);
    }
  }
  std::printf("Model %s, periodic x %d, particles read the %s velocity: rel. imbalance %.2e\n",
              model_b ? "B" : "A", periodic_x, adjoint ? "smoothed" : "unsmoothed", worst);
  return worst;
}

} // namespace

TEST(Smoothing, NewtonThirdLawWithSmoothing) {
  for (const auto model : {gas::PressureModel::A, gas::PressureModel::B})
    for (const bool px : {false, true}) EXPECT_LT(third_law(model, px, true), 1e-10);
  // Negative control: the smoothed K with the particles' own velocity does not balance.
  EXPECT_GT(third_law(gas::PressureModel::A, false, false), 1e-6);
}
