// Banded Cholesky factorisation and solves (band_solver.hpp).
#include "gas/band_solver.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/simd_clones.hpp"

namespace fluidem::gas {

BandCholesky::BandCholesky(std::array<int, 3> extent) {
  n_ = static_cast<std::size_t>(extent[0]) * static_cast<std::size_t>(extent[1]) *
       static_cast<std::size_t>(extent[2]);
  b_ = extent[2] > 1 ? extent[0] * extent[1] : (extent[1] > 1 ? extent[0] : 1);
  if (extent[0] == 1 && extent[1] == 1 && extent[2] == 1) b_ = 0;
  // A row's chunks end at most kAlign - 1 slots before its band (the column alignment) plus
  // b + 1 band slots plus kAlign - 1 past it (the last chunk rounded up).
  const std::size_t b = static_cast<std::size_t>(b_);
  stride_ = (b + 2 * kAlign - 1 + kAlign - 1) / kAlign * kAlign;
  store_.assign(n_ * stride_ + kAlign, 0.0);
  const auto misalign = (reinterpret_cast<std::uintptr_t>(store_.data()) / sizeof(double)) % kAlign;
  offset_ = misalign == 0 ? 0 : kAlign - misalign;
  inv_.assign(n_, 0.0);
}

void BandCholesky::clear() {
  // The band part of each row: the slots around it hold zeros after it (never changed: the
  // updates only subtract u * 0 there) and, before it, values no band slot reads.
  const std::size_t w = static_cast<std::size_t>(b_) + 1;
  for (std::size_t r = 0; r < n_; ++r) std::fill_n(base() + band_start(r), w, 0.0);
}

namespace {
constexpr std::size_t kChunk = BandCholesky::kAlign;
/// r[m] -= u s[m] over `chunks` whole chunks; r and s do not overlap (two different rows).
[[gnu::always_inline]] inline void subtract_scaled(double* __restrict r, const double* __restrict s,
                                                   double u, std::size_t chunks) {
  for (std::size_t c = 0; c < chunks; ++c)
    for (std::size_t m = 0; m < kChunk; ++m) r[c * kChunk + m] -= u * s[c * kChunk + m];
}
} // namespace

// Right-looking band Cholesky on U = L^T stored by rows [Golub & Van Loan, Alg. 4.3.5 in its
// outer-product form]: for k = 0 .. n-1,
//   U(k, k) = sqrt(A(k, k)),  U(k, k+m) = A(k, k+m) / U(k, k)  (m = 1 .. b),
//   A(k+i, k+i+m) -= U(k, k+i) U(k, k+i+m)  (i = 1 .. b, m = 0 .. b-i),
// each update a contiguous axpy of two rows (no reduction chain: it vectorises). The axpy runs
// over whole aligned chunks, from the chunk of column k + i to that of column k + b: before
// column k + i it writes slots no band slot reads (it reads row k's values or the slots before
// its band, which are zeroed first, so that nothing grows there); after column k + b it
// subtracts u * 0 (the zeros after row k's band). Compiled for AVX-512, AVX2 and the baseline
// (core/simd_clones.hpp), without FP contraction: the same bits from every clone.
FLUIDEM_SIMD_CLONES bool BandCholesky::factor() {
  const std::size_t b = static_cast<std::size_t>(b_);
  double* const a = base();
  for (std::size_t k = 0; k < n_; ++k) {
    double* const row = a + k * stride_; // aligned
    const std::size_t pad = k % kChunk;
    double* const rk = row + pad;
    if (!(rk[0] > 0.0)) return false;
    const double d = std::sqrt(rk[0]), inv = 1.0 / d;
    inv_[k] = inv;
    const std::size_t last = std::min(b, n_ - 1 - k); // columns k+1 .. k+last exist
    std::fill_n(row, pad, 0.0);
    const std::size_t scaled = (pad + last + kChunk) / kChunk; // chunks up to column k + last
    for (std::size_t m = 0; m < scaled * kChunk; ++m) row[m] *= inv;
    rk[0] = d;
    for (std::size_t i = 1; i <= last; ++i) {
      const double u = rk[i];
      if (u == 0.0) continue;
      const std::size_t pad_i = (k + i) % kChunk; // row k + i's chunk of column k + i starts
      subtract_scaled(a + (k + i) * stride_, rk + i - pad_i, u,
                      (pad_i + b - i + kChunk) / kChunk); // .. the chunk of column k + b
    }
  }
  return true;
}

void BandCholesky::solve(const double* rhs, double* x) const {
  const std::size_t b = static_cast<std::size_t>(b_);
  if (x != rhs) std::copy(rhs, rhs + n_, x);
  // U^T y = rhs (forward), column-oriented: once y_k is final, remove it from rows k+1 .. k+b.
  for (std::size_t k = 0; k < n_; ++k) {
    const double* rk = base() + band_start(k);
    x[k] *= inv_[k];
    const double yk = x[k];
    const std::size_t last = std::min(b, n_ - 1 - k);
    for (std::size_t m = 1; m <= last; ++m) x[k + m] -= rk[m] * yk;
  }
  // U x = y (backward): x_k = (y_k - sum_m U(k, k+m) x_{k+m}) / U(k, k).
  for (std::size_t k = n_; k-- > 0;) {
    const double* rk = base() + band_start(k);
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
