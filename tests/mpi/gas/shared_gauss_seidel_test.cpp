// The momentum equations' red-black Gauss-Seidel shared by MPI ranks
// (gas::RedBlackGaussSeidel::share, docs/parallel.md "The gas on several ranks"). Run by ctest
// under mpirun with 1, 2, 3 and 4 ranks. On random non-symmetric, diagonally dominant 7-point
// systems (the shape of a momentum equation: upwinded convection makes the links of a point's two
// sides differ) on a walled 3-D box, the box of a z velocity component (its faces from index 0:
// the row below the box is not stored), a box periodic along x and along z with an odd period
// (7 planes: uneven parts, and across the period a rank's halo comes from the last rank), a box
// of 3 planes (at 4 ranks one rank has none) and a 2-D box (one cell along y):
//  - on every rank the solution equals, bit for bit, that of the same solver on one process
//    alone, and so do the sweep count and the residual it reports (the stopping decision);
//  - also when the sweeps stop before the tolerance (max_sweeps 3, converged = false);
//  - it is a solution: the relative residual computed here independently of the solver
//    (tests/common/stencil_residual.hpp) is <= the tolerance 1e-10 (+ round-off);
//  - a control: another right-hand side gives another solution.
#define OMPI_SKIP_MPICXX 1
#include "../../common/mpi_bits.hpp"
#include "../../common/stencil_residual.hpp"
#include "gas/gauss_seidel.hpp"
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
  std::array<int, 3> n;  ///< interior cells (padded: n + 2)
  std::array<int, 3> lo; ///< first unknown (0 or 1 per axis); the last is n
  std::array<bool, 3> periodic;
  std::array<int, 3> padded() const { return {n[0] + 2, n[1] + 2, n[2] + 2}; }
  long idx(int i, int j, int k) const {
    return i + static_cast<long>(n[0] + 2) * (j + static_cast<long>(n[1] + 2) * k);
  }
  std::size_t size() const { return static_cast<std::size_t>(n[0] + 2) * (n[1] + 2) * (n[2] + 2); }
};

// Links -c with c in [0.1, 1] (x 3 on the upwind side: convection), 0 where the neighbour is
// outside a non-periodic box; diag = 1.2 x the sum of |links| (diagonally dominant, as the
// momentum rows are with their time term) + 0.05.
StencilSystem momentum_like_system(const Box& b, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> c(0.1, 1.0), rhs(-1.0, 1.0);
  StencilSystem s;
  s.resize(b.size());
  std::array<std::vector<double>*, 3> lower{&s.xm, &s.ym, &s.zm}, upper{&s.xp, &s.yp, &s.zp};
  for (int k = b.lo[2]; k <= b.n[2]; ++k)
    for (int j = b.lo[1]; j <= b.n[1]; ++j)
      for (int i = b.lo[0]; i <= b.n[0]; ++i) {
        const long q = b.idx(i, j, k);
        const int cc[3] = {i, j, k};
        double sum = 0.0;
        for (int a = 0; a < 3; ++a) {
          if (b.n[a] == 1 && !b.periodic[a]) continue;
          const bool first = cc[a] == b.lo[a], last = cc[a] == b.n[a];
          const double lo_link = first && !b.periodic[a] ? 0.0 : -3.0 * c(rng);
          const double hi_link = last && !b.periodic[a] ? 0.0 : -c(rng);
          (*lower[a])[q] = lo_link;
          (*upper[a])[q] = hi_link;
          sum -= lo_link + hi_link;
        }
        s.diag[q] = 1.2 * sum + 0.05;
        s.rhs[q] = rhs(rng);
      }
  return s;
}

constexpr double kTol = 1e-10;

struct Solved {
  std::vector<double> x;
  LinearSolveStats stats;
};

// One system through a solver, shared by the world's ranks or alone; the guess is a smooth
// field (everywhere in the padded array, as the gas's velocities are).
Solved solve(const Box& b, unsigned seed, bool shared, int max_sweeps) {
  RedBlackGaussSeidel gs(b.padded(), b.lo, b.n, b.periodic);
  if (shared) gs.share(static_cast<int>(MPI_Comm_c2f(MPI_COMM_WORLD)), world_rank(), world_size());
  Solved out;
  out.x.assign(b.size(), 0.0);
  for (std::size_t q = 0; q < out.x.size(); ++q)
    out.x[q] = 0.1 * std::sin(0.37 * static_cast<double>(q));
  out.stats = gs.solve(momentum_like_system(b, seed), out.x, kTol, max_sweeps);
  return out;
}

void check_box(const Box& b) {
  const Solved alone = solve(b, 5, false, 200);
  ASSERT_TRUE(alone.stats.converged) << "residual " << alone.stats.relative_residual;
  const Solved shared = solve(b, 5, true, 200);
  EXPECT_EQ(shared.stats.iterations, alone.stats.iterations);
  EXPECT_EQ(shared.stats.converged, alone.stats.converged);
  EXPECT_EQ(shared.stats.relative_residual, alone.stats.relative_residual);
  EXPECT_EQ(bits_hash(shared.x), bits_hash(alone.x)) << "P = " << world_size();
  EXPECT_TRUE(same_on_every_rank(bits_hash(shared.x)));
  // It solves the system: the residual measured here.
  EXPECT_LE(fluidem::test::stencil_relative_residual(b.padded(), b.lo, b.n, b.periodic,
                                                     momentum_like_system(b, 5), shared.x),
            1.01 * kTol);
  // Stopped early (not converged): still the same bits.
  const Solved short_alone = solve(b, 5, false, 3), short_shared = solve(b, 5, true, 3);
  EXPECT_FALSE(short_shared.stats.converged);
  EXPECT_EQ(short_shared.stats.iterations, short_alone.stats.iterations);
  EXPECT_EQ(bits_hash(short_shared.x), bits_hash(short_alone.x));
  // Control: another right-hand side, another solution.
  EXPECT_NE(bits_hash(solve(b, 9, true, 200).x), bits_hash(shared.x));
}

class SharedGaussSeidel : public ::testing::Test {
protected:
  static void SetUpTestSuite() { ensure_mpi_initialised(); }
};

TEST_F(SharedGaussSeidel, WalledBoxSameBitsOnAnyRanks) {
  check_box({{14, 6, 11}, {1, 1, 1}, {false, false, false}});
}

TEST_F(SharedGaussSeidel, ZComponentBoxFromIndexZeroSameBitsOnAnyRanks) {
  check_box({{10, 5, 12}, {1, 1, 0}, {false, false, false}});
}

TEST_F(SharedGaussSeidel, PeriodicBoxOddPeriodSameBitsOnAnyRanks) {
  check_box({{9, 4, 7}, {1, 1, 1}, {true, false, true}});
}

TEST_F(SharedGaussSeidel, FewerPlanesThanRanksSameBitsOnAnyRanks) {
  check_box({{12, 5, 3}, {1, 1, 1}, {false, true, false}});
}

TEST_F(SharedGaussSeidel, TwoDimensionalBoxSameBitsOnAnyRanks) {
  check_box({{20, 1, 30}, {0, 1, 1}, {false, false, false}});
}

} // namespace
