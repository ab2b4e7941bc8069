// Porous-cube mapping between the particles and the gas grid [Deen07 §3.5, eq. 38-39; Link05]:
// particle i is represented by a cube of side a d_i centred on it [Deen07 eq. 34] (the same cube
// as the porous-cube porosity, porosity.hpp). A grid quantity phi is mapped to the particle as
//   phi_i = sum_j w_j phi_j,  w_j = f_j^cube V_j / V_cube = (volume of control volume j inside
//   the cube) / V_cube                                                          [Deen07 eq. 38]
// and a particle quantity (a force) is distributed back to the grid with the same weights
// [Deen07 eq. 39], so that the exchange conserves it: sum_j w_j = 1.
//
// Control volumes of `component`:
//  - cell_component (-1): the interior cells 1..n per axis (scalars: porosity, density,
//    pressure);
//  - d = 0, 1, 2: the velocity faces normal to d (padded index of the HIGH face of cell i, as in
//    gas_grid.hpp). Along d, face i (0..n_d) owns [lo + (i - 1/2) h, lo + (i + 1/2) h]; along
//    the other axes the cell extents.
// Walled (non-periodic) axis: the cube is shifted into the domain, its centre clamped to
// [lo + half, hi - half] exactly as porosity.cpp does; if the domain is narrower than the cube it
// is centred on the domain and clipped to it. The boundary faces 0 and n_d then get only their
// inside halves, and the weights are renormalised to sum to 1 (this matters only for the clipped
// cube: otherwise the normalisation is the cube's side up to round-off).
// Periodic axis (gas solver convention: ghost cell 0 = image of cell n, ghost n + 1 = image of
// cell 1; face 0 = copy of face n_d, faces 1..n_d are the unknowns): the cube is not shifted; the
// overlaps are computed on the unwrapped index range and each index is wrapped into 1..n (cells
// and faces alike), several wraps if the cube is wider than the period; every index appears once.
// 2-D grids (x-z plane, one cell across y): area fractions of the square of side 2 half in x-z;
// component 1 (v_y) has no weights.
#pragma once
#include "core/vec3.hpp"
#include "gas/gas_grid.hpp"
#include <array>
#include <cstddef>
#include <vector>

namespace fluidem::coupling {

/// `component` value selecting the cell-centre control volumes.
inline constexpr int cell_component = -1;

/// A cube's 1-D weights along each axis on both lattices: cell[a] over the cells along axis a,
/// face[a] over the faces normal to a (2-D: the one cell across y, weight 1, on both). The
/// weights of any component are their tensor product (for_cube_weights), so that a particle
/// loop that needs several components computes the six lists once.
struct CubeAxes {
  std::array<std::vector<long>, 3> cell_q, face_q;
  std::array<std::vector<double>, 3> cell_w, face_w;
};
/// Reusable list of (padded grid index, weight) pairs; clear() keeps the capacity. The per-axis
/// scratch lists are kept here too, so that cube_weights does not allocate once warmed up.
struct CubeWeights {
  std::vector<long> q;
  std::vector<double> w;
  void clear() {
    q.clear();
    w.clear();
  }
  std::size_t size() const { return q.size(); }

  CubeAxes axes; ///< scratch: the 1-D lists, reused between calls
};

/// The six lists of the cube (centre c, half side `half`) into out (no allocation once warm).
void cube_axes(const gas::GasGrid& g, const Vec3& c, double half,
               const std::array<bool, 3>& periodic, CubeAxes& out);
/// Only the three lists that the weights of `component` need.
void cube_axes(const gas::GasGrid& g, int component, const Vec3& c, double half,
               const std::array<bool, 3>& periodic, CubeAxes& out);

/// Calls f(q, w) for the weights of `component` (cell_component or a face direction d) from the
/// lists of cube_axes: cube_weights' entries, in its order and with its products (bitwise).
template <class F>
void for_cube_weights(const gas::GasGrid& g, const CubeAxes& a, int component, F&& f) {
  if (g.dimension == 2 && component == 1) return; // no v_y in 2-D
  const auto& qx = component == 0 ? a.face_q[0] : a.cell_q[0];
  const auto& qy = component == 1 ? a.face_q[1] : a.cell_q[1];
  const auto& qz = component == 2 ? a.face_q[2] : a.cell_q[2];
  const auto& wx = component == 0 ? a.face_w[0] : a.cell_w[0];
  const auto& wy = component == 1 ? a.face_w[1] : a.cell_w[1];
  const auto& wz = component == 2 ? a.face_w[2] : a.cell_w[2];
  // Box-box overlap = product of the 1-D overlaps [Deen07 eq. 38].
  for (std::size_t k = 0; k < qz.size(); ++k)
    for (std::size_t j = 0; j < qy.size(); ++j) {
      const long qjk = g.stride[1] * qy[j] + g.stride[2] * qz[k];
      const double wjk = wy[j] * wz[k];
      for (std::size_t i = 0; i < qx.size(); ++i) f(qjk + qx[i], wjk * wx[i]);
    }
}

/// Weights of a porous cube (centre c, half side `half` = a d_i / 2 > 0 [Deen07 eq. 34]) over
/// the control volumes of `component` (cell_component or a face direction d = 0, 1, 2):
/// w_j = (volume of control volume j inside the cube) / V_cube = f_j^cube V_j / V_cube
/// [Deen07 eq. 38]; the weights are > 0, sum to 1 and their indices are distinct. `out` is
/// overwritten.
void cube_weights(const gas::GasGrid& g, int component, const Vec3& c, double half,
                  const std::array<bool, 3>& periodic, CubeWeights& out);

/// phi_p = sum_j w_j a_j [Deen07 eq. 38] (a in the padded layout of the grid).
inline double cube_average(const CubeWeights& w, const std::vector<double>& a) {
  double s = 0.0;
  for (std::size_t m = 0; m < w.q.size(); ++m) s += w.w[m] * a[static_cast<std::size_t>(w.q[m])];
  return s;
}

} // namespace fluidem::coupling
