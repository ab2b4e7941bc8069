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

  // Scratch: 1-D (index, weight) lists per axis, reused between calls.
  std::array<std::vector<long>, 3> axis_q;
  std::array<std::vector<double>, 3> axis_w;
};

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
