// Red-black Gauss-Seidel for the 7-point momentum systems of the gas phase (docs/gas.md,
// "Linear solvers"). With backward Euler at flow time steps DT ~ 1e-4 s and the particle drag
// on the diagonal the momentum matrices are strongly diagonally dominant, and a handful of
// sweeps reaches the tolerance: far cheaper than a Krylov solve with a multigrid set-up.
//
// Convergence: ||b - A x||_2 <= rel_tol ||b||_2 (as hypre's relative residual). After a black
// half-sweep the residual vanishes on the black points, so the red half-sweep that follows
// computes the full residual of the previous sweep for free; the solve stops once it is below
// the tolerance (the returned x then carries that extra red half-sweep). When the observed
// contraction per sweep says the tolerance will not be reached within max_sweeps (a
// diffusion-dominated system, e.g. DT near the viscous time), it stops early and reports
// converged = false; the caller then falls back to a Krylov solver.
//
// Threads (optional): the rows of a half-sweep are independent (their neighbours along the
// sweep are the other colour), so they can run in parallel; the residual norms are summed per
// row and then over rows in a fixed order. Results are bitwise independent of the thread count
// and of `threaded`.
#pragma once
#include "gas/pressure_solver.hpp"
#include <array>
#include <vector>

namespace fluidem::gas {

class RedBlackGaussSeidel {
public:
  /// Same box conventions as StructLinearSolver: padded array dimensions (x fastest), inclusive
  /// box lo..hi of unknowns, periodic axes (the box spans the period; the ghost layer of x
  /// outside the box is used as the periodic image and overwritten).
  /// threaded: run the half-sweeps with OpenMP threads (worth it only for large boxes: each
  /// half-sweep is a parallel region with its barrier).
  RedBlackGaussSeidel(std::array<int, 3> padded, std::array<int, 3> lo, std::array<int, 3> hi,
                      std::array<bool, 3> periodic, bool threaded = false);

  /// Solves for x on the box (x holds the initial guess; outside the box only the periodic
  /// images are written). Entries of sys that link out of the box along a non-periodic axis
  /// must be 0; x is read there only inside the padded array (it must be finite).
  LinearSolveStats solve(const StencilSystem& sys, std::vector<double>& x, double rel_tol,
                         int max_sweeps);

private:
  void refresh_periodic(std::vector<double>& x) const;
  /// One half-sweep over the points of `colour`; returns sum over them of the squared
  /// residual before the update.
  double half_sweep(const StencilSystem& sys, std::vector<double>& x, int colour);

  std::array<int, 3> padded_{}, lo_{}, hi_{};
  std::array<bool, 3> periodic_{};
  long sy_ = 0, sz_ = 0;
  int rows_ = 0; ///< (j, k) rows of the box
  bool parallel_ = false;
  std::vector<double> row_sum_;
  std::vector<double> zeros_; ///< stands in for the row below a box that starts at index 0
};

} // namespace fluidem::gas
