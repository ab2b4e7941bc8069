// The pressure solve shared by MPI ranks (gas::StructLinearSolver::share, docs/parallel.md "The
// gas on several ranks"). Run by ctest under mpirun with 1, 2, 3 and 4 ranks. On random
// symmetric positive definite 7-point systems (an anisotropic, variable-coefficient diffusion
// operator plus a small shift: the shape of the pressure-correction equation) on a walled 3-D
// box, a box periodic along x (an odd period, 15) and z, and a 2-D box (one cell along y):
//  - the solution on P ranks equals, bit for bit, that of the same solver on one process alone,
//    on every rank, for the chosen cut and for forced slabs, columns and 2 x 2 parts; the
//    iteration counts are equal too (the stopping decision is the same);
//  - it is a solution: the relative residual computed here independently of hypre (explicit
//    neighbours, periodic wrap) is <= the tolerance 1e-10 (+ round-off), and on the walled
//    boxes it agrees with the banded Cholesky solution (gas/band_solver.hpp, a direct method)
//    to 1e-8 relative;
//  - a second system through the same solver (its multigrid set-up reused) keeps both;
//  - a control: another right-hand side gives another solution.
#define OMPI_SKIP_MPICXX 1
#include "../../common/mpi_bits.hpp"
#include "../../common/stencil_residual.hpp"
#include "gas/pressure_solver.hpp"
#include <cmath>
#include <cstdint>
#include <cstring>
#include <gtest/gtest.h>
#include <mpi.h>
#include <random>

using namespace fluidem::gas;
using fluidem::test::bits_hash;
using fluidem::test::same_on_every_rank;
using fluidem::test::world_rank;
using fluidem::test::world_size;

namespace {

struct Box {
  std::array<int, 3> n;
  std::array<bool, 3> periodic;
  std::array<int, 3> padded() const { return {n[0] + 2, n[1] + 2, n[2] + 2}; }
  long idx(int i, int j, int k) const {
    return i + static_cast<long>(n[0] + 2) * (j + static_cast<long>(n[1] + 2) * k);
  }
  std::size_t size() const { return static_cast<std::size_t>(n[0] + 2) * (n[1] + 2) * (n[2] + 2); }
};

// Links -c (c in [0.1, 1] times an axis weight 1, 4, 0.25: anisotropic), the same on both rows
// of a link; links leaving a walled box are 0; diag = sum of |links| + shift.
StencilSystem spd_system(const Box& b, unsigned seed, double shift) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> c(0.1, 1.0), rhs(-1.0, 1.0);
  StencilSystem s;
  s.resize(b.size());
  const std::array<double, 3> weight{1.0, 4.0, 0.25};
  std::array<std::vector<double>*, 3> lower{&s.xm, &s.ym, &s.zm}, upper{&s.xp, &s.yp, &s.zp};
  for (int k = 1; k <= b.n[2]; ++k)
    for (int j = 1; j <= b.n[1]; ++j)
      for (int i = 1; i <= b.n[0]; ++i) {
        const long q = b.idx(i, j, k);
        const int cc[3] = {i, j, k};
        for (int a = 0; a < 3; ++a) {
          if (b.n[a] == 1 && !b.periodic[a]) continue;
          const bool last = cc[a] == b.n[a];
          if (last && !b.periodic[a]) continue;
          int nb[3] = {i, j, k};
          nb[a] = last ? 1 : cc[a] + 1; // the upper neighbour (wrapped on a periodic axis)
          const double v = -weight[a] * c(rng);
          (*upper[a])[q] = v;
          (*lower[a])[b.idx(nb[0], nb[1], nb[2])] = v;
        }
        s.rhs[q] = rhs(rng);
      }
  for (int k = 1; k <= b.n[2]; ++k)
    for (int j = 1; j <= b.n[1]; ++j)
      for (int i = 1; i <= b.n[0]; ++i) {
        const long q = b.idx(i, j, k);
        s.diag[q] = -(s.xm[q] + s.xp[q] + s.ym[q] + s.yp[q] + s.zm[q] + s.zp[q]) + shift;
      }
  return s;
}

// ||b - A x|| / ||b||, neighbours read explicitly (periodic axes wrapped).
double relative_residual(const Box& b, const StencilSystem& s, const std::vector<double>& x) {
  return fluidem::test::stencil_relative_residual(b.padded(), {1, 1, 1}, b.n, b.periodic, s, x);
}

