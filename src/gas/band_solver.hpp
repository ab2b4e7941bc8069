// Direct solver for the small symmetric positive definite 7-point systems of the gas phase (the
// pressure correction on grids of a few hundred to a few thousand cells, e.g. the 15 x 25 cells
// of the Tsuji bed): banded Cholesky factorisation A = L L^T (Golub & Van Loan, Matrix
// Computations, 4th ed., Algorithm 4.3.5 "band Cholesky"), then the two triangular solves.
// With the unknowns numbered along the box axes, the slowest axis last, the band half-width is
// the product of the two faster extents (15 for a 15 x 1 x 25 box); the work is about
// N b^2 / 2 multiply-adds for the factorisation and 2 N b per solve, and nothing is iterative:
// the answer is exact up to round-off (the iterative solvers reach it to their tolerance).
#pragma once
#include <array>
#include <cstddef>
#include <vector>

namespace fluidem::gas {

class BandCholesky {
public:
  /// extent: unknowns per axis of the box, axis 0 fastest in the numbering (the caller picks
  /// the order). Allocates the band once.
  explicit BandCholesky(std::array<int, 3> extent);

  std::size_t size() const { return n_; }
  /// Half bandwidth b: row i couples to i - b .. i + b.
  int bandwidth() const { return b_; }
  /// Multiply-adds of one factorisation, ~ N b^2 / 2.
  double factor_work() const { return 0.5 * static_cast<double>(n_) * b_ * b_; }

  /// Entry (i, i - off) = (i - off, i) of the symmetric matrix, off = 0 (diagonal) .. b; zero
  /// the band first with clear(). Only the couplings of the 7-point stencil (off = 0, 1, e1,
  /// e1 e2) need to be set. (Stored as the upper band, row i - off, the factor's layout.)
  void clear();
  double& lower(std::size_t i, int off) {
    return base()[band_start(i - static_cast<std::size_t>(off)) + static_cast<std::size_t>(off)];
  }
  /// Factorises in place. False if a pivot is not positive (not SPD to round-off): the band
  /// is then unusable until set again.
  bool factor();
  /// x = A^-1 rhs with the factor (rhs and x may be the same array).
  void solve(const double* rhs, double* x) const;

  /// Column alignment of the storage, in doubles (64 bytes: one AVX-512 vector, two AVX2, four
  /// SSE2).
  static constexpr std::size_t kAlign = 8;

private:
  // Row r of U = L^T holds U(r, r .. r + b) from slot band_start(r) = r stride + r mod kAlign:
  // column c then lies at the same offset modulo kAlign in every row, so that factor()'s
  // updates, in whole aligned chunks, load a row's values exactly where an earlier update or
  // the scaling stored them (a load across two recent stores waits for them) and vectorise
  // without remainders. Before the band: up to kAlign - 1 slots the chunks also cover (their
  // values are never read into the band); after it, zeros (what the chunks read past the band).
  std::size_t band_start(std::size_t r) const { return r * stride_ + r % kAlign; }
  double* base() { return store_.data() + offset_; }
  const double* base() const { return store_.data() + offset_; }

  std::size_t n_ = 0;
  int b_ = 0;
  std::size_t stride_ = kAlign; ///< b + 2 kAlign - 1 rounded up to kAlign
  std::size_t offset_ = 0;      ///< of the first row in store_: 64-byte aligned
  std::vector<double> store_;
  std::vector<double> inv_; ///< 1 / L(i, i)
};

} // namespace fluidem::gas
