// hypre Struct wrapper: PFMG-preconditioned PCG / GMRES on one box, one MPI rank.
// Open MPI: C bindings only (the C++ bindings would need libmpi_cxx at link time).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include "gas/pressure_solver.hpp"
#include "core/error.hpp"
#include <HYPRE_struct_ls.h>
#include <algorithm>
#include <cstdlib>
#include <mpi.h>
#include <mutex>

namespace fluidem::gas {

void StencilSystem::resize(std::size_t n) {
  for (auto* v : {&diag, &xm, &xp, &ym, &yp, &zm, &zp, &rhs}) v->assign(n, 0.0);
}

namespace {
void finalize_mpi() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}
void finalize_hypre() {
  HYPRE_Finalize();
}
} // namespace

void ensure_mpi_initialised() {
  static std::once_flag once;
  std::call_once(once, [] {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) {
      // Open MPI refuses some set-ups as root only under mpirun; a singleton (no mpirun) works
      // as root here. Keep the singleton from probing network interfaces.
      setenv("OMPI_MCA_btl", "self", 0);
      int provided = 0;
      if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
        throw InstabilityError("gas: MPI_Init_thread failed (needed by hypre)");
      std::atexit(finalize_mpi);
    }
    HYPRE_Init();
    std::atexit(finalize_hypre); // registered last, so it runs before MPI_Finalize
  });
}

struct StructLinearSolver::Impl {
  std::array<int, 3> padded{}, lo{}, hi{};
  std::array<bool, 3> periodic{}; ///< periodic in hypre (period >= 3)
  std::array<int, 3> fold{};      ///< periodic with period 1 or 2: folded here
  bool symmetric = false;
  int max_levels = 0; ///< PFMG levels (0: hypre's default)
  HYPRE_StructGrid grid = nullptr;
  HYPRE_StructStencil stencil = nullptr;
  std::vector<double> values, buf_b, buf_x;
};

StructLinearSolver::StructLinearSolver(std::array<int, 3> padded, std::array<int, 3> lo,
                                       std::array<int, 3> hi, std::array<bool, 3> periodic,
                                       bool symmetric)
    : impl_(std::make_unique<Impl>()) {
  ensure_mpi_initialised();
  Impl& m = *impl_;
  m.padded = padded;
  m.lo = lo;
  m.hi = hi;
  m.symmetric = symmetric;
  // hypre's periodic Struct grids misbehave when a period (on any PFMG level) is below 3: the
  // two neighbours along the axis coincide. Periods 1 and 2 are folded into the stencil here;
  // for the others PFMG coarsening is limited so the coarsest period stays >= 3.
  int min_period = 1 << 30;
  for (int d = 0; d < 3; ++d) {
    const int period = hi[d] - lo[d] + 1;
    m.periodic[d] = periodic[d] && period >= 3;
    m.fold[d] = periodic[d] && period < 3 ? period : 0;
    if (m.periodic[d]) min_period = std::min(min_period, period);
  }
  if (min_period < (1 << 30)) {
    m.max_levels = 1;
    for (int p = min_period; p / 2 >= 3; p /= 2) ++m.max_levels;
  }
  HYPRE_StructGridCreate(MPI_COMM_WORLD, 3, &m.grid);
  HYPRE_StructGridSetExtents(m.grid, m.lo.data(), m.hi.data());
  std::array<int, 3> period{};
  for (int d = 0; d < 3; ++d) period[d] = m.periodic[d] ? hi[d] - lo[d] + 1 : 0;
  HYPRE_StructGridSetPeriodic(m.grid, period.data());
  HYPRE_StructGridAssemble(m.grid);
  HYPRE_StructStencilCreate(3, 7, &m.stencil);
  int offsets[7][3] = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0},
                       {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  for (int e = 0; e < 7; ++e) HYPRE_StructStencilSetElement(m.stencil, e, offsets[e]);
  std::size_t n = 1;
  for (int d = 0; d < 3; ++d) n *= static_cast<std::size_t>(hi[d] - lo[d] + 1);
  m.values.resize(7 * n);
  m.buf_b.resize(n);
  m.buf_x.resize(n);
}

StructLinearSolver::~StructLinearSolver() {
  HYPRE_StructStencilDestroy(impl_->stencil);
  HYPRE_StructGridDestroy(impl_->grid);
}

