// Periodic axis [Hoomans96 Table 1]: the ghost layers hold the images of the opposite side
// (gas_solver.cpp, fill_periodic); set by domain.periodic on both faces of the axis, never on a
// region. The ghost rules below are not used on a periodic face.
#pragma once
#include "core/gas_boundary_kind.hpp"

namespace fluidem::gas {

template <>
struct BoundaryKindOf<BoundaryType::periodic> {
  static constexpr BoundaryKind kind{
      .name = "periodic",
      .source = "[Hoomans96 Table 1]",
      .normal = NormalRule::periodic,
      .tangential = 1.0,
      .pressure = GhostRule::copy,
      .porosity = GhostRule::copy,
      .lets_gas_through = true,
      .chosen_in_case = false,
      .on_regions = false,
      .keys = no_keys,
      .check = nullptr,
  };
};

} // namespace fluidem::gas
