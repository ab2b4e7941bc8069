// Continuous outflow [Hoomans96 Table 1]: zero normal gradient of every quantity (the normal
// face copies the interior face next to it).
#pragma once
#include "core/gas_boundary_kind.hpp"

namespace fluidem::gas {

template <>
struct BoundaryKindOf<BoundaryType::outflow> {
  static constexpr BoundaryKind kind{
      .name = "outflow",
      .source = "[Hoomans96 Table 1]",
      .normal = NormalRule::outflow,
      .tangential = 1.0,
      .pressure = GhostRule::copy,
      .porosity = GhostRule::copy,
      .lets_gas_through = true,
      .chosen_in_case = true,
      .on_regions = true,
      .keys = no_keys,
      .check = nullptr,
  };
};

} // namespace fluidem::gas
