// Inflow [Hoomans96 Table 1, §3.5]: a prescribed superficial velocity into the domain (the face
// velocity is it over the ghost porosity, the distributor's), zero tangential velocity on the
// face; the ghost pressure is set from the face pressure each flow step (gas_solver.hpp,
// inflow_face_pressure), the copy below is its starting value.
#pragma once
#include "core/gas_boundary_kind.hpp"

namespace fluidem::gas {

template <>
struct BoundaryKindOf<BoundaryType::inflow> {
  static constexpr BoundaryKind kind{
      .name = "inflow",
      .source = "[Hoomans96 Table 1, §3.5; Deen07 §6.1]",
      .normal = NormalRule::inflow,
      .tangential = -1.0, // zero on the face
      .pressure = GhostRule::copy,
      .porosity = GhostRule::prescribed, // `.porosity`, the distributor's
      .lets_gas_through = true,
      .chosen_in_case = true,
      .on_regions = true,
      .keys = inflow_keys | porosity_key,
      .check = nullptr, // the profile and the porosity: checked on every face
  };
};

} // namespace fluidem::gas
