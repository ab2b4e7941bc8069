// Compact trilinear stencils for the particle loops of the coupling (exchange.cpp): the
// bilinear / trilinear weighting of [Hoomans96 eq. 40-41] with the node lattices of
// interpolation.hpp (faces of component d along d, cell centres with the ghosts across; the cell
// centres' own lattice for porosity and density), stored as the grid index of the lower node and
// the upper node's weight t per axis (32 bytes instead of a 136-byte Stencil of nodes).
//
// Its nodes are always the 2 x 2 x 2 around the point (2 x 1 x 2 in 2-D: one cell across y), in
// the order of interpolation.hpp's Stencil (x fastest, then y, then z) with the same weight
// products w = (f_x f_y) f_z (2-D: f_x f_z), f = 1 - t on the lower node and t on the upper one.
// Where a Stencil drops the upper node of an axis (t = 0 exactly; an inactive axis) this one
// keeps it with weight 0: the sums then add exact zeros, and the values are those of the Stencil
// (bitwise, but for the sign of a zero result). An inactive axis of the cell stencil (a walled
// axis of one cell in 3-D) has t = 0; its upper node is the ghost cell, which the solver keeps
// finite.
#pragma once
#include "core/vec3.hpp"
#include "gas/gas_grid.hpp"
#include <algorithm>
#include <array>

namespace fluidem::coupling {

/// Lower index i0 and weight t of the upper node along one axis, s the position in units of the
/// lattice spacing from its node 0, lower node clamped to [imin, imax] (t to [0, 1]). floor by
/// truncation and a correction (std::floor is a library call without SSE4.1): the same integer
/// for every s inside the int range; beyond it clamped anyway; NaN stays NaN in t.
[[gnu::always_inline]] inline void axis_at(double s, int imin, int imax, int& i0, double& t) {
  const double c = std::clamp(s, -1e9, 1e9);
  int i = static_cast<int>(c);
  i -= c < static_cast<double>(i) ? 1 : 0;
  i0 = std::clamp(i, imin, imax);
  t = std::clamp(s - i0, 0.0, 1.0);
}

struct TrilinearStencil {
  long base = 0;             ///< padded grid index of the lower node
  std::array<double, 3> t{}; ///< the upper node's weight per axis (0: inactive axis)
};

/// The face stencils of components 0, 1, 2 (faces[1] unused in 2-D) and the cell-centre stencil
/// at x: the nodes and weights of face_stencil and cell_stencil (interpolation.hpp).
[[gnu::always_inline]] inline void trilinear_stencils(const gas::GasGrid& g, const Vec3& x,
                                                      const std::array<bool, 3>& periodic,
                                                      TrilinearStencil* faces,
                                                      TrilinearStencil& cell) {
  const bool two_d = g.dimension == 2;
  std::array<int, 3> i_face{1, 1, 1}, i_cell{1, 1, 1}, i_mid{1, 1, 1};
  std::array<double, 3> t_face{}, t_cell{}, t_mid{};
  for (int e = 0; e < 3; ++e) {
    if (two_d && e == 1) continue; // one cell across y: node 1, inactive
    const double s = (x[e] - g.lo[e]) / g.h[e];
    axis_at(s, 0, g.n[e] - 1, i_face[e], t_face[e]);   // faces normal to e: 0 .. n
    axis_at(s + 0.5, 0, g.n[e], i_cell[e], t_cell[e]); // cell centres with the ghosts
    if (periodic[e]) {                                 // the ghosts are the images
      i_mid[e] = i_cell[e], t_mid[e] = t_cell[e];
    } else if (g.n[e] >= 2) { // walled: interior centres (zero gradient beyond them)
      axis_at(s + 0.5, 1, g.n[e] - 1, i_mid[e], t_mid[e]);
    } // else: one cell along a walled axis: inactive
  }
  // Element by element: whole arrays assembled on the stack and copied made the copies wait on
  // their partial stores (store-forwarding stalls, a quarter of the particle loop's time).
  cell.base = g.idx(i_mid[0], i_mid[1], i_mid[2]);
  for (int e = 0; e < 3; ++e) cell.t[e] = t_mid[e];
  for (int d = 0; d < 3; ++d) {
    faces[d].base = g.idx(d == 0 ? i_face[0] : i_cell[0], d == 1 ? i_face[1] : i_cell[1],
                          d == 2 ? i_face[2] : i_cell[2]);
    for (int e = 0; e < 3; ++e) faces[d].t[e] = e == d ? t_face[e] : t_cell[e];
  }
}

/// Calls f(offset, weight) for the nodes of s in order (NY = 1: 2-D, NY = 2: 3-D).
template <int NY, class F>
[[gnu::always_inline]] inline void for_trilinear_nodes(const TrilinearStencil& s, long sy, long sz,
                                                       F&& f) {
  const double fx[2] = {1.0 - s.t[0], s.t[0]}, fy[2] = {1.0 - s.t[1], s.t[1]},
               fz[2] = {1.0 - s.t[2], s.t[2]};
  for (int bz = 0; bz < 2; ++bz)
    for (int by = 0; by < NY; ++by)
      for (int bx = 0; bx < 2; ++bx) {
        const double w = NY == 2 ? fx[bx] * fy[by] * fz[bz] : fx[bx] * fz[bz];
        f(s.base + bx + by * sy + bz * sz, w);
      }
}

/// sum_nodes w a[q] in node order.
template <int NY>
[[gnu::always_inline]] inline double trilinear_sum(const TrilinearStencil& s, long sy, long sz,
                                                   const double* a) {
  double v = 0.0;
  for_trilinear_nodes<NY>(s, sy, sz, [&](long q, double w) { v += w * a[q]; });
  return v;
}

/// sum_nodes w a[q] and sum_nodes w b[q] in node order, together.
template <int NY>
[[gnu::always_inline]] inline void trilinear_sums(const TrilinearStencil& s, long sy, long sz,
                                                  const double* a, const double* b, double& va,
                                                  double& vb) {
  va = 0.0;
  vb = 0.0;
  for_trilinear_nodes<NY>(s, sy, sz, [&](long q, double w) {
    va += w * a[q];
    vb += w * b[q];
  });
}

} // namespace fluidem::coupling
