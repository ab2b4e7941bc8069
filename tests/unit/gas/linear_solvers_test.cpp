// Linear solvers of the gas step (docs/gas.md, "Linear solvers"):
//  - red-black Gauss-Seidel reaches the relative residual it reports, agrees with hypre GMRES
//    to 1e-8 relative (both solved to 1e-12) on diagonally dominant 7-point systems with
//    non-periodic and periodic axes (periods 1, 2 and an odd 5), is bitwise independent of the
//    thread count, and gives up early (converged = false) on a diffusion-dominated system;
//  - the hypre pressure solver with its set-up reused converges like a fresh set-up, and the
//    reuse policies do the number of set-ups they promise;
//  - the direct (banded Cholesky) path of StructLinearSolver agrees with hypre PCG + PFMG
//    (solved to 1e-13) to 1e-9 relative on random symmetric diagonally dominant systems on 2-D
//    and 3-D boxes whose longest axis is any of x, y, z, reaches a relative residual of 1e-12,
//    and its factorisation refuses a matrix that is not positive definite; a second system
//    through the same solver is solved directly again; direct solves leave MPI unstarted;
//  - GasSolver: results bitwise independent of the thread count (1, 2, 3 threads with every
//    threaded loop switched on, and unthreaded); the linear-solver options (hypre momentum,
//    SMG with a set-up per solve, hypre PCG instead of the direct pressure solve) agree with
//    the default within the SIMPLEC velocity
//    tolerance (1e-6 m/s) and 1e-8 relative in pressure after 20 steps of the 2-D bed; the
//    hypre fallback of the momentum solve is taken at DT near the viscous time; a linear solve
//    that does not converge is an InstabilityError naming the settings.
#include "../../common/stencil_residual.hpp"
#include "core/error.hpp"
#include "gas/band_solver.hpp"
#include "gas/gas_solver.hpp"
#include "gas/gauss_seidel.hpp"
#include "gas/pressure_solver.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>
#include <omp.h>
#include <random>
#include <string>

using namespace fluidem;
using namespace fluidem::gas;

