#include "coupling/interpolation.hpp"
#include "coupling/trilinear.hpp"
#include <algorithm>
#include <cmath>

namespace fluidem::coupling {

namespace {
void axis(double x, double lo, double h, double shift, int imin, int imax, int& i0, double& t) {
  axis_at((x - lo) / h - shift, imin, imax, i0, t);
}

/// Tensor-product stencil: per active axis the lower node (weight 1 - t) and, unless t = 0, the
/// upper one (weight t); inactive axes keep i0 alone. Nodes x fastest, then y, then z; the
/// weight is the product of the active axes' factors in the order x, y, z.
[[gnu::always_inline]] inline void tensor(const gas::GasGrid& g, const std::array<int, 3>& i0,
                                          const std::array<double, 3>& t,
                                          const std::array<bool, 3>& active, Stencil& s) {
  double f[3][2];
  int nb[3];
  for (int d = 0; d < 3; ++d) {
    const bool two = active[d] && t[d] != 0.0;
    nb[d] = two ? 2 : 1;
    f[d][0] = active[d] ? 1.0 - t[d] : 1.0;
    f[d][1] = t[d];
  }
  const long base = g.idx(i0[0], i0[1], i0[2]);
  const long sy = g.stride[1], sz = g.stride[2];
  // Two nodes along x and z (the common case): the loops below unrolled, 8 nodes (3-D) or 4
  // (one node along y); the same nodes, and the weights the same products in the same order.
  const auto two_by_two = [&]<int NY>() {
    int n = 0;
    for (int bz = 0; bz < 2; ++bz)
      for (int by = 0; by < NY; ++by, n += 2) {
        const long row = base + by * sy + bz * sz;
        s.q[static_cast<std::size_t>(n)] = row;
        s.w[static_cast<std::size_t>(n)] = f[0][0] * f[1][by] * f[2][bz];
        s.q[static_cast<std::size_t>(n + 1)] = row + 1;
        s.w[static_cast<std::size_t>(n + 1)] = f[0][1] * f[1][by] * f[2][bz];
      }
    s.n = n;
  };
  if (nb[0] == 2 && nb[2] == 2) {
    if (nb[1] == 2)
      two_by_two.template operator()<2>();
    else
      two_by_two.template operator()<1>();
    return;
  }
  int n = 0;
  for (int bz = 0; bz < nb[2]; ++bz)
    for (int by = 0; by < nb[1]; ++by)
      for (int bx = 0; bx < nb[0]; ++bx, ++n) {
        s.q[static_cast<std::size_t>(n)] = base + bx + by * sy + bz * sz;
        s.w[static_cast<std::size_t>(n)] = f[0][bx] * f[1][by] * f[2][bz];
      }
  s.n = n;
}
Stencil tensor(const gas::GasGrid& g, const std::array<int, 3>& i0, const std::array<double, 3>& t,
               const std::array<bool, 3>& active) {
  Stencil s;
  tensor(g, i0, t, active, s);
  return s;
}
} // namespace

Stencil face_stencil(const gas::GasGrid& g, int d, const Vec3& x) {
  const bool two_d = g.dimension == 2;
  if (two_d && d == 1) return {};
  std::array<int, 3> i0{1, 1, 1};
  std::array<double, 3> t{0.0, 0.0, 0.0};
  std::array<bool, 3> active{true, true, true};
  for (int e = 0; e < 3; ++e) {
    if (two_d && e == 1) {
      active[e] = false; // one cell across y
      continue;
    }
    if (e == d)
      axis(x[e], g.lo[e], g.h[e], 0.0, 0, g.n[e] - 1, i0[e], t[e]);
    else
      axis(x[e], g.lo[e], g.h[e], -0.5, 0, g.n[e], i0[e], t[e]); // ghost centres included
  }
  return tensor(g, i0, t, active);
}

Stencil cell_stencil(const gas::GasGrid& g, const Vec3& x, const std::array<bool, 3>& periodic) {
  std::array<int, 3> i0{1, 1, 1};
  std::array<double, 3> t{0.0, 0.0, 0.0};
  std::array<bool, 3> active{true, true, true};
  for (int e = 0; e < 3; ++e) {
    if (g.dimension == 2 && e == 1) {
      active[e] = false; // one cell across y
      continue;
    }
    if (periodic[e]) {
      axis(x[e], g.lo[e], g.h[e], -0.5, 0, g.n[e], i0[e], t[e]); // ghost images included
      continue;
    }
    if (g.n[e] < 2) {
      active[e] = false;
      continue;
    }
    axis(x[e], g.lo[e], g.h[e], -0.5, 1, g.n[e] - 1, i0[e], t[e]);
  }
  return tensor(g, i0, t, active);
}

long periodic_image(const gas::GasGrid& g, const std::array<bool, 3>& periodic, int d, long q) {
  if (!periodic[0] && !periodic[1] && !periodic[2]) return q;
  std::array<long, 3> c{q % g.padded[0], (q / g.padded[0]) % g.padded[1],
                        q / (static_cast<long>(g.padded[0]) * g.padded[1])};
  for (int e = 0; e < 3; ++e) {
    if (!periodic[e]) continue;
    const long n = g.n[e];
    if (c[e] == 0)
      c[e] = n; // ghost cell 0 = cell n; along d, face 0 = face n
    else if (c[e] == n + 1 && e != d)
      c[e] = 1;
  }
  return g.idx(static_cast<int>(c[0]), static_cast<int>(c[1]), static_cast<int>(c[2]));
}

Vec3 gas_velocity_at(const gas::GasSolver& gs, const Vec3& x) {
  Vec3 u{0.0, 0.0, 0.0};
  for (int d = 0; d < 3; ++d) u[d] = interpolate(face_stencil(gs.grid(), d, x), gs.velocity(d));
  return u;
}

Vec3 pressure_gradient_at(const gas::GasSolver& gs, const Vec3& x) {
  const gas::GasGrid& g = gs.grid();
  const std::vector<double>& p = gs.pressure();
  Vec3 gp{0.0, 0.0, 0.0};
  for (int d = 0; d < 3; ++d) {
    const Stencil s = face_stencil(g, d, x);
    double v = 0.0;
    for (int m = 0; m < s.n; ++m) {
      const auto q = static_cast<std::size_t>(s.q[static_cast<std::size_t>(m)]);
      v += s.w[static_cast<std::size_t>(m)] * (p[q + static_cast<std::size_t>(g.stride[d])] - p[q]);
    }
    gp[d] = v / g.h[d];
  }
  return gp;
}

void face_pressure_differences(const gas::GasSolver& gs, std::array<std::vector<double>, 3>& dp) {
  const std::vector<double>& p = gs.pressure();
  const std::size_t n = p.size();
  for (int d = 0; d < 3; ++d) {
    std::vector<double>& out = dp[static_cast<std::size_t>(d)];
    out.resize(n);
    const auto sd = static_cast<std::size_t>(gs.grid().stride[d]);
    const std::size_t m = n > sd ? n - sd : 0;
    for (std::size_t q = 0; q < m; ++q) out[q] = p[q + sd] - p[q];
    for (std::size_t q = m; q < n; ++q) out[q] = 0.0;
  }
}

double porosity_at(const gas::GasSolver& gs, const Vec3& x) {
  return interpolate(cell_stencil(gs.grid(), x, periodic_axes(gs)), gs.porosity());
}

std::array<bool, 3> periodic_axes(const gas::GasSolver& gs) {
  return {gs.boundary().periodic(0), gs.boundary().periodic(1), gs.boundary().periodic(2)};
}

} // namespace fluidem::coupling
