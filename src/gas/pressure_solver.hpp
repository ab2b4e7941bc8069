// Linear solver for the 7-point systems of the gas phase (pressure correction; momentum when
// Gauss-Seidel is not enough), on a structured box. The only file that sees hypre: its Struct
// interface, PCG (symmetric matrices) or GMRES (non-symmetric) preconditioned by one PFMG (or
// SMG) multigrid cycle. The hypre grid, stencil, matrix, vectors and Krylov solver are created
// once; each solve only overwrites the matrix and vector values. The multigrid set-up (coarse
// operators) is redone according to StructSolverOptions::reuse (docs/gas.md, "Linear solvers").
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
  int iterations = 0;             ///< Krylov iterations or Gauss-Seidel sweeps (direct: 1)
  double relative_residual = 0.0; ///< ||b - A x||_2 / ||b||_2
  bool converged = false;         ///< relative_residual <= the requested tolerance
  int setups = 0;                 ///< multigrid set-ups done for this solve (0: reused)
};

/// How the hypre solver is preconditioned and when its multigrid set-up is redone.
struct StructSolverOptions {
  enum class Multigrid { pfmg, smg };
  /// When the multigrid set-up is redone (the matrix values change at every solve):
  ///  every_solve: before each solve;
  ///  per_step: at the first solve after new_step() (reused for the rest of the flow step);
  ///  adaptive: when the previous solve needed more than twice (+2) the iterations of the
  ///    first solve after the last set-up.
  /// A solve with a reused set-up that does not converge is repeated after a fresh set-up.
  enum class Reuse { every_solve, per_step, adaptive };
  Multigrid multigrid = Multigrid::pfmg;
  Reuse reuse = Reuse::adaptive;
  int relax_type = 2; ///< PFMG: 0 Jacobi, 1 weighted Jacobi, 2 red-black GS (symmetric),
                      ///< 3 red-black GS (non-symmetric); red-black forces rap_type 1 in hypre
  int rap_type = 0;   ///< PFMG coarse operators: 0 Galerkin, 1 non-Galerkin
  int pre_relax = 3, post_relax = 3; ///< relaxation sweeps per level
  int skip_relax = 1;                ///< PFMG: skip relaxation on some levels (hypre's default 1)
  /// PFMG levels: max_levels > 0 caps them; 0 coarsens while a level keeps at least
  /// min_coarse_cells cells (the per-level overhead of hypre dominates tiny levels);
  /// max_levels = 0 and min_coarse_cells = 0: hypre's choice. Always limited further so that
  /// periodic axes keep a period >= 3.
  int max_levels = 0;
  int min_coarse_cells = 64;
  /// Symmetric systems on boxes without periodic axes: solved directly by banded Cholesky
  /// (band_solver.hpp) instead of hypre when N b^2 / 2 (N unknowns, b the half bandwidth with
  /// the longest axis numbered last) is at most this many multiply-adds; 0: never. A direct
  /// solution whose relative residual misses the tolerance (or a failed factorisation) is
  /// handed to hypre as its initial guess. The gas solver's pressure correction enables it
  /// (LinearSolverOptions).
  double direct_max_work = 0.0;
};

/// The MPI ranks that solve one symmetric system together (StructLinearSolver::share): each
/// holds the whole system and the whole solution, and solves the rows of its part of the box.
struct SharedSolve {
  int comm = -1; ///< the communicator's MPI_Comm_c2f handle; -1: this process alone
  int rank = 0, size = 1;
  /// Parts per grid axis (product = size), or {0, 0, 0}: chosen (the longest parts cut first).
  std::array<int, 3> parts{0, 0, 0};
  /// false: a solve writes only this rank's part of the solution (no gather).
  bool whole_solution = true;
};

class StructLinearSolver {
public:
  /// padded: array dimensions (x fastest); lo/hi: inclusive box of unknowns in padded indices;
  /// periodic: per axis (the box then spans the period); symmetric: PCG, else GMRES.
  /// A box one cell thick along y (not periodic there) is solved as a 2-D hypre problem.
  StructLinearSolver(std::array<int, 3> padded, std::array<int, 3> lo, std::array<int, 3> hi,
                     std::array<bool, 3> periodic, bool symmetric,
                     const StructSolverOptions& options = {});
  ~StructLinearSolver();
  StructLinearSolver(const StructLinearSolver&) = delete;
  StructLinearSolver& operator=(const StructLinearSolver&) = delete;

  /// Solves for x on the box (x outside the box untouched); x holds the initial guess.
  LinearSolveStats solve(const StencilSystem& sys, std::vector<double>& x, double rel_tol,
                         int max_iterations);
  /// From now on, solve on the ranks of `shared`, with the same bits for any number of them
  /// (docs/parallel.md, "The gas on several ranks"): the box is cut into shared.size parts, each
  /// rank hands hypre the rows of its part, PCG runs with fixed-point inner products
  /// (rank_dot.hpp) preconditioned by one PFMG cycle whose coarsening is fixed from the whole
  /// system (not by hypre's sums over the ranks), and the ranks' parts of the solution are
  /// gathered on every rank. Symmetric systems only (std::logic_error otherwise); collective:
  /// every solve must then be made by all ranks. The direct path, when it applies, stays a
  /// solve of the whole system on each rank (the same bits everywhere).
  void share(const SharedSolve& shared);
  /// Whether a solve reads rows of the system outside this rank's part (part_lo() .. part_hi()):
  /// not shared, or solved whole by the direct solver on every rank. When false, the caller
  /// need only assemble the part's rows.
  bool reads_whole_system() const;
  /// This rank's part of the box (inclusive padded indices; hi < lo along some axis: empty).
  std::array<int, 3> part_lo() const;
  std::array<int, 3> part_hi() const;
  /// A new flow step begins (Reuse::per_step redoes the set-up at the next solve).
  void new_step();
  /// Replaces the options; the next solve does a fresh set-up.
  void set_options(const StructSolverOptions& options);
  const StructSolverOptions& options() const;
  /// Multigrid set-ups and solves since construction; solves done by the direct solver.
  long setups() const;
  long solves() const;
  long direct_solves() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Initialises MPI (one rank, MPI_THREAD_FUNNELED) and hypre once, if not done already.
void ensure_mpi_initialised();
/// True once MPI has been initialised in this process (by the first solve that needs hypre).
bool mpi_started();

} // namespace fluidem::gas
