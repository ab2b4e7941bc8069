// Staggered Cartesian grid of the gas phase [Hoomans96 §3.3, Fig. 6]: scalars (porosity,
// pressure, density) at cell centres, velocity component d on the faces normal to axis d,
// one layer of ghost (boundary) cells around the domain.
//
// Layout (every cell and face array has the same padded size): cell (i, j, k) with
// i = 0..nx+1 (0 and nx+1 are ghost cells, 1..nx interior) is stored at
// idx(i, j, k) = i + (nx + 2) * (j + (ny + 2) * k). The face value of component d stored at
// idx(i, j, k) belongs to the HIGH face of cell (i, j, k) along d: u at x = lo.x + i dx, with
// the cell-centre coordinates along the other axes. The domain faces along d are the face
// indices 0 (low boundary) and n_d (high boundary); faces 1..n_d-1 are interior.
// A 2-D grid is the x-z plane: ny = 1, dy = depth, no flow along y (v = 0).
#pragma once
#include "core/vec3.hpp"
#include <array>
#include <cstddef>
#include <vector>

namespace fluidem::gas {

struct GasGrid {
  std::array<int, 3> n{1, 1, 1};           ///< interior cells per axis
  std::array<int, 3> padded{3, 3, 3};      ///< n + 2
  std::array<double, 3> h{1.0, 1.0, 1.0};  ///< cell sizes, m
  std::array<double, 3> lo{0.0, 0.0, 0.0}; ///< lower domain corner, m
  std::array<long, 3> stride{1, 3, 9};     ///< index offsets of the neighbours along x, y, z
  int dimension = 3;

  GasGrid() = default;
  GasGrid(int dim, std::array<int, 3> cells, std::array<double, 3> lower,
          std::array<double, 3> upper)
      : n(cells), lo(lower), dimension(dim) {
    for (int d = 0; d < 3; ++d) {
      padded[d] = n[d] + 2;
      h[d] = (upper[d] - lower[d]) / n[d];
    }
    stride = {1, padded[0], static_cast<long>(padded[0]) * padded[1]};
  }

  std::size_t size() const { return static_cast<std::size_t>(padded[0]) * padded[1] * padded[2]; }
  long idx(int i, int j, int k) const { return i + stride[1] * j + stride[2] * k; }
  double cell_volume() const { return h[0] * h[1] * h[2]; }
  /// Area of a face normal to axis d, m^2.
  double face_area(int d) const { return cell_volume() / h[d]; }
  Vec3 cell_centre(int i, int j, int k) const {
    return {lo[0] + (i - 0.5) * h[0], lo[1] + (j - 0.5) * h[1], lo[2] + (k - 0.5) * h[2]};
  }
  /// Centre of the high face along d of cell (i, j, k).
  Vec3 face_centre(int d, int i, int j, int k) const {
    Vec3 c = cell_centre(i, j, k);
    c[d] += 0.5 * h[d];
    return c;
  }
  /// Interior cell containing a point (clamped to the domain), 1-based indices.
  std::array<int, 3> cell_of(const Vec3& x) const {
    std::array<int, 3> c{};
    for (int d = 0; d < 3; ++d) {
      int i = static_cast<int>((x[d] - lo[d]) / h[d]) + 1;
      c[d] = i < 1 ? 1 : (i > n[d] ? n[d] : i);
    }
    return c;
  }
};

/// Periodic axes: the ghost layer holds the images (ghost 0 = cell n, ghost n + 1 = cell 1,
/// along every axis of the padded array; for a face array along its own axis, face 0 = face n).
void fill_periodic_ghosts(const GasGrid& g, const std::array<bool, 3>& periodic,
                          std::vector<double>& a);

} // namespace fluidem::gas