namespace {

struct Box {
  std::array<int, 3> padded, lo, hi;
  std::array<bool, 3> periodic;
  long idx(int i, int j, int k) const {
    return i + static_cast<long>(padded[0]) * (j + static_cast<long>(padded[1]) * k);
  }
  std::size_t size() const { return static_cast<std::size_t>(padded[0]) * padded[1] * padded[2]; }
};

Box make_box(std::array<int, 3> n, std::array<bool, 3> periodic) {
  return {{n[0] + 2, n[1] + 2, n[2] + 2}, {1, 1, 1}, n, periodic};
}

// Random non-symmetric 7-point rows; diag = (sum |off-diagonal|) * dominance + 1e-3; links
// leaving the box along non-periodic axes are 0.
StencilSystem random_system(const Box& b, double dominance, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> off(0.1, 1.0), rhs(-1.0, 1.0);
  StencilSystem s;
  s.resize(b.size());
  std::array<std::vector<double>*, 6> slots{&s.xm, &s.xp, &s.ym, &s.yp, &s.zm, &s.zp};
  for (int k = b.lo[2]; k <= b.hi[2]; ++k)
    for (int j = b.lo[1]; j <= b.hi[1]; ++j)
      for (int i = b.lo[0]; i <= b.hi[0]; ++i) {
        const long q = b.idx(i, j, k);
        const int c[3] = {i, j, k};
        double sum = 0.0;
        for (int e = 0; e < 6; ++e) {
          const int a = e / 2;
          const bool out = !b.periodic[a] &&
                           ((e % 2 == 0 && c[a] == b.lo[a]) || (e % 2 == 1 && c[a] == b.hi[a]));
          const double v = out ? 0.0 : -off(rng);
          (*slots[e])[q] = v;
          sum += std::abs(v);
        }
        s.diag[q] = dominance * sum + 1e-3;
        s.rhs[q] = rhs(rng);
      }
  return s;
}

// ||b - A x|| / ||b|| on the box, the periodic neighbours wrapped explicitly.
double relative_residual(const Box& b, const StencilSystem& s, const std::vector<double>& x) {
  return test::stencil_relative_residual(b.padded, b.lo, b.hi, b.periodic, s, x);
}

double max_rel_diff(const Box& b, const std::vector<double>& x, const std::vector<double>& y) {
  double d = 0.0, m = 0.0;
  for (int k = b.lo[2]; k <= b.hi[2]; ++k)
    for (int j = b.lo[1]; j <= b.hi[1]; ++j)
      for (int i = b.lo[0]; i <= b.hi[0]; ++i) {
        const long q = b.idx(i, j, k);
        d = std::max(d, std::abs(x[q] - y[q]));
        m = std::max(m, std::abs(y[q]));
      }
  return d / m;
}

bool bitwise_equal(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// random_system made symmetric: a(P, P+e) = a(P+e, P) (the upper links copied down), diag
// = sum |off-diagonal| + shift.
StencilSystem symmetric_system(const Box& b, unsigned seed, double shift) {
  StencilSystem s = random_system(b, 1.0, seed);
  const std::array<long, 3> st{1, b.padded[0], static_cast<long>(b.padded[0]) * b.padded[1]};
  std::array<std::vector<double>*, 3> lower{&s.xm, &s.ym, &s.zm}, upper{&s.xp, &s.yp, &s.zp};
  for (int k = b.lo[2]; k <= b.hi[2]; ++k)
    for (int j = b.lo[1]; j <= b.hi[1]; ++j)
      for (int i = b.lo[0]; i <= b.hi[0]; ++i) {
        const long q = b.idx(i, j, k);
        const int c[3] = {i, j, k};
        for (int a = 0; a < 3; ++a)
          if (c[a] < b.hi[a]) (*lower[a])[q + st[a]] = (*upper[a])[q];
      }
  for (int k = b.lo[2]; k <= b.hi[2]; ++k)
    for (int j = b.lo[1]; j <= b.hi[1]; ++j)
      for (int i = b.lo[0]; i <= b.hi[0]; ++i) {
        const long q = b.idx(i, j, k);
        s.diag[q] = -(s.xm[q] + s.xp[q] + s.ym[q] + s.yp[q] + s.zm[q] + s.zp[q]) + shift;
      }
  return s;
}

} // namespace

// The direct path needs no hypre objects: a run whose pressure is solved directly never starts
// MPI (a singleton MPI_Init spawns Open MPI's daemon, 0.35 s on this machine); the first
// iterative solve does.
TEST(StructLinearSolver, DirectSolvesDoNotStartMpi) {
  if (mpi_started()) GTEST_SKIP() << "MPI was started by an earlier test in this process";
  const Box b = make_box({15, 1, 25}, {false, false, false});
  const StencilSystem s = symmetric_system(b, 11u, 1e-2);
  StructSolverOptions direct, hypre;
  direct.direct_max_work = 1e9;
  hypre.direct_max_work = 0.0;
  StructLinearSolver ds(b.padded, b.lo, b.hi, b.periodic, true, direct);
  StructLinearSolver hs(b.padded, b.lo, b.hi, b.periodic, true, hypre);
  std::vector<double> x(b.size(), 0.0);
  ASSERT_TRUE(ds.solve(s, x, 1e-12, 100).converged);
  EXPECT_EQ(ds.direct_solves(), 1);
  EXPECT_FALSE(mpi_started());
  std::vector<double> xh(b.size(), 0.0);
  ASSERT_TRUE(hs.solve(s, xh, 1e-12, 500).converged);
  EXPECT_TRUE(mpi_started());
  EXPECT_LT(max_rel_diff(b, x, xh), 1e-8);
}

TEST(StructLinearSolver, DirectSolveAgreesWithHypre) {
  StructSolverOptions direct, hypre;
  direct.direct_max_work = 1e9;
  for (const std::array<int, 3> n :
       {std::array<int, 3>{15, 1, 25}, std::array<int, 3>{9, 4, 5}, std::array<int, 3>{3, 11, 4},
        std::array<int, 3>{4, 5, 3}, std::array<int, 3>{1, 1, 1},
        // band widths b + 1 = 8 and 32 (the factor's compile-time widths, as 16 above)
        std::array<int, 3>{7, 1, 30}, std::array<int, 3>{31, 1, 40}}) {
    const Box b = make_box(n, {false, false, false});
    const StencilSystem s = symmetric_system(b, 5u + static_cast<unsigned>(n[0]), 1e-2);
    StructLinearSolver ds(b.padded, b.lo, b.hi, b.periodic, true, direct);
    StructLinearSolver hs(b.padded, b.lo, b.hi, b.periodic, true, hypre);
    std::vector<double> xd(b.size(), 0.0), xh(b.size(), 0.0);
    const LinearSolveStats sd = ds.solve(s, xd, 1e-12, 100);
    const LinearSolveStats sh = hs.solve(s, xh, 1e-13, 500);
    ASSERT_TRUE(sd.converged && sh.converged) << n[0] << "x" << n[1] << "x" << n[2];
    EXPECT_EQ(ds.direct_solves(), 1);
    EXPECT_EQ(hs.direct_solves(), 0);
    EXPECT_LE(relative_residual(b, s, xd), 1e-12);
    EXPECT_LT(max_rel_diff(b, xd, xh), 1e-9) << n[0] << "x" << n[1] << "x" << n[2];
    // A second system through the same band: the first factor's fill-in must be cleared.
    const StencilSystem s2 = symmetric_system(b, 17u + static_cast<unsigned>(n[2]), 3e-2);
    std::vector<double> x2(b.size(), 0.0);
    ASSERT_TRUE(ds.solve(s2, x2, 1e-12, 100).converged) << n[0] << "x" << n[1] << "x" << n[2];
    EXPECT_LE(relative_residual(b, s2, x2), 1e-12);
    EXPECT_EQ(ds.direct_solves(), 2); // solved directly, not by the iterative fallback
  }
  // Not positive definite (A -> -A): the factorisation refuses it.
  const Box b = make_box({6, 1, 7}, {false, false, false});
  const StencilSystem s = symmetric_system(b, 3u, 1e-2);
  BandCholesky band({6, 1, 7});
  band.clear();
  for (int k = 1; k <= 7; ++k)
    for (int i = 1; i <= 6; ++i) {
      const auto r = static_cast<std::size_t>((i - 1) + 6 * (k - 1));
      const long q = b.idx(i, 1, k);
      band.lower(r, 0) = -s.diag[q];
      if (i > 1) band.lower(r, 1) = -s.xm[q];
      if (k > 1) band.lower(r, 6) = -s.zm[q];
    }
  EXPECT_EQ(band.bandwidth(), 6);
  EXPECT_FALSE(band.factor());
}

TEST(GaussSeidel, AgreesWithHypreOnPeriodicAndWalledBoxes) {
  const std::array<std::array<int, 3>, 4> sizes{{{9, 5, 7}, {6, 1, 8}, {7, 2, 5}, {8, 4, 6}}};
  const std::array<std::array<bool, 3>, 4> periodic{
      {{false, true, false}, {false, true, false}, {true, true, false}, {false, false, true}}};
  for (std::size_t c = 0; c < sizes.size(); ++c) {
    const Box b = make_box(sizes[c], periodic[c]);
    const StencilSystem s = random_system(b, 1.5, 17u + static_cast<unsigned>(c));
    std::vector<double> x(b.size(), 0.0), y(b.size(), 0.0);
    RedBlackGaussSeidel gs(b.padded, b.lo, b.hi, b.periodic);
    const LinearSolveStats st = gs.solve(s, x, 1e-12, 200);
    ASSERT_TRUE(st.converged) << "case " << c << ": " << st.relative_residual;
    EXPECT_LE(relative_residual(b, s, x), 1e-12) << "case " << c;
    StructLinearSolver hypre(b.padded, b.lo, b.hi, b.periodic, false);
    ASSERT_TRUE(hypre.solve(s, y, 1e-12, 200).converged) << "case " << c;
    EXPECT_LT(max_rel_diff(b, x, y), 1e-8) << "case " << c;
  }
}

// The box of a velocity component starts at index 0 along its axis (the low boundary faces):
// nothing below the array may be read (found by valgrind in the bench; ASan builds check it).
TEST(GaussSeidel, BoxStartingAtIndexZero) {
  for (int axis : {0, 1, 2}) {
    Box b = make_box({6, 5, 7}, {false, false, false});
    b.lo[axis] = 0;
    const StencilSystem s = random_system(b, 1.5, 23u + static_cast<unsigned>(axis));
    std::vector<double> x(b.size(), 0.0), y(b.size(), 0.0);
    RedBlackGaussSeidel gs(b.padded, b.lo, b.hi, b.periodic);
    ASSERT_TRUE(gs.solve(s, x, 1e-12, 200).converged) << axis;
    EXPECT_LE(relative_residual(b, s, x), 1e-12) << axis;
    StructLinearSolver hypre(b.padded, b.lo, b.hi, b.periodic, false);
    ASSERT_TRUE(hypre.solve(s, y, 1e-12, 200).converged) << axis;
    EXPECT_LT(max_rel_diff(b, x, y), 1e-8) << axis;
  }
}

TEST(GaussSeidel, BitwiseIndependentOfThreads) {
  const Box b = make_box({20, 9, 11}, {false, true, false});
  const StencilSystem s = random_system(b, 1.2, 5u);
  std::vector<std::vector<double>> x;
  const int before = omp_get_max_threads();
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    std::vector<double> v(b.size(), 0.25);
    RedBlackGaussSeidel gs(b.padded, b.lo, b.hi, b.periodic, true);
    ASSERT_TRUE(gs.solve(s, v, 1e-11, 200).converged);
    x.push_back(v);
  }
  omp_set_num_threads(before);
  EXPECT_TRUE(bitwise_equal(x[0], x[1]));
  EXPECT_TRUE(bitwise_equal(x[0], x[2]));
  std::vector<double> serial(b.size(), 0.25);
  RedBlackGaussSeidel gs(b.padded, b.lo, b.hi, b.periodic, false);
  gs.solve(s, serial, 1e-11, 200);
  EXPECT_TRUE(bitwise_equal(x[0], serial));
}

