// Interpolation [Hoomans96 eq. 40-41]: a linear velocity field (set on every stored face,
// ghosts included) and a linear pressure field are reproduced exactly at random points
// (1e-12 relative), 3-D and 2-D. Porosity (cell-centre stencil) of a linear field inside the
// interior cell centres: exact (1e-12).
#include "coupling/interpolation.hpp"
#include "coupling/trilinear.hpp"
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <random>

using namespace fluidem;
using namespace fluidem::coupling;

namespace {
double lin(int d, const Vec3& x) {
  return 0.3 + 1.7 * d + (2.0 + d) * x[0] - 3.0 * x[1] + (0.5 - d) * x[2];
}

void run(int dim) {
  gas::GasSettings s;
  s.dimension = dim;
  s.cells = {5, dim == 2 ? 1 : 4, 6};
  s.hi = {0.05, 0.04, 0.06};
  s.eos = gas::EquationOfState::incompressible;
  gas::GasSolver gs(s);
  const gas::GasGrid& g = gs.grid();
  for (int k = 0; k < g.padded[2]; ++k)
    for (int j = 0; j < g.padded[1]; ++j)
      for (int i = 0; i < g.padded[0]; ++i) {
        const auto q = static_cast<std::size_t>(g.idx(i, j, k));
        for (int d = 0; d < 3; ++d) gs.velocity(d)[q] = lin(d, g.face_centre(d, i, j, k));
        const Vec3 c = g.cell_centre(i, j, k);
        gs.pressure()[q] = 1e5 + 10.0 * c[0] - 20.0 * c[1] + 30.0 * c[2];
        gs.porosity()[q] = 0.5 + c[0] + (dim == 3 ? c[1] : 0.0) + c[2];
      }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> ux(0, 0.05), uy(0, 0.04), uz(0, 0.06);
  double err = 0.0, errp = 0.0, erre = 0.0;
  for (int n = 0; n < 1000; ++n) {
    const Vec3 x{ux(rng), dim == 2 ? 0.5 * g.h[1] : uy(rng), uz(rng)};
    const Vec3 u = gas_velocity_at(gs, x);
    for (int d = 0; d < 3; ++d) {
      if (dim == 2 && d == 1) continue;
      err = std::max(err, std::abs(u[d] - lin(d, x)) / std::abs(lin(d, x)));
    }
    const Vec3 gp = pressure_gradient_at(gs, x);
    errp = std::max({errp, std::abs(gp[0] / 10.0 - 1.0), std::abs(gp[2] / 30.0 - 1.0)});
    if (dim == 3) errp = std::max(errp, std::abs(gp[1] / -20.0 - 1.0));
    Vec3 xi = x; // inside the interior cell centres
    for (int d = 0; d < 3; ++d)
      if (g.n[d] > 1)
        xi[d] = std::clamp(xi[d], g.lo[d] + 0.5 * g.h[d], g.lo[d] + (g.n[d] - 0.5) * g.h[d]);
    const double e = 0.5 + xi[0] + (dim == 3 ? xi[1] : 0.0) + xi[2];
    erre = std::max(erre, std::abs(porosity_at(gs, xi) / e - 1.0));
  }
  std::printf("%d-D: max rel. errors velocity %.2e, pressure gradient %.2e, porosity %.2e\n", dim,
              err, errp, erre);
  EXPECT_LT(err, 1e-12);
  EXPECT_LT(errp, 1e-9); // differences of pressures ~1e5 Pa: round-off 1e5 * 1e-16 / 1e-2
  EXPECT_LT(erre, 1e-12);
}
} // namespace

TEST(Interpolation, LinearFieldExact3D) {
  run(3);
}
TEST(Interpolation, LinearFieldExact2D) {
  run(2);
}

// The compact stencils of the coupling's particle loops (trilinear.hpp) are the Stencils of
// face_stencil (each component) and cell_stencil: the same nodes in the same order with bitwise
// the same weights, plus nodes of weight exactly 0 where a Stencil drops the upper node (t = 0,
// an inactive axis); and the sums over them are the Stencils' interpolations (==). For points
// inside the domain, on cell faces and centre planes and outside it (clamped), on 2-D and 3-D
// grids (one cell across y as in the Tsuji beds, and several), walled and periodic axes.
TEST(Interpolation, TrilinearStencilsAreTheSeparateOnes) {
  long checked = 0;
  for (int dim : {2, 3})
    for (int ny : {1, 4})
      for (int per = 0; per < 8; ++per) {
        if (dim == 2 && ny != 1) continue;
        gas::GasSettings s;
        s.dimension = dim;
        s.cells = {5, ny, 6};
        s.hi = {0.05, 0.04, 0.06};
        s.eos = gas::EquationOfState::incompressible;
        gas::GasSolver gs(s);
        const gas::GasGrid& g = gs.grid();
        const std::array<bool, 3> periodic{(per & 1) != 0, (per & 2) != 0 && dim == 3,
                                           (per & 4) != 0};
        std::mt19937_64 rng(11 + per);
        std::uniform_real_distribution<double> u(-0.1, 1.1); // 10% outside on each side
        std::vector<double> field(g.size());
        for (double& v : field) v = u(rng);
        for (int n = 0; n < 400; ++n) {
          Vec3 x{u(rng) * 0.05, u(rng) * 0.04, u(rng) * 0.06};
          if (n % 4 == 0) x[0] = 0.01 * (n % 6);         // on a face normal to x
          if (n % 5 == 0) x[2] = 0.005 + 0.01 * (n % 7); // on a cell centre plane
          TrilinearStencil faces[3], cell;
          trilinear_stencils(g, x, periodic, faces, cell);
          const auto same = [&](const TrilinearStencil& t, const Stencil& ref) {
            std::vector<std::pair<long, double>> nodes;
            const auto add = [&](long q, double w) { nodes.emplace_back(q, w); };
            if (dim == 2)
              for_trilinear_nodes<1>(t, g.stride[1], g.stride[2], add);
            else
              for_trilinear_nodes<2>(t, g.stride[1], g.stride[2], add);
            int m = 0;
            for (const auto& [q, w] : nodes) {
              const auto k = static_cast<std::size_t>(m);
              if (m < ref.n && q == ref.q[k] && std::memcmp(&w, &ref.w[k], sizeof(double)) == 0)
                ++m;
              else
                ASSERT_EQ(w, 0.0) << "node " << q << " not in the Stencil";
            }
            ASSERT_EQ(m, ref.n);
            const double v = dim == 2 ? trilinear_sum<1>(t, g.stride[1], g.stride[2], field.data())
                                      : trilinear_sum<2>(t, g.stride[1], g.stride[2], field.data());
            ASSERT_EQ(v, interpolate(ref, field));
          };
          for (int d = 0; d < 3; ++d) {
            const Stencil ref = face_stencil(g, d, x);
            if (ref.n == 0) continue; // v_y in 2-D: no stencil
            same(faces[d], ref);
          }
          same(cell, cell_stencil(g, x, periodic));
          ++checked;
        }
      }
  EXPECT_EQ(checked, 400 * 8 * 3);
}
