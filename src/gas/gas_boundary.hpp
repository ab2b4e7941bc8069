// Boundary cells of the gas grid [Hoomans96 Table 1, §3.5], assigned by geometry: every ghost
// cell on a domain face gets the type of the face, or of the last region of that face whose
// rectangle contains the ghost cell's face centre. Corner ghost cells take no part.
#pragma once
#include "core/gas_settings.hpp"
#include "gas/gas_grid.hpp"
#include <array>
#include <cstddef>
#include <vector>

namespace fluidem::gas {

/// What one boundary (ghost) cell is: its type's values, and its type's rules
/// (core/gas_boundary/<type>.hpp) copied here, so that the per-cell loops read them from the
/// patch and never ask for the type.
struct BoundaryPatch {
  BoundaryType type = BoundaryType::wall_no_slip;
  InflowProfile inflow;                 ///< inflow only: superficial velocity into the domain, m/s
  double porosity = 0.4;                ///< a prescribed ghost porosity (inflow)
  double pressure = 101325.0;           ///< a prescribed pressure on the boundary face, Pa
  NormalRule normal = NormalRule::wall; ///< BoundaryKind::normal
  GhostRule pressure_rule = GhostRule::copy; ///< BoundaryKind::pressure
  GhostRule porosity_rule = GhostRule::copy; ///< BoundaryKind::porosity
  double tangential = -1.0;                  ///< BoundaryKind::tangential
  /// The patch of a face or region of type `t` with these values.
  static BoundaryPatch of(BoundaryType t, const InflowProfile& inflow, double porosity,
                          double pressure);
};

class BoundaryMap {
public:
  BoundaryMap() = default;
  BoundaryMap(const GasSettings& s, const GasGrid& g);

  /// Patch of the ghost cell next to interior cell (i, j, k) across side `side`
  /// (0 left, 1 right, 2 front, 3 back, 4 bottom, 5 top); the tangential indices of (i, j, k)
  /// are used, the normal one is ignored.
  const BoundaryPatch& at(int side, int i, int j, int k) const {
    return patches_[index_[side][slot(side, i, j, k)]];
  }
  /// at(side, i, j, k).tangential, from a table (the momentum assembly's hot path).
  double tangential_factor_at(int side, int i, int j, int k) const {
    return tangential_[side][slot(side, i, j, k)];
  }
  bool periodic(int axis) const { return periodic_[axis]; }
  /// True if any boundary cell has a prescribed pressure.
  bool any_pressure() const { return any_pressure_; }
  /// True if any boundary face copies its normal velocity from the interior (outflow).
  bool any_outflow() const { return any_outflow_; }

private:
  /// Index of the ghost cell next to (i, j, k) across `side` in the side's tables: its two
  /// tangential indices (axes a1 < a2 other than the side's axis), a1 fastest.
  std::size_t slot(int side, int i, int j, int k) const {
    const int axis = side / 2;
    const int t1 = axis == 0 ? j : i, t2 = axis == 2 ? j : k;
    return static_cast<std::size_t>(t1 + grid_.padded[axis == 0 ? 1 : 0] * t2);
  }
  GasGrid grid_;
  std::array<std::vector<double>, 6> tangential_;
  std::vector<BoundaryPatch> patches_;
  std::array<std::vector<int>, 6> index_;
  std::array<bool, 3> periodic_{false, false, false};
  bool any_pressure_ = false;
  bool any_outflow_ = false;
};

} // namespace fluidem::gas