TEST(GaussSeidel, GivesUpEarlyWhenDiffusionDominated) {
  const Box b = make_box({40, 1, 40}, {false, false, false});
  StencilSystem s = random_system(b, 1.0, 9u); // diag = sum |off| + 1e-3: Poisson-like
  std::vector<double> x(b.size(), 0.0);
  RedBlackGaussSeidel gs(b.padded, b.lo, b.hi, b.periodic);
  const LinearSolveStats st = gs.solve(s, x, 1e-10, 50);
  EXPECT_FALSE(st.converged);
  EXPECT_LT(st.iterations, 50) << "the contraction rate predicts failure before the budget";
  EXPECT_GT(st.relative_residual, 1e-10);
}

TEST(GaussSeidel, ZeroRightHandSideGivesZero) {
  const Box b = make_box({5, 3, 4}, {false, false, false});
  StencilSystem s = random_system(b, 2.0, 3u);
  std::fill(s.rhs.begin(), s.rhs.end(), 0.0);
  std::vector<double> x(b.size(), 1.0);
  RedBlackGaussSeidel gs(b.padded, b.lo, b.hi, b.periodic);
  EXPECT_TRUE(gs.solve(s, x, 1e-10, 50).converged);
  EXPECT_EQ(x[b.idx(2, 2, 2)], 0.0);
}

