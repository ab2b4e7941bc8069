// What a gas boundary type does, declared once per type [Hoomans96 Table 1, §3.5]: its
// case-file name, the case keys it takes (and so the checks that apply), the rule of its ghost
// cell for the normal and the tangential velocity, the pressure and the porosity, and whether
// gas crosses it. One file per type in core/gas_boundary/ specialises BoundaryKindOf; the case
// reader (names, keys), the settings check (core), the writer and the gas solver (the rules)
// all read it here. The rules are data: the gas module (gas_solver.cpp) implements each kind of
// rule once and applies it per face or per region, not per type.
//
// Adding a boundary type: its enumerator below (the one list; its place is its place in
// messages), its file core/gas_boundary/<name>.hpp, its #include in gas_boundary_kinds.cpp, its
// test and its row in docs/gas.md. A type whose rule is none of the kinds below also needs that
// rule in gas_solver.cpp.
#pragma once
#include <cstddef>
#include <string>

namespace fluidem::gas {

/// Boundary cell types of [Hoomans96 Table 1], assigned per domain face or per region of a face.
enum class BoundaryType : unsigned char {
  wall_free_slip, ///< impermeable wall, zero tangential stress
  wall_no_slip,   ///< impermeable wall, zero tangential velocity
  inflow,         ///< prescribed (superficial) inflow velocity, tangential velocity zero
  pressure,       ///< prescribed pressure on the boundary face, normal velocity free
  outflow,        ///< continuous outflow: zero normal gradient of all quantities
  periodic,       ///< periodic axis (both faces of the axis must say so)
  count           ///< not a type: the number of types
};
inline constexpr std::size_t boundary_type_count = static_cast<std::size_t>(BoundaryType::count);

/// The velocity normal to a boundary face.
enum class NormalRule : unsigned char {
  wall,     ///< zero, not solved
  inflow,   ///< the inflow's superficial velocity / the ghost porosity, into the domain
  pressure, ///< solved (the face's pressure is the prescribed one)
  outflow,  ///< copies the interior face next to it (zero normal gradient)
  periodic  ///< no boundary face: the axis wraps
};

/// A scalar (pressure, porosity) in the ghost cell.
enum class GhostRule : unsigned char {
  copy,      ///< the interior cell's value (zero normal gradient)
  prescribed ///< porosity: the `.porosity` key; pressure: 2 p_b - p_interior, p_b = `.pressure`
};

/// The case keys of a type, besides `type` (bits).
enum BoundaryKeys : unsigned {
  no_keys = 0,
  inflow_keys = 1,  ///< `.mode`, `.velocity` and the keys of the mode (InflowProfile)
  porosity_key = 2, ///< `.porosity`: the ghost cell's porosity
  pressure_key = 4  ///< `.pressure`, Pa, on the boundary face
};

/// The values of one face or region that a type's check reads.
struct InflowProfile;
struct BoundaryValues {
  const InflowProfile& inflow;
  double porosity;
  double pressure;
};

struct BoundaryKind {
  const char* name;      ///< the case-file value of `.type`
  const char* source;    ///< where the rules are from
  NormalRule normal;     ///< the normal velocity on the face
  double tangential;     ///< tangential ghost velocity = tangential * interior (-1: zero on
                         ///< the face, no slip; +1: zero normal gradient, free slip)
  GhostRule pressure;    ///< the ghost pressure
  GhostRule porosity;    ///< the ghost porosity
  bool lets_gas_through; ///< gas crosses the face
  bool chosen_in_case;   ///< a face's or region's `.type` may name it (periodic: no, it
                         ///< follows domain.periodic)
  bool on_regions;       ///< a region of a face may have it
  unsigned keys;         ///< BoundaryKeys
  /// The type's own check of its values (InputError naming `key` + ".<key>"); nullptr: none.
  /// The inflow profile and the porosity are checked on every face (every face holds them).
  void (*check)(const BoundaryValues& v, const std::string& key);
};

/// Specialised once per type, in core/gas_boundary/<name>.hpp: `static constexpr BoundaryKind
/// kind`.
template <BoundaryType T>
struct BoundaryKindOf;

/// The declaration of type t (t < count).
const BoundaryKind& boundary_kind(BoundaryType t);

/// The checks of the keys, shared by the types' checks: InputError naming `key`.
void check_boundary_pressure(double p, const std::string& key); ///< > 0 Pa, finite

} // namespace fluidem::gas
