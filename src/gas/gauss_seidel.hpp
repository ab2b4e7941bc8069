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
//
// Ranks (optional, share()): the ranks sweep their own contiguous z planes of the box and pass
// the planes at their cuts to their neighbours after each half-sweep; the residual norms of all
// rows are gathered and summed in the same order as on one process. Every point gets the same
// arithmetic as on one process, so the solution is the same bits for any number of ranks
// (docs/parallel.md, "The gas on several ranks").
#pragma once
#include "gas/pressure_solver.hpp"
#include "gas/rank_dot.hpp"
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
  /// Shared (share()): only the rows of this rank's planes of sys are read, and x holds the
  /// whole solution on every rank on return.
  LinearSolveStats solve(const StencilSystem& sys, std::vector<double>& x, double rel_tol,
                         int max_sweeps);

  /// From now on, solve together with the ranks of the communicator `comm` (its MPI_Comm_c2f
  /// handle, rank_dot.hpp), each sweeping its part of the box's z planes (contiguous, as even
  /// as the planes allow; ranks beyond the number of planes get none). Every solve is then
  /// collective.
  void share(int comm, int rank, int size);
  /// The same with the planes given: rank r sweeps planes plane_begin[r] .. plane_begin[r+1] - 1
  /// (size + 1 entries, non-decreasing, the last hi + 1; the first is taken as the box's lo).
  void share(int comm, int rank, const std::vector<int>& plane_begin);
  /// Shared: false leaves x current only on this rank's planes and the halo planes beside them
  /// (plane_lo() - 1, plane_hi() + 1) on return from solve(), instead of gathering the whole
  /// solution on every rank; x must then be current there on entry too.
  void set_whole_solution(bool whole) { whole_solution_ = whole; }
  bool shared() const { return comm_ != kNotShared; }
  /// This rank's planes lo..hi of the box (hi < lo: none); the whole box when not shared.
  int plane_lo() const { return k_lo_; }
  int plane_hi() const { return k_hi_; }
  /// Collective when shared: every rank's array gets the other ranks' planes of the box (each
  /// rank's whole padded planes). Nothing when not shared.
  void gather_planes(std::vector<double>& a) const;

private:
  static constexpr int kNotShared = -2;
  /// The ghost layers of the periodic axes; z only when `with_z`.
  void refresh_periodic(std::vector<double>& x, bool with_z = true) const;
  /// One half-sweep over the points of `colour` on this rank's planes; returns the sum over
  /// all the box's points of that colour of the squared residual before the update (when
  /// `want_sum`; shared, the ranks' row sums are gathered for it).
  double half_sweep(const StencilSystem& sys, std::vector<double>& x, int colour, bool want_sum);
  /// Shared: the planes next to this rank's part (z-periodic: across the period) from the
  /// ranks that own them.
  void exchange_halo(std::vector<double>& x) const;
  /// The per-row sums of all rows (shared: gathered from the ranks) added in row order.
  double sum_rows();

  std::array<int, 3> padded_{}, lo_{}, hi_{};
  std::array<bool, 3> periodic_{};
  long sy_ = 0, sz_ = 0;
  int rows_ = 0; ///< (j, k) rows of the box
  int ny_ = 0;   ///< rows per plane
  int comm_ = kNotShared;
  int k_lo_ = 0, k_hi_ = -1;     ///< this rank's planes
  int r_begin_ = 0, r_end_ = 0;  ///< this rank's rows
  std::vector<int> plane_begin_; ///< first plane of each rank, and one past the last
  int rank_ = 0;
  bool parallel_ = false;
  bool whole_solution_ = true;
  std::vector<double> row_sum_;
  std::vector<double> zeros_; ///< stands in for the row below a box that starts at index 0
};

} // namespace fluidem::gas