// Symmetric pressure-like systems changing a little from solve to solve.
TEST(StructLinearSolver, SetUpReuseConvergesAndCountsSetUps) {
  const Box b = make_box({15, 1, 25}, {false, false, false});
  StencilSystem base = random_system(b, 1.0, 11u);
  // Symmetrise: a(P, P+e) = a(P+e, P).
  for (int k = 1; k <= b.hi[2]; ++k)
    for (int i = 1; i <= b.hi[0]; ++i) {
      const long q = b.idx(i, 1, k);
      if (i < b.hi[0]) base.xm[q + 1] = base.xp[q];
      if (k < b.hi[2]) base.zm[b.idx(i, 1, k + 1)] = base.zp[q];
      base.ym[q] = base.yp[q] = 0.0;
    }
  for (int k = 1; k <= b.hi[2]; ++k)
    for (int i = 1; i <= b.hi[0]; ++i) {
      const long q = b.idx(i, 1, k);
      base.diag[q] = -(base.xm[q] + base.xp[q] + base.zm[q] + base.zp[q]) + 1e-2;
    }
  using Reuse = StructSolverOptions::Reuse;
  for (Reuse reuse : {Reuse::every_solve, Reuse::per_step, Reuse::adaptive}) {
    StructSolverOptions o;
    o.reuse = reuse;
    StructLinearSolver solver(b.padded, b.lo, b.hi, b.periodic, true, o);
    const int steps = 4, per_step = 3;
    for (int n = 0; n < steps; ++n) {
      solver.new_step();
      for (int m = 0; m < per_step; ++m) {
        StencilSystem s = base;
        for (double& d : s.diag) d *= 1.0 + 0.01 * (n * per_step + m);
        std::vector<double> x(b.size(), 0.0);
        const LinearSolveStats st = solver.solve(s, x, 1e-10, 100);
        ASSERT_TRUE(st.converged) << static_cast<int>(reuse) << " solve " << n << "," << m;
        EXPECT_LE(relative_residual(b, s, x), 1.01e-10);
      }
    }
    const long expect = reuse == Reuse::every_solve ? steps * per_step
                        : reuse == Reuse::per_step  ? steps
                                                    : 1;
    EXPECT_EQ(solver.setups(), expect) << static_cast<int>(reuse);
    EXPECT_EQ(solver.solves(), steps * per_step);
  }
}