StructSolverOptions iterative() {
  StructSolverOptions o;
  o.direct_max_work = 0.0; // hypre (shared), never the direct path
  return o;
}

constexpr double kTol = 1e-10;

struct Solved {
  std::vector<double> x;
  std::vector<int> iterations;
};

// Two systems (seeds s, s + 1) through one solver shared as `how`.
Solved solve_two(const Box& b, unsigned seed, const SharedSolve& how) {
  StructLinearSolver solver(b.padded(), {1, 1, 1}, b.n, b.periodic, true, iterative());
  solver.share(how);
  Solved out;
  for (unsigned s = seed; s < seed + 2; ++s) {
    std::vector<double> x(b.size(), 0.0);
    const LinearSolveStats st = solver.solve(spd_system(b, s, 1e-2), x, kTol, 200);
    EXPECT_TRUE(st.converged) << "seed " << s << ": residual " << st.relative_residual;
    out.iterations.push_back(st.iterations);
    out.x.insert(out.x.end(), x.begin(), x.end());
  }
  return out;
}

void check_box(const Box& b) {
  const int P = world_size(), rank = world_rank();
  const int world = static_cast<int>(MPI_Comm_c2f(MPI_COMM_WORLD));
  const Solved alone = solve_two(b, 7, {-1, 0, 1, {0, 0, 0}});
  std::vector<std::array<int, 3>> cuts{{0, 0, 0}};
  if (P == 4) {
    cuts.push_back({4, 1, 1}); // slabs across x
    cuts.push_back({1, 1, 4}); // slabs across z
    cuts.push_back({2, 1, 2}); // 2 x 2
  }
  for (const auto& parts : cuts) {
    const Solved shared = solve_two(b, 7, {world, rank, P, parts});
    EXPECT_EQ(shared.iterations, alone.iterations) << "parts " << parts[0] << parts[2];
    EXPECT_EQ(bits_hash(shared.x), bits_hash(alone.x))
        << "P = " << P << ", parts " << parts[0] << " x " << parts[1] << " x " << parts[2];
    EXPECT_TRUE(same_on_every_rank(bits_hash(shared.x)));
  }
  // It solves the systems: the residual measured here, and (walled) the direct solution.
  for (unsigned s = 7; s < 9; ++s) {
    const StencilSystem sys = spd_system(b, s, 1e-2);
    const std::vector<double> x(alone.x.begin() + (s - 7) * b.size(),
                                alone.x.begin() + (s - 6) * b.size());
    EXPECT_LE(relative_residual(b, sys, x), 1.01 * kTol);
    if (!b.periodic[0] && !b.periodic[1] && !b.periodic[2]) {
      StructSolverOptions direct;
      direct.direct_max_work = 1e12;
      StructLinearSolver band(b.padded(), {1, 1, 1}, b.n, b.periodic, true, direct);
      std::vector<double> xd(b.size(), 0.0);
      band.solve(sys, xd, 1e-13, 10);
      ASSERT_EQ(band.direct_solves(), 1);
      double num = 0.0, den = 0.0;
      for (std::size_t q = 0; q < x.size(); ++q) {
        num = std::max(num, std::abs(x[q] - xd[q]));
        den = std::max(den, std::abs(xd[q]));
      }
      EXPECT_LE(num / den, 1e-8) << "seed " << s;
    }
  }
  // Control: another right-hand side, another solution.
  const Solved other = solve_two(b, 11, {world, rank, P, {0, 0, 0}});
  EXPECT_NE(bits_hash(other.x), bits_hash(alone.x));
}

class SharedPressureSolve : public ::testing::Test {
protected:
  static void SetUpTestSuite() { ensure_mpi_initialised(); }
};

TEST_F(SharedPressureSolve, WalledBoxSameBitsOnAnyRanks) {
  check_box({{24, 10, 18}, {false, false, false}});
}

TEST_F(SharedPressureSolve, PeriodicBoxSameBitsOnAnyRanks) {
  check_box({{15, 6, 20}, {true, false, true}}); // (an odd period: rank_dot_test.cpp)
}

TEST_F(SharedPressureSolve, TwoDimensionalBoxSameBitsOnAnyRanks) {
  check_box({{30, 1, 44}, {false, false, false}});
}

} // namespace
