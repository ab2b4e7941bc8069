// Settings of the particle-gas coupling: plain data, one field per case-file key
// (`coupling.<field>`). The models themselves live in src/coupling/ (drag closures in
// src/coupling/drag/, one file each, with their registry): the case holds the drag closure's
// name as a string, which the coupling module checks against its registry at set-up (with the
// key's source location), so that core knows no drag law.
#pragma once
#include <string>
#include <string_view>

namespace fluidem::coupling {

/// Porosity from the particles [Deen07 §3.5] (`coupling.porosity`).
enum class PorosityMethod {
  cell,       ///< exact sphere (disc) volume (area) per cell [Deen07 eq. 33]
  porous_cube ///< porous cube of side a d [Deen07 eq. 34-37]
};

struct PorositySettings {
  PorosityMethod method = PorosityMethod::cell; ///< `coupling.porosity`: "cell" | "porous_cube"
  double cube_factor = 3.0; ///< `coupling.cube_factor`: a of [Deen07 eq. 34], >= (pi/6)^(1/3)
};

/// [Zhu07 §3.2]: scheme 1 (local-average force on the gas), 2 (cell force distributed to the
/// particles, [Chang08 eq. 2.11] by surface area), 3 (per-particle forces summed; default).
/// All three are implemented in coupling/exchange.cpp (docs/coupling.md).
enum class ExchangeScheme { scheme1, scheme2, scheme3 };

struct CouplingSettings {
  /// `coupling.drag`: the name of a closure of src/coupling/drag/drag_model.hpp (checked there
  /// at set-up: coupling::drag::drag_model_of_case). Empty: the key was not given, and the
  /// closure the registry declares the default is used; the set-up writes its name here, so that
  /// the resolved case names the closure a run used.
  std::string drag;
  PorositySettings porosity;                       ///< `coupling.porosity`, `.cube_factor`
  ExchangeScheme scheme = ExchangeScheme::scheme3; ///< `coupling.scheme`: 1 | 2 | 3
  /// `coupling.hold_gas_at_rest`: each flow step a uniform force on the gas (a mean pressure
  /// gradient, the reaction of the container of a periodic suspension) removes the gas's mean
  /// momentum along every periodic axis: the gas is at rest on average, the momentum the
  /// particles give it leaves the system. Only with a periodic axis.
  bool hold_gas_at_rest = false;
  /// `coupling.smoothing_length`, m: standard deviation sigma of the Gaussian the diffusion
  /// smoothing of the solids fraction and the momentum source spreads a cell's content over
  /// (D T = sigma^2 / 2; coupling/smoothing.hpp, docs/smoothing.md). 0 = off.
  double smoothing_length = 0.0;
  double d_mean = 0.0; ///< `coupling.d_mean`, m: Sauter mean diameter (polydisperse closures;
                       ///< 0 = computed from the inserted particles)
};

std::string_view to_string(PorosityMethod m);
PorosityMethod porosity_method_from_string(std::string_view name, const std::string& key);

} // namespace fluidem::coupling
