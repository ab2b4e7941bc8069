// The non-contact forces between particles a case asks for ([van_der_waals], [electrostatics]
// [Zhu07 §2.2, Table 2]): plain data in SI units, read by io/case_reader, used by the noncontact
// module. The charges are the particles' (SpeciesSpec::charge, InsertSpec::charge).
#pragma once
#include <array>
#include <optional>

namespace fluidem {

/// `[van_der_waals]`: the Hamaker attraction (noncontact/kernels/van_der_waals.hpp).
struct VanDerWaalsSpec {
  double hamaker = 0.0;        ///< A between two particles, J, > 0
  double min_separation = 0.0; ///< h0, m, > 0 (0.165-1 nm [Zhu07 §2.2])
  double range = 0.0;          ///< h_c: no force at surface gaps >= range, m, > min_separation
  /// A between a particle and a wall, J; empty: no particle-wall attraction.
  std::optional<double> wall_hamaker;
};

/// `[electrostatics]`: Coulomb forces between the charged particles, shifted force with a cut-off
/// (noncontact/kernels/coulomb.hpp), image charges at conducting walls.
struct ElectrostaticsSpec {
  double cutoff = 0.0;                ///< r_c, centre distance, m, > 0
  double relative_permittivity = 1.0; ///< eps_r of the gas, >= 1
  /// Per face (Face order): a grounded conductor (image charges), or not (no wall force).
  std::array<bool, 6> conducting{};
};

struct NonContactSpec {
  std::optional<VanDerWaalsSpec> van_der_waals;
  std::optional<ElectrostaticsSpec> electrostatics;
  /// Whether any non-contact force is on.
  bool any() const { return van_der_waals.has_value() || electrostatics.has_value(); }
};

} // namespace fluidem
