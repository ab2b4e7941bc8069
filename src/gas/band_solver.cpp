// Banded Cholesky factorisation and solves (band_solver.hpp).
#include "gas/band_solver.hpp"
#include <algorithm>
#include <cmath>

namespace fluidem::gas {

BandCholesky::BandCholesky(std::array<int, 3> extent) {
  n_ = static_cast<std::size_t>(extent[0]) * static_cast<std::size_t>(extent[1]) *
       static_cast<std::size_t>(extent[2]);
  b_ = extent[2] > 1 ? extent[0] * extent[1] : (extent[1] > 1 ? extent[0] : 1);
  if (extent[0] == 1 && extent[1] == 1 && extent[2] == 1) b_ = 0;
  // Row k of U = L^T holds U(k, k .. k + b), then b + 1 zeros: the updates of factor() run over
  // the full width b + 1 of a row (a fixed trip count: they vectorise without remainders),
  // reading zeros beyond the band. Spare rows at the end keep the updates of the last rows
  // inside the array (they only ever touch columns >= n, which are never read).
  stride_ = 2 * static_cast<std::size_t>(b_ + 1);
  a_.assign((n_ + 1) * stride_, 0.0);
  inv_.assign(n_, 0.0);
}

void BandCholesky::clear() {
  // The band part of each row only: the zeros that follow it are never written (factor()'s
  // updates write columns k+i .. k+i+b of row k+i, its band part, and only read the zeros).
  const std::size_t w = static_cast<std::size_t>(b_) + 1;
  for (std::size_t r = 0; r <= n_; ++r) std::fill_n(&a_[r * stride_], w, 0.0);
}

namespace {
/// r[m] -= u s[m], m < W; r and s do not overlap (two different rows of the band).
template <std::size_t W>
void subtract_scaled(double* __restrict r, const double* __restrict s, double u) {
  for (std::size_t m = 0; m < W; ++m) r[m] -= u * s[m];
}
} // namespace

// Right-looking band Cholesky on U = L^T stored by rows [Golub & Van Loan, Alg. 4.3.5 in its
// outer-product form]: for k = 0 .. n-1,
//   U(k, k) = sqrt(A(k, k)),  U(k, k+m) = A(k, k+m) / U(k, k)  (m = 1 .. b),
//   A(k+i, k+i+m) -= U(k, k+i) U(k, k+i+m)  (i = 1 .. b, m = 0 .. b-i),
// each update a contiguous axpy of two rows (no reduction chain: it vectorises). The axpy
// runs over the whole row width b + 1: its entries past m = b - i read the zeros that follow
// row k's band (subtracting u * 0 leaves them as they are).
bool BandCholesky::factor() {
  const std::size_t w = static_cast<std::size_t>(b_) + 1, b = static_cast<std::size_t>(b_);
  for (std::size_t k = 0; k < n_; ++k) {
    double* rk = &a_[k * stride_];
    if (!(rk[0] > 0.0)) return false;
    const double d = std::sqrt(rk[0]), inv = 1.0 / d;
    rk[0] = d;
    inv_[k] = inv;
    const std::size_t last = std::min(b, n_ - 1 - k); // columns k+1 .. k+last exist
    for (std::size_t m = 1; m <= last; ++m) rk[m] *= inv;
    for (std::size_t i = 1; i <= last; ++i) {
      const double u = rk[i];
      if (u == 0.0) continue;
      double* ri = &a_[(k + i) * stride_];
      const double* src = rk + i;
      switch (w) { // compile-time widths for common grids (e.g. the 15-cell-wide Tsuji bed)
      case 8:
        subtract_scaled<8>(ri, src, u);
        break;
      case 16:
        subtract_scaled<16>(ri, src, u);
        break;
      case 32:
        subtract_scaled<32>(ri, src, u);
        break;
      default: { // the band part only
        const std::size_t len = last - i + 1;
        for (std::size_t m = 0; m < len; ++m) ri[m] -= u * src[m];
      }
      }
    }
  }
  return true;
}

void BandCholesky::solve(const double* rhs, double* x) const {
  const std::size_t b = static_cast<std::size_t>(b_);
  if (x != rhs) std::copy(rhs, rhs + n_, x);
  // U^T y = rhs (forward), column-oriented: once y_k is final, remove it from rows k+1 .. k+b.
  for (std::size_t k = 0; k < n_; ++k) {
    const double* rk = &a_[k * stride_];
    x[k] *= inv_[k];
    const double yk = x[k];
    const std::size_t last = std::min(b, n_ - 1 - k);
    for (std::size_t m = 1; m <= last; ++m) x[k + m] -= rk[m] * yk;
  }
  // U x = y (backward): x_k = (y_k - sum_m U(k, k+m) x_{k+m}) / U(k, k).
  for (std::size_t k = n_; k-- > 0;) {
    const double* rk = &a_[k * stride_];
    const std::size_t last = std::min(b, n_ - 1 - k);
    double s0 = 0.0, s1 = 0.0; // two partial sums, fixed order
    std::size_t m = 1;
    for (; m + 1 <= last; m += 2) {
      s0 += rk[m] * x[k + m];
      s1 += rk[m + 1] * x[k + m + 1];
    }
    if (m <= last) s0 += rk[m] * x[k + m];
    x[k] = (x[k] - (s0 + s1)) * inv_[k];
  }
}

} // namespace fluidem::gas
