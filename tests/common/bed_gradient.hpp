// The pressure drop per height of a bed in the gas grid: the tests of fixed and coupled beds
// against Ergun read it over a band of cell layers in the bed's middle.
#pragma once

#include <array>
#include <cstddef>

#include "gas/gas_solver.hpp"

namespace fluidem::test {

/// -dp/dz between the centres of cells k and k+1, averaged over the columns and the layers
/// k0 <= k < k1, and the mean porosity of those cells: {-dp/dz (Pa/m), porosity}.
inline std::array<double, 2> band_pressure_gradient(const gas::GasSolver& gs, int k0, int k1) {
  const gas::GasGrid& g = gs.grid();
  double grad = 0.0, eps = 0.0;
  int m = 0;
  for (int k = k0; k < k1; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i, ++m) {
        const auto q = static_cast<std::size_t>(g.idx(i, j, k));
        const auto up = static_cast<std::size_t>(g.idx(i, j, k + 1));
        grad += (gs.pressure()[up] - gs.pressure()[q]) / g.h[2];
        eps += gs.porosity()[q];
      }
  return {-grad / m, eps / m};
}

} // namespace fluidem::test