namespace {
GasSettings bed(int dim, std::array<int, 3> cells, Vec3 hi) {
  GasSettings s;
  s.dimension = dim;
  s.cells = cells;
  s.hi = hi;
  s.depth = 0.004;
  for (auto& b : s.boundary) b.type = BoundaryType::wall_no_slip;
  s.boundary[bottom].type = BoundaryType::inflow;
  s.boundary[bottom].inflow.velocity = 2.5;
  s.boundary[bottom].porosity = 0.4;
  s.boundary[top].type = BoundaryType::pressure;
  return s;
}

void run_bed(GasSolver& gs, int steps) {
  const GasGrid& g = gs.grid();
  for (int d = 0; d < 3; ++d)
    for (std::size_t q = 0; q < g.size(); ++q)
      gs.drag_coefficient(d)[q] =
          (q / static_cast<std::size_t>(g.stride[2])) <= static_cast<std::size_t>(g.n[2] / 2) ? 1e4
                                                                                              : 0.0;
  double t = 0.0;
  for (int n = 0; n < steps; ++n, t += 1e-4) {
    for (int k = 1; k <= g.n[2]; ++k)
      for (int j = 1; j <= g.n[1]; ++j)
        for (int i = 1; i <= g.n[0]; ++i)
          gs.porosity()[g.idx(i, j, k)] =
              k <= g.n[2] / 2 ? 0.45 + 0.02 * std::sin(0.3 * i + 0.2 * j + 0.1 * k + 30.0 * n)
                              : 1.0;
    if (n == 0) gs.sync_old_porosity();
    gs.step(t, 1e-4);
  }
}
} // namespace

TEST(GasSolverThreads, BitwiseIndependentOfThreadCount) {
  const GasSettings s = bed(3, {12, 10, 16}, {0.06, 0.05, 0.16});
  const int before = omp_get_max_threads();
  std::vector<std::array<std::vector<double>, 4>> fields;
  for (int threads : {1, 2, 3, 0}) { // 0: the default thresholds (no threads on this grid)
    omp_set_num_threads(std::max(threads, 1));
    GasSolver gs(s);
    if (threads > 0) gs.set_parallel_cells(0, 0); // every threaded loop on
    EXPECT_EQ(gs.threaded_assembly(), threads > 0);
    run_bed(gs, 3);
    fields.push_back({gs.velocity(0), gs.velocity(1), gs.velocity(2), gs.pressure()});
  }
  omp_set_num_threads(before);
  for (std::size_t run = 1; run < fields.size(); ++run)
    for (int f = 0; f < 4; ++f) EXPECT_TRUE(bitwise_equal(fields[0][f], fields[run][f])) << run;
}