LinearSolveStats StructLinearSolver::solve(const StencilSystem& sys, std::vector<double>& x,
                                           double rel_tol, int max_iterations) {
  Impl& m = *impl_;
  const long sx = 1, sy = m.padded[0], sz = static_cast<long>(m.padded[0]) * m.padded[1];
  const std::array<const std::vector<double>*, 7> a{&sys.diag, &sys.xm, &sys.xp, &sys.ym,
                                                    &sys.yp,   &sys.zm, &sys.zp};
  std::size_t q = 0;
  for (int k = m.lo[2]; k <= m.hi[2]; ++k)
    for (int j = m.lo[1]; j <= m.hi[1]; ++j)
      for (int i = m.lo[0]; i <= m.hi[0]; ++i, ++q) {
        const long p = i * sx + j * sy + k * sz;
        double* v = &m.values[7 * q];
        for (int e = 0; e < 7; ++e) v[e] = (*a[e])[p];
        // Periods 1 and 2: both neighbours are the point itself (1) or the other point (2).
        const int c[3] = {i, j, k};
        for (int d = 0; d < 3; ++d) {
          if (m.fold[d] == 1) {
            v[0] += v[1 + 2 * d] + v[2 + 2 * d];
            v[1 + 2 * d] = v[2 + 2 * d] = 0.0;
          } else if (m.fold[d] == 2) {
            const bool first = c[d] == m.lo[d];
            v[first ? 2 + 2 * d : 1 + 2 * d] += v[first ? 1 + 2 * d : 2 + 2 * d];
            v[first ? 1 + 2 * d : 2 + 2 * d] = 0.0;
          }
        }
        // Links leaving the box along a non-periodic axis are dropped (documented as 0).
        if (!m.periodic[0] && i == m.lo[0]) m.values[7 * q + 1] = 0.0;
        if (!m.periodic[0] && i == m.hi[0]) m.values[7 * q + 2] = 0.0;
        if (!m.periodic[1] && j == m.lo[1]) m.values[7 * q + 3] = 0.0;
        if (!m.periodic[1] && j == m.hi[1]) m.values[7 * q + 4] = 0.0;
        if (!m.periodic[2] && k == m.lo[2]) m.values[7 * q + 5] = 0.0;
        if (!m.periodic[2] && k == m.hi[2]) m.values[7 * q + 6] = 0.0;
        m.buf_b[q] = sys.rhs[p];
        m.buf_x[q] = x[p];
      }
  HYPRE_StructMatrix A = nullptr;
  HYPRE_StructVector b = nullptr, xv = nullptr;
  HYPRE_StructMatrixCreate(MPI_COMM_WORLD, m.grid, m.stencil, &A);
  HYPRE_StructMatrixInitialize(A);
  int entries[7] = {0, 1, 2, 3, 4, 5, 6};
  HYPRE_StructMatrixSetBoxValues(A, m.lo.data(), m.hi.data(), 7, entries, m.values.data());
  HYPRE_StructMatrixAssemble(A);
  HYPRE_StructVectorCreate(MPI_COMM_WORLD, m.grid, &b);
  HYPRE_StructVectorInitialize(b);
  HYPRE_StructVectorSetBoxValues(b, m.lo.data(), m.hi.data(), m.buf_b.data());
  HYPRE_StructVectorAssemble(b);
  HYPRE_StructVectorCreate(MPI_COMM_WORLD, m.grid, &xv);
  HYPRE_StructVectorInitialize(xv);
  HYPRE_StructVectorSetBoxValues(xv, m.lo.data(), m.hi.data(), m.buf_x.data());
  HYPRE_StructVectorAssemble(xv);

  HYPRE_StructSolver precond = nullptr, solver = nullptr;
  HYPRE_StructPFMGCreate(MPI_COMM_WORLD, &precond);
  HYPRE_StructPFMGSetMaxIter(precond, 1);
  HYPRE_StructPFMGSetTol(precond, 0.0);
  HYPRE_StructPFMGSetZeroGuess(precond);
  HYPRE_StructPFMGSetRelaxType(precond, m.symmetric ? 2 : 3); // red-black Gauss-Seidel
  HYPRE_StructPFMGSetNumPreRelax(precond, 1);
  HYPRE_StructPFMGSetNumPostRelax(precond, 1);
  if (m.max_levels > 0) HYPRE_StructPFMGSetMaxLevels(precond, m.max_levels);

  LinearSolveStats stats;
  if (m.symmetric) {
    HYPRE_StructPCGCreate(MPI_COMM_WORLD, &solver);
    HYPRE_StructPCGSetTol(solver, rel_tol);
    HYPRE_StructPCGSetMaxIter(solver, max_iterations);
    HYPRE_StructPCGSetTwoNorm(solver, 1);
    HYPRE_StructPCGSetPrecond(solver, HYPRE_StructPFMGSolve, HYPRE_StructPFMGSetup, precond);
    HYPRE_StructPCGSetup(solver, A, b, xv);
    HYPRE_StructPCGSolve(solver, A, b, xv);
    HYPRE_StructPCGGetNumIterations(solver, &stats.iterations);
    HYPRE_StructPCGGetFinalRelativeResidualNorm(solver, &stats.relative_residual);
    HYPRE_StructPCGDestroy(solver);
  } else {
    HYPRE_StructGMRESCreate(MPI_COMM_WORLD, &solver);
    HYPRE_StructGMRESSetTol(solver, rel_tol);
    HYPRE_StructGMRESSetMaxIter(solver, max_iterations);
    HYPRE_StructGMRESSetKDim(solver, 30);
    HYPRE_StructGMRESSetPrecond(solver, HYPRE_StructPFMGSolve, HYPRE_StructPFMGSetup, precond);
    HYPRE_StructGMRESSetup(solver, A, b, xv);
    HYPRE_StructGMRESSolve(solver, A, b, xv);
    HYPRE_StructGMRESGetNumIterations(solver, &stats.iterations);
    HYPRE_StructGMRESGetFinalRelativeResidualNorm(solver, &stats.relative_residual);
    HYPRE_StructGMRESDestroy(solver);
  }
  HYPRE_ClearAllErrors(); // non-convergence is judged by the outer iterations
  HYPRE_StructPFMGDestroy(precond);
  HYPRE_StructVectorGetBoxValues(xv, m.lo.data(), m.hi.data(), m.buf_x.data());
  HYPRE_StructVectorDestroy(xv);
  HYPRE_StructVectorDestroy(b);
  HYPRE_StructMatrixDestroy(A);

  q = 0;
  for (int k = m.lo[2]; k <= m.hi[2]; ++k)
    for (int j = m.lo[1]; j <= m.hi[1]; ++j)
      for (int i = m.lo[0]; i <= m.hi[0]; ++i, ++q) x[i * sx + j * sy + k * sz] = m.buf_x[q];
  return stats;
}

} // namespace fluidem::gas
