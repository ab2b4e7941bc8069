// Linear solver for the 7-point systems of the gas phase (pressure correction, momentum), on
// a structured box. The only file that sees hypre: its Struct interface, PCG (symmetric
// matrices) or GMRES (non-symmetric) preconditioned by PFMG geometric multigrid.
#pragma once
#include <array>
#include <memory>
#include <vector>

namespace fluidem::gas {

/// Rows of a 7-point system in the padded (ghost-layer) layout of GasGrid:
/// diag[P] x[P] + xm[P] x[P-x] + xp[P] x[P+x] + ym.. + zp[P] x[P+z] = rhs[P].
/// Entries pointing out of the box along a non-periodic axis must be 0; along a periodic axis
/// they wrap around (the box spans exactly one period there).
struct StencilSystem {
  std::vector<double> diag, xm, xp, ym, yp, zm, zp, rhs;
  void resize(std::size_t n);
};

struct LinearSolveStats {
  int iterations = 0;
  double relative_residual = 0.0;
};

class StructLinearSolver {
public:
  /// padded: array dimensions (x fastest); lo/hi: inclusive box of unknowns in padded indices;
  /// periodic: per axis (the box then spans the period); symmetric: PCG, else GMRES.
  StructLinearSolver(std::array<int, 3> padded, std::array<int, 3> lo, std::array<int, 3> hi,
                     std::array<bool, 3> periodic, bool symmetric);
  ~StructLinearSolver();
  StructLinearSolver(const StructLinearSolver&) = delete;
  StructLinearSolver& operator=(const StructLinearSolver&) = delete;

  /// Solves for x on the box (x outside the box untouched); x holds the initial guess.
  LinearSolveStats solve(const StencilSystem& sys, std::vector<double>& x, double rel_tol,
                         int max_iterations);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Initialises MPI (one rank, MPI_THREAD_FUNNELED) and hypre once, if not done already.
void ensure_mpi_initialised();

} // namespace fluidem::gas
