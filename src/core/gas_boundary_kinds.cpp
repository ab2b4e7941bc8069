// The table of boundary type declarations, one per enumerator of BoundaryType.
#include <array>
#include <cmath>
#include <utility>

#include "core/error.hpp"
#include "core/gas_boundary_kind.hpp"

#include "core/gas_boundary/inflow.hpp"
#include "core/gas_boundary/outflow.hpp"
#include "core/gas_boundary/periodic.hpp"
#include "core/gas_boundary/pressure.hpp"
#include "core/gas_boundary/wall_free_slip.hpp"
#include "core/gas_boundary/wall_no_slip.hpp"

namespace fluidem::gas {

namespace {
template <std::size_t... I>
constexpr std::array<const BoundaryKind*, sizeof...(I)> make_table(std::index_sequence<I...>) {
  return {&BoundaryKindOf<static_cast<BoundaryType>(I)>::kind...};
}
constexpr auto kinds = make_table(std::make_index_sequence<boundary_type_count>{});
} // namespace

const BoundaryKind& boundary_kind(BoundaryType t) {
  return *kinds[static_cast<std::size_t>(t)];
}

void check_boundary_pressure(double p, const std::string& key) {
  if (!(p > 0.0) || !std::isfinite(p)) throw InputError(key + ": must be > 0 Pa");
}

} // namespace fluidem::gas