TEST(GasSolverLinearOptions, AgreeWithinTheSolverTolerance) {
  const GasSettings s = bed(2, {15, 1, 25}, {0.15, 0.004, 0.5});
  LinearSolverOptions hypre_momentum, smg_every_solve, pfmg_pressure;
  hypre_momentum.momentum = LinearSolverOptions::Momentum::hypre;
  smg_every_solve.pressure.multigrid = StructSolverOptions::Multigrid::smg;
  smg_every_solve.pressure.reuse = StructSolverOptions::Reuse::every_solve;
  smg_every_solve.pressure.direct_max_work = 0.0;
  pfmg_pressure.pressure.direct_max_work = 0.0; // hypre PCG + PFMG, set-up reused
  GasSolver ref(s);
  run_bed(ref, 20);
  for (const LinearSolverOptions& o : {hypre_momentum, smg_every_solve, pfmg_pressure}) {
    GasSolver gs(s);
    gs.set_linear_solver_options(o);
    run_bed(gs, 20);
    double du = 0.0, dp = 0.0;
    for (int d = 0; d < 3; ++d)
      for (std::size_t q = 0; q < ref.pressure().size(); ++q)
        du = std::max(du, std::abs(gs.velocity(d)[q] - ref.velocity(d)[q]));
    for (std::size_t q = 0; q < ref.pressure().size(); ++q)
      dp = std::max(dp, std::abs(gs.pressure()[q] - ref.pressure()[q]) / ref.pressure()[q]);
    std::printf("option set: max |du| = %.2e m/s, max |dp|/p = %.2e\n", du, dp);
    EXPECT_LT(du, s.velocity_tolerance);
    EXPECT_LT(dp, 1e-8);
    EXPECT_EQ(gs.last_iterations(), ref.last_iterations());
  }
  EXPECT_EQ(ref.linear_counters().momentum_fallbacks, 0);
  // The default solves the pressure correction of the 15 x 25 grid directly: no set-ups, one
  // "iteration" per solve.
  EXPECT_EQ(ref.linear_counters().pressure_setups, 0);
  EXPECT_EQ(ref.linear_counters().pressure_iterations, ref.linear_counters().pressure_solves);
  GasSolver pf(s);
  pf.set_linear_solver_options(pfmg_pressure);
  run_bed(pf, 20);
  EXPECT_LT(pf.linear_counters().pressure_setups, 5) << "the PFMG set-up is reused";
}

TEST(GasSolverLinearOptions, MomentumFallsBackToHypreNearTheViscousTime) {
  GasSettings s;
  s.dimension = 2;
  s.cells = {20, 1, 4};
  s.hi = {0.01, 0.002, 0.004};
  s.depth = 0.002;
  s.eos = EquationOfState::incompressible;
  s.gravity = {0.0, 0.0, 0.0};
  for (auto& b : s.boundary) b.type = BoundaryType::wall_no_slip;
  s.boundary[bottom].type = s.boundary[top].type = BoundaryType::periodic;
  GasSolver gs(s);
  for (auto& v : gs.explicit_source(2)) v = 0.5;
  gs.step(0.0, 1.0); // dt = 1 s: viscous, the momentum matrix is Poisson-like
  EXPECT_GT(gs.linear_counters().momentum_fallbacks, 0);
}

TEST(GasSolverLinearOptions, LinearNonConvergenceIsAnInstabilityError) {
  GasSettings s = bed(2, {15, 1, 25}, {0.15, 0.004, 0.5});
  s.linear_max_iterations = 1;
  s.linear_tolerance = 1e-14;
  GasSolver gs(s);
  LinearSolverOptions o;
  o.momentum_max_sweeps = 1;
  o.pressure.direct_max_work = 0.0; // hypre PCG, stopped after 1 iteration
  gs.set_linear_solver_options(o);
  try {
    gs.step(0.0, 1e-4);
    FAIL() << "expected InstabilityError";
  } catch (const InstabilityError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("did not converge"), std::string::npos) << m;
    EXPECT_NE(m.find("gas.solver.linear_tolerance"), std::string::npos) << m;
    EXPECT_NE(m.find("gas.solver.linear_max_iterations"), std::string::npos) << m;
  }
}
