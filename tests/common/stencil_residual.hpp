// ||b - A x||_2 / ||b||_2 of a 7-point system (gas/pressure_solver.hpp's StencilSystem) on the box
// lo..hi of a padded array, computed independently of the solvers: each neighbour read
// explicitly, wrapped across a periodic axis, and 0 outside the padded array (a box starting at
// index 0, whose coefficient there is 0).
#pragma once
#include <array>
#include <cmath>
#include <vector>

#include "gas/pressure_solver.hpp"

namespace fluidem::test {

inline double stencil_relative_residual(std::array<int, 3> padded, std::array<int, 3> lo,
                                        std::array<int, 3> hi, std::array<bool, 3> periodic,
                                        const gas::StencilSystem& s, const std::vector<double>& x) {
  const auto idx = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i + static_cast<long>(padded[0]) *
                                            (j + static_cast<long>(padded[1]) * k));
  };
  const auto at = [&](int i, int j, int k) {
    int c[3] = {i, j, k};
    for (int a = 0; a < 3; ++a) {
      const int period = hi[a] - lo[a] + 1;
      if (periodic[a] && c[a] < lo[a]) c[a] += period;
      if (periodic[a] && c[a] > hi[a]) c[a] -= period;
      if (c[a] < 0 || c[a] >= padded[a]) return 0.0;
    }
    return x[idx(c[0], c[1], c[2])];
  };
  double rr = 0.0, bb = 0.0;
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const std::size_t q = idx(i, j, k);
        const double r = s.rhs[q] - s.diag[q] * x[q] - s.xm[q] * at(i - 1, j, k) -
                         s.xp[q] * at(i + 1, j, k) - s.ym[q] * at(i, j - 1, k) -
                         s.yp[q] * at(i, j + 1, k) - s.zm[q] * at(i, j, k - 1) -
                         s.zp[q] * at(i, j, k + 1);
        rr += r * r;
        bb += s.rhs[q] * s.rhs[q];
      }
  return std::sqrt(rr / bb);
}

} // namespace fluidem::test
