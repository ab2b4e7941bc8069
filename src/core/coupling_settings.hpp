// Settings of the particle-gas coupling: plain data, one field per case-file key
// (`coupling.<field>`). The models themselves live in src/coupling/ (drag closures in
// src/coupling/drag/, one file each); this header only names them, so that the case (core) can
// hold the settings without depending on the coupling module.
#pragma once
#include <array>
#include <string>
#include <string_view>

namespace fluidem::coupling {

namespace drag {
/// Drag closures by case-file name (`coupling.drag`); each is a type in src/coupling/drag/.
enum class DragModel {
  ergun,            ///< [Deen07 eq. 3]
  wen_yu,           ///< beta form [Deen07 eq. 4]
  wen_yu_single,    ///< single-particle form [Hoomans96 eq. 35-39]
  ergun_wen_yu,     ///< switch at eps = 0.8 [Hoomans96 eq. 45-46]
  ergun_wen_yu_min, ///< the smaller of the two [Deen07 §3.1]
  hill_koch_ladd,   ///< [Deen07 eq. 5]
  beetstra,         ///< monodisperse [Deen07 eq. 6]
  beetstra_poly,    ///< polydisperse [Deen07 eq. 6] with the Sauter mean diameter
  di_felice,        ///< [Zhu07 Table 3]
  koch_hill,        ///< [Zhu07 Table 3]
  chang_joint,      ///< joint Ergun/Wen-Yu correlation [Chang08 §2.1]
};

/// All models, in the order of the enum.
inline constexpr std::array<DragModel, 11> all_drag_models = {
    DragModel::ergun,        DragModel::wen_yu,           DragModel::wen_yu_single,
    DragModel::ergun_wen_yu, DragModel::ergun_wen_yu_min, DragModel::hill_koch_ladd,
    DragModel::beetstra,     DragModel::beetstra_poly,    DragModel::di_felice,
    DragModel::koch_hill,    DragModel::chang_joint};

/// Case-file names, in the order of the enum (each equals the closure type's `name`; tested).
inline constexpr std::array<std::string_view, 11> drag_model_name_table = {
    "ergun",          "wen_yu",   "wen_yu_single", "ergun_wen_yu", "ergun_wen_yu_min",
    "hill_koch_ladd", "beetstra", "beetstra_poly", "di_felice",    "koch_hill",
    "chang_joint"};

/// The case-file name of m ("ergun", "wen_yu", ...).
std::string_view to_string(DragModel m);
/// Why a case may not choose m today; empty if it may. `wen_yu_single` is refused: it is the
/// TOTAL gas force on a particle [Hoomans96 eq. 34-37], to be used without a pressure-gradient
/// force, but the exchange (coupling/exchange.hpp) always adds -V grad p (Model A) or the
/// buoyancy term with the drag divided by eps (Model B), so the pressure force would be counted
/// twice. The closure itself stays (tested against tests/models/drag/wen_yu_single.toml) for the
/// exchange form that omits the pressure force.
std::string_view drag_model_refusal(DragModel m);
/// Comma-separated list of the names a case may choose (those without a refusal), for error
/// messages and docs.
std::string drag_model_names();
/// The model named `name`; InputError listing the valid names if there is none.
DragModel drag_model_from_string(std::string_view name);
} // namespace drag

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
  drag::DragModel drag = drag::DragModel::ergun_wen_yu; ///< `coupling.drag`
  PorositySettings porosity;                            ///< `coupling.porosity`, `.cube_factor`
  ExchangeScheme scheme = ExchangeScheme::scheme3;      ///< `coupling.scheme`: 1 | 2 | 3
  /// `coupling.hold_gas_at_rest`: each flow step a uniform force on the gas (a mean pressure
  /// gradient, the reaction of the container of a periodic suspension) removes the gas's mean
  /// momentum along every periodic axis: the gas is at rest on average, the momentum the
  /// particles give it leaves the system. Only with a periodic axis.
  bool hold_gas_at_rest = false;
  double d_mean = 0.0; ///< `coupling.d_mean`, m: Sauter mean diameter (polydisperse closures;
                       ///< 0 = computed from the inserted particles)
};

std::string_view to_string(PorosityMethod m);
PorosityMethod porosity_method_from_string(std::string_view name, const std::string& key);

} // namespace fluidem::coupling
