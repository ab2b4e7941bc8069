// Banded Cholesky factorisation and solves (band_solver.hpp).
#include "gas/band_solver.hpp"
#include <algorithm>
#include <cmath>

namespace fluidem::gas {

namespace {
/// sum_k a[k] b[k], k < len, in four interleaved partial sums (independent chains the compiler
/// can pipeline; a fixed order, so the result does not depend on anything but the inputs).
inline double dot(const double* a, const double* b, long len) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  long k = 0;
  for (; k + 4 <= len; k += 4) {
    s0 += a[k] * b[k];
    s1 += a[k + 1] * b[k + 1];
    s2 += a[k + 2] * b[k + 2];
    s3 += a[k + 3] * b[k + 3];
  }
  for (; k < len; ++k) s0 += a[k] * b[k];
  return (s0 + s1) + (s2 + s3);
}
} // namespace

BandCholesky::BandCholesky(std::array<int, 3> extent) {
  n_ = static_cast<std::size_t>(extent[0]) * static_cast<std::size_t>(extent[1]) *
       static_cast<std::size_t>(extent[2]);
  b_ = extent[2] > 1 ? extent[0] * extent[1] : (extent[1] > 1 ? extent[0] : 1);
  if (extent[0] == 1 && extent[1] == 1 && extent[2] == 1) b_ = 0;
  a_.assign(n_ * static_cast<std::size_t>(b_ + 1), 0.0);
  inv_.assign(n_, 0.0);
}

void BandCholesky::clear() {
  std::fill(a_.begin(), a_.end(), 0.0);
}

// Row-oriented band Cholesky [Golub & Van Loan, Alg. 4.3.5]: for row i and column j <= i,
//   L(i, j) = (A(i, j) - sum_{k < j} L(i, k) L(j, k)) / L(j, j),  L(i, i) = sqrt(A(i, i) - ...),
// the sums running over the columns inside both rows' bands.
bool BandCholesky::factor() {
  const std::size_t w = static_cast<std::size_t>(b_) + 1;
  const long b = b_;
  for (std::size_t i = 0; i < n_; ++i) {
    double* ri = &a_[i * w]; // ri[b - (i - j)] = L(i, j)
    const long li = static_cast<long>(i);
    const long j0 = std::max(0L, li - b);
    for (long j = j0; j <= li; ++j) {
      const double* rj = &a_[static_cast<std::size_t>(j) * w];
      const long k0 = std::max(j0, j - b); // columns shared by both bands
      // L(i, k) = ri[b - (i - k)], L(j, k) = rj[b - (j - k)].
      const double s = ri[b - (li - j)] - dot(ri + (b - (li - k0)), rj + (b - (j - k0)), j - k0);
      if (j < li) {
        ri[b - (li - j)] = s * inv_[static_cast<std::size_t>(j)];
      } else {
        if (!(s > 0.0)) return false;
        ri[b] = std::sqrt(s);
        inv_[i] = 1.0 / ri[b];
      }
    }
  }
  return true;
}

void BandCholesky::solve(const double* rhs, double* x) const {
  const std::size_t w = static_cast<std::size_t>(b_) + 1;
  const long b = b_, n = static_cast<long>(n_);
  // L y = rhs (forward), row by row.
  for (long i = 0; i < n; ++i) {
    const double* ri = &a_[static_cast<std::size_t>(i) * w];
    const long j0 = std::max(0L, i - b);
    x[i] = (rhs[i] - dot(ri + (b - (i - j0)), x + j0, i - j0)) * inv_[static_cast<std::size_t>(i)];
  }
  // L^T x = y (backward), column-oriented: after x_i is final, remove it from rows j < i.
  for (long i = n - 1; i >= 0; --i) {
    const double* ri = &a_[static_cast<std::size_t>(i) * w];
    x[i] *= inv_[static_cast<std::size_t>(i)];
    const double xi = x[i];
    const long j0 = std::max(0L, i - b);
    for (long j = j0; j < i; ++j) x[j] -= ri[b - (i - j)] * xi;
  }
}

} // namespace fluidem::gas
