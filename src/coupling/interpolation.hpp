// Gas -> particle interpolation on the staggered grid by area (2-D) / volume (3-D) weighting
// [Hoomans96 eq. 40-41]: bilinear/trilinear between the 4/8 nearest faces of velocity component
// d (face positions x_d = lo + i h_d, cell-centre coordinates across), using the ghost (boundary)
// values the gas solver keeps. The same stencil distributes the particle forces back to the
// faces (exchange.hpp), which is what makes the exchange conserve momentum [Zhu07 §3.2].
// Cell-centre scalars (porosity, density) use the trilinear stencil of the interior cell
// centres, constant (zero gradient) within half a cell of a wall.
// Periodic axes: the gas solver keeps images in the ghost layer (ghost 0 = cell n, ghost n + 1 =
// cell 1; along d the face 0 of component d = face n), so the stencils read the ghosts there as
// ordinary nodes; forces deposited on a ghost or copy node go to its image (periodic_image).
#pragma once
#include "core/vec3.hpp"
#include "gas/gas_grid.hpp"
#include "gas/gas_solver.hpp"
#include <array>
#include <vector>

namespace fluidem::coupling {

/// Up to 8 (index, weight) pairs; weights >= 0, sum 1 (n = 0: no stencil, e.g. v_y in 2-D).
struct Stencil {
  std::array<long, 8> q{};
  std::array<double, 8> w{};
  int n = 0;
};

/// Stencil of velocity component d (faces normal to d) at point x. Points outside the domain
/// are clamped onto it.
Stencil face_stencil(const gas::GasGrid& g, int d, const Vec3& x);
/// Stencil of the cell centres at point x: interior centres along walled axes (clamped, zero
/// gradient at the boundary), ghost centres (periodic images) included along periodic axes.
Stencil cell_stencil(const gas::GasGrid& g, const Vec3& x, const std::array<bool, 3>& periodic);

/// The node a periodic ghost or copy node stands for: grid index q of component d (faces normal
/// to d; -1: cell centres) with every index along a periodic axis wrapped into the unknowns
/// (cells 1..n; along d for faces: 1..n, face 0 being the copy of face n). Other q unchanged.
long periodic_image(const gas::GasGrid& g, const std::array<bool, 3>& periodic, int d, long q);

inline double interpolate(const Stencil& s, const std::vector<double>& a) {
  double v = 0.0;
  for (int m = 0; m < s.n; ++m)
    v += s.w[static_cast<std::size_t>(m)] *
         a[static_cast<std::size_t>(s.q[static_cast<std::size_t>(m)])];
  return v;
}

/// Interstitial gas velocity at x, m/s [Hoomans96 eq. 40-41].
Vec3 gas_velocity_at(const gas::GasSolver& gs, const Vec3& x);
/// Pressure gradient at x, Pa/m: the face gradients (p_+ - p_-)/h_d (ghost pressures at the
/// boundary) interpolated with the stencil of component d.
Vec3 pressure_gradient_at(const gas::GasSolver& gs, const Vec3& x);
/// The face pressure differences p[q + stride_d] - p[q] of each component d (the numerators of
/// the face gradients), for the stencils' faces, into dp[d] (grid-sized; 0 where q + stride_d
/// is beyond the grid, a face no stencil holds).
void face_pressure_differences(const gas::GasSolver& gs, std::array<std::vector<double>, 3>& dp);
/// Which axes of the solver's grid are periodic.
std::array<bool, 3> periodic_axes(const gas::GasSolver& gs);
/// Porosity at x (cell-centre stencil; periodic axes from the solver's boundary map).
double porosity_at(const gas::GasSolver& gs, const Vec3& x);

} // namespace fluidem::coupling
