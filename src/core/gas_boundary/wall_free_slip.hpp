// Free-slip wall [Hoomans96 Table 1]: impermeable, zero tangential stress; the scalars have zero
// normal gradient.
#pragma once
#include "core/gas_boundary_kind.hpp"

namespace fluidem::gas {

template <>
struct BoundaryKindOf<BoundaryType::wall_free_slip> {
  static constexpr BoundaryKind kind{
      .name = "wall_free_slip",
      .source = "[Hoomans96 Table 1]",
      .normal = NormalRule::wall,
      .tangential = 1.0, // zero normal gradient
      .pressure = GhostRule::copy,
      .porosity = GhostRule::copy,
      .lets_gas_through = false,
      .chosen_in_case = true,
      .on_regions = true,
      .keys = no_keys,
      .check = nullptr,
  };
};

} // namespace fluidem::gas
