// Preconditioned conjugate gradients [Saad 2003, Alg. 9.1] on the unknowns of one rank, with
// every inner product taken by a caller-given reduction over the ranks. When the reduction's
// result does not depend on how the unknowns are split (fixed-point sums, rank_dot.hpp) and the
// matrix product and preconditioner are pointwise (hypre's Struct matvec and PFMG with red-black
// Gauss-Seidel), the iterates, the iteration count and the stopping decision are the same bits
// on any number of ranks (docs/parallel.md, "The gas on several ranks").
#pragma once
#include <functional>
#include <vector>

namespace fluidem::gas {

struct SharedPcgOperators {
  /// out = A in, on this rank's unknowns (in: this rank's part of a global vector).
  std::function<void(const std::vector<double>& in, std::vector<double>& out)> apply;
  /// out = M^-1 in (one multigrid cycle from a zero guess).
  std::function<void(const std::vector<double>& in, std::vector<double>& out)> precondition;
  /// sum over all ranks' unknowns of a_i b_i.
  std::function<double(const std::vector<double>& a, const std::vector<double>& b)> dot;
};

/// The iteration's vectors, kept between solves (no allocation, no fresh pages, per solve).
struct SharedPcgWork {
  std::vector<double> r, z, p, q;
};

struct SharedPcgResult {
  int iterations = 0;
  double relative_residual = 0.0; ///< ||b - A x||_2 / ||b||_2 (the recursively updated r)
  bool converged = false;
};

/// Solves A x = b to ||r|| <= rel_tol ||b|| or max_iterations; x: the initial guess, then the
/// iterate. b = 0 gives x = 0 (as hypre's PCG answers). A breakdown (p.Ap <= 0 or not finite:
/// A or M not positive definite) stops the iteration unconverged.
SharedPcgResult shared_pcg(const SharedPcgOperators& op, const std::vector<double>& b,
                           std::vector<double>& x, double rel_tol, int max_iterations,
                           SharedPcgWork& work);

} // namespace fluidem::gas
