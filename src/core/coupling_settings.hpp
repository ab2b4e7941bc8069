// Settings of the particle-gas coupling: plain data, one field per case-file key
// (`coupling.<field>`). The models themselves live in src/coupling/ (drag closures in
// src/coupling/drag/, one file each, with their registry): the case holds the drag closure's
// name as a string, which the coupling module checks against its registry at set-up (with the
// key's source location), so that core knows no drag law.
#pragma once
#include <array>
#include <optional>
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

/// `coupling.mode`: who acts on whom (docs/coupling.md, "Coupling modes").
enum class CouplingMode {
  two_way, ///< the gas moves the particles and the particles the gas (porosity and momentum)
  one_way, ///< the gas moves the particles; the gas is solved without them (porosity 1, no
           ///< momentum source): its field is that of the empty domain
  frozen   ///< the gas is not solved: a prescribed steady field (frozen_velocity + gradient)
};

/// `coupling.particle_force`: the form of the gas force on a particle (docs/coupling.md,
/// "Particle force forms"); the gas receives exactly minus it in every form.
enum class ParticleForceForm {
  pressure_gradient, ///< drag + (-V grad p) [Zhu07 eq. 5]; gas Model A (its default)
  buoyancy,          ///< drag / eps + (-V rho g) [Zhu07 §3.1 after eq. 7]; gas Model B (default)
  total ///< the closure's total force + (-V rho g) [Hoomans96 eq. 34; buoyancy added]; Model B
};

/// `[coupling.forces]`: the particle-fluid forces beyond drag and pressure [Zhu07 Table 3]
/// (docs/coupling.md, "Fluid forces beyond drag"; kernels in src/coupling/forces/).
struct FluidForceSettings {
  /// `virtual_mass`: the added-mass force C rho_f V (Du/Dt - dv/dt), implicit in the particle's
  /// inertia; `virtual_mass_coefficient` C (0.5: a sphere in potential flow).
  bool virtual_mass = false;
  double virtual_mass_coefficient = 0.5;
  /// `basset`: the Basset history force [Zhu07 Table 3]; `basset_window`: the flow steps of
  /// recent history integrated exactly (older history: an exponential-sum tail).
  bool basset = false;
  int basset_window = 10;
  /// `saffman`: shear lift, Saffman 1965/68 with Mei's (1992) finite-Re correction.
  bool saffman = false;
  /// `magnus`: "off" | "rubinow_keller" (low Re) | "oesterle_bui_dinh" (finite Re).
  std::string magnus = "off";
  /// `torque`: the fluid torque on a spinning particle, "off" | "stokes" (8 pi mu a^3
  /// (Omega/2 - omega)) | "dennis" (Dennis, Singh & Ingham 1980, finite Re).
  std::string torque = "off";
  bool any() const {
    return virtual_mass || basset || saffman || magnus != "off" || torque != "off";
  }
};

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
  CouplingMode mode = CouplingMode::two_way; ///< `coupling.mode`
  /// `coupling.particle_force`; not given: pressure_gradient in gas Model A, buoyancy in Model B
  /// (the set-up writes the resolved form here).
  std::optional<ParticleForceForm> particle_force;
  /// Frozen gas (mode = frozen): u(x) = frozen_velocity + frozen_gradient x, m/s, with
  /// frozen_gradient[i][j] = du_i/dx_j, 1/s (`coupling.frozen_velocity`,
  /// `coupling.frozen_velocity_gradient`); the pressure is hydrostatic.
  std::array<double, 3> frozen_velocity{};
  std::array<std::array<double, 3>, 3> frozen_gradient{};
  FluidForceSettings forces; ///< `[coupling.forces]`
  /// Not a case key: the factor from a particle's diameter to the one the drag closure sees,
  /// set by the coarse-graining set-up (integrate/coarse_graining.hpp; 1 without it). The
  /// particle's volume stays its own.
  double drag_diameter_factor = 1.0;
};

std::string_view to_string(CouplingMode m);
std::string_view to_string(ParticleForceForm f);

std::string_view to_string(PorosityMethod m);
PorosityMethod porosity_method_from_string(std::string_view name, const std::string& key);

} // namespace fluidem::coupling
