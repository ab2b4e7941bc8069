// Prescribed pressure [Hoomans96 Table 1]: p_b on the boundary face (ghost 2 p_b - p_interior),
// the normal velocity solved, zero normal gradient of the tangential velocity and the porosity.
#pragma once
#include "core/gas_boundary_kind.hpp"

namespace fluidem::gas {

template <>
struct BoundaryKindOf<BoundaryType::pressure> {
  static constexpr BoundaryKind kind{
      .name = "pressure",
      .source = "[Hoomans96 Table 1]",
      .normal = NormalRule::pressure,
      .tangential = 1.0,
      .pressure = GhostRule::prescribed,
      .porosity = GhostRule::copy,
      .lets_gas_through = true,
      .chosen_in_case = true,
      .on_regions = true,
      .keys = pressure_key,
      .check =
          [](const BoundaryValues& v, const std::string& key) {
            check_boundary_pressure(v.pressure, key + ".pressure");
          },
  };
};

} // namespace fluidem::gas
