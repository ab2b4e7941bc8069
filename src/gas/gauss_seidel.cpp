// Red-black Gauss-Seidel on a structured box (gauss_seidel.hpp).
#include "gas/gauss_seidel.hpp"
#include <algorithm>
#include <cmath>

namespace fluidem::gas {

RedBlackGaussSeidel::RedBlackGaussSeidel(std::array<int, 3> padded, std::array<int, 3> lo,
                                         std::array<int, 3> hi, std::array<bool, 3> periodic,
                                         bool threaded)
    : padded_(padded), lo_(lo), hi_(hi), periodic_(periodic), parallel_(threaded) {
  sy_ = padded[0];
  sz_ = static_cast<long>(padded[0]) * padded[1];
  rows_ = (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
  row_sum_.assign(static_cast<std::size_t>(rows_), 0.0);
  zeros_.assign(static_cast<std::size_t>(padded[0]), 0.0);
}

// Periodic images: ghost layer lo-1 holds x[hi], hi+1 holds x[lo] (whole padded planes, so
// edges of two periodic axes come out right after both passes).
void RedBlackGaussSeidel::refresh_periodic(std::vector<double>& x) const {
  const std::array<long, 3> stride{1, sy_, sz_};
  for (int d = 0; d < 3; ++d) {
    if (!periodic_[d]) continue;
    const int a = d == 0 ? 1 : 0, b = d == 2 ? 1 : 2; // the other two axes
    const long sd = stride[d], period = hi_[d] - lo_[d] + 1;
    for (int q = 0; q < padded_[b]; ++q)
      for (int p = 0; p < padded_[a]; ++p) {
        const long base = p * stride[a] + q * stride[b];
        x[base + (lo_[d] - 1) * sd] = x[base + (lo_[d] - 1 + period) * sd];
        x[base + (hi_[d] + 1) * sd] = x[base + (hi_[d] + 1 - period) * sd];
      }
  }
}

double RedBlackGaussSeidel::half_sweep(const StencilSystem& s, std::vector<double>& xv,
                                       int colour) {
  if (periodic_[0] || periodic_[1] || periodic_[2]) refresh_periodic(xv);
  const int ny = hi_[1] - lo_[1] + 1, i_lo = lo_[0], i_hi = hi_[0];
  const long sy = sy_, sz = sz_;
  const double *diag = s.diag.data(), *xm = s.xm.data(), *xp = s.xp.data(), *ym = s.ym.data(),
               *yp = s.yp.data(), *zm = s.zm.data(), *zp = s.zp.data(), *rhs = s.rhs.data();
  double* x = xv.data();
  double* row_sum = row_sum_.data();
  const double* zeros = zeros_.data();
  // One row; the unthreaded path calls it without entering an OpenMP region at all (a region
  // with if(false) still costs a runtime call per half-sweep, which shows on small grids).
  const auto row = [&](int r) {
    const int j = lo_[1] + r % ny, k = lo_[2] + r / ny;
    const long base = j * sy + k * sz;
    // A box starting at index 0 (the low boundary faces of a velocity component) has no row
    // below it along y or z: read zeros there (the coefficients are 0 anyway).
    const double* x_ym = j > 0 ? x + base - sy : zeros;
    const double* x_zm = k > 0 ? x + base - sz : zeros;
    const double *x_yp = x + base + sy, *x_zp = x + base + sz;
    double* xr = x + base;
    double sum = 0.0;
    for (int i = i_lo + ((i_lo + j + k + colour) & 1); i <= i_hi; i += 2) {
      const long p = base + i;
      const double xl = i > 0 ? xr[i - 1] : 0.0;
      const double res = rhs[p] - diag[p] * xr[i] - xm[p] * xl - xp[p] * xr[i + 1] -
                         ym[p] * x_ym[i] - yp[p] * x_yp[i] - zm[p] * x_zm[i] - zp[p] * x_zp[i];
      xr[i] += res / diag[p];
      sum += res * res;
    }
    row_sum[r] = sum;
  };
  if (parallel_) {
#pragma omp parallel for schedule(static)
    for (int r = 0; r < rows_; ++r) row(r);
  } else {
    for (int r = 0; r < rows_; ++r) row(r);
  }
  double total = 0.0;
  for (int r = 0; r < rows_; ++r) total += row_sum[r]; // fixed order: thread-independent
  return total;
}

LinearSolveStats RedBlackGaussSeidel::solve(const StencilSystem& s, std::vector<double>& x,
                                            double rel_tol, int max_sweeps) {
  const int ny = hi_[1] - lo_[1] + 1;
  const double* rhs = s.rhs.data();
  const auto rhs_row = [&](int r) {
    const long base = (lo_[1] + r % ny) * sy_ + (lo_[2] + r / ny) * sz_;
    double sum = 0.0;
    for (int i = lo_[0]; i <= hi_[0]; ++i) sum += rhs[base + i] * rhs[base + i];
    row_sum_[r] = sum;
  };
  if (parallel_) {
#pragma omp parallel for schedule(static)
    for (int r = 0; r < rows_; ++r) rhs_row(r);
  } else {
    for (int r = 0; r < rows_; ++r) rhs_row(r);
  }
  double bb = 0.0;
  for (int r = 0; r < rows_; ++r) bb += row_sum_[r];
  LinearSolveStats st;
  if (bb == 0.0) { // the solution is 0 (as hypre's Krylov solvers answer b = 0)
    for (int r = 0; r < rows_; ++r) {
      const long base = (lo_[1] + r % ny) * sy_ + (lo_[2] + r / ny) * sz_;
      for (int i = lo_[0]; i <= hi_[0]; ++i) x[base + i] = 0.0;
    }
    if (periodic_[0] || periodic_[1] || periodic_[2]) refresh_periodic(x);
    st.converged = true;
    return st;
  }
  const double target = rel_tol * rel_tol * bb;
  half_sweep(s, x, 0);
  half_sweep(s, x, 1);
  int sweeps = 1;
  double previous = -1.0;
  for (;;) {
    // Black residuals are 0 now: this red half-sweep sees the whole residual of sweep `sweeps`.
    const double rr = half_sweep(s, x, 0);
    st.iterations = sweeps;
    st.relative_residual = std::sqrt(rr / bb);
    if (rr <= target) {
      st.converged = true;
      break;
    }
    if (!std::isfinite(rr) || sweeps >= max_sweeps) break;
    if (previous > 0.0 && sweeps >= 3) {
      const double rate = std::sqrt(rr / previous); // contraction per sweep
      if (rate >= 1.0) break;
      const double more = std::log(std::sqrt(target / rr)) / std::log(rate);
      if (sweeps + more > max_sweeps) break; // hopeless within the budget: let the caller switch
    }
    previous = rr;
    half_sweep(s, x, 1);
    ++sweeps;
  }
  if (periodic_[0] || periodic_[1] || periodic_[2]) refresh_periodic(x);
  return st;
}

} // namespace fluidem::gas
