// The non-contact forces between particles a case asks for ([van_der_waals], [electrostatics],
// [liquid_bridge] [Zhu07 §2.2, Table 2]): plain data in SI units, read by io/case_reader, used by
// the noncontact module. The charges and the liquid are the particles' (SpeciesSpec::charge,
// InsertSpec::charge, SpeciesSpec::liquid_fraction).
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

/// `[liquid_bridge]`: pendular bridges between wet particles and with the walls
/// (noncontact/kernels/liquid_bridge.hpp); each particle's liquid is its species'
/// liquid_fraction of its volume (SpeciesSpec::liquid_fraction).
struct LiquidBridgeSpec {
  double surface_tension = 0.0; ///< gamma, N/m, > 0
  /// theta as the case gives it, degrees, in [0, 50) (Willett's fit); kept in degrees so that
  /// the resolved case reads back to the same bits.
  double contact_angle_degrees = 0.0;
  /// theta, rad.
  double contact_angle() const { return contact_angle_degrees * (3.14159265358979323846 / 180.0); }
  double viscosity = 0.0; ///< mu_l of the liquid, Pa s, >= 0 (0: no viscous force)
  double min_gap = 0.0;   ///< S_min of the viscous force, m, > 0
  bool walls = true;      ///< bridges between particles and walls (the wall brings no liquid)
};

struct NonContactSpec {
  std::optional<VanDerWaalsSpec> van_der_waals;
  std::optional<ElectrostaticsSpec> electrostatics;
  std::optional<LiquidBridgeSpec> liquid_bridge;
  /// Whether a conservative non-contact force is on (van der Waals, electrostatics).
  bool any_conservative() const { return van_der_waals.has_value() || electrostatics.has_value(); }
  /// Whether any non-contact force is on.
  bool any() const { return any_conservative() || liquid_bridge.has_value(); }
};

} // namespace fluidem
