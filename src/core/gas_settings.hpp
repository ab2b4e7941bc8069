// Settings of the gas phase: plain data in SI units, one field per case-file key
// (`gas.<field>`; the key of each field is named in its comment). validate() throws
// fluidem::InputError naming the key. Equations: [Deen07 eq. 7-9], Model A/B [Zhu07 eq. 4-7],
// ideal gas [Hoomans96 eq. 44], boundary cell types [Hoomans96 Table 1] (what each type does:
// core/gas_boundary_kind.hpp, one file per type in core/gas_boundary/).
#pragma once
#include "core/gas_boundary_kind.hpp"
#include "core/vec3.hpp"
#include <array>
#include <string>
#include <vector>

namespace fluidem::gas {

/// Time dependence of an inflow velocity [Deen07 §6.1].
enum class InflowMode {
  constant,  ///< velocity
  pulse,     ///< velocity during [start, start + duration), background otherwise
  pulsation, ///< velocity + amplitude * sin(2 pi frequency t)
  table      ///< piecewise linear through (times[k], velocities[k]), constant beyond the ends
};

enum class PressureModel {
  A, ///< -eps grad p in the gas momentum equation [Zhu07 eq. 5]
  B  ///< -grad p in the gas momentum equation [Zhu07 eq. 7]
};

enum class EquationOfState {
  ideal_gas,     ///< rho = p M / (R T) [Hoomans96 eq. 44]
  incompressible ///< rho = density
};

/// Inflow velocity as a function of time. The velocity is the superficial velocity (volume flow
/// per unit face area) INTO the domain, m/s; the gas velocity on the boundary face is this
/// divided by the porosity of the boundary (ghost) cell.
struct InflowProfile {
  InflowMode mode = InflowMode::constant; ///< `.mode`: "constant" | "pulse" | "pulsation"
  double velocity = 0.0;            ///< `.velocity`, m/s: constant value; pulse: during the pulse;
                                    ///< pulsation: the mean
  double background = 0.0;          ///< `.background`, m/s: pulse only, velocity outside the pulse
  double start = 0.0;               ///< `.start`, s: pulse only, start time
  double duration = 0.0;            ///< `.duration`, s: pulse only, >= 0
  double amplitude = 0.0;           ///< `.amplitude`, m/s: pulsation only
  double frequency = 0.0;           ///< `.frequency`, Hz: pulsation only, >= 0
  std::vector<double> times{};      ///< `.times`, s: table only, strictly increasing, >= 2
  std::vector<double> velocities{}; ///< `.velocities`, m/s: table only, one per time
};

/// Superficial inflow velocity of a profile at time t, m/s (exact formula, no smoothing).
double inflow_velocity(const InflowProfile& profile, double t);

/// A rectangle on a domain face with its own boundary type (an orifice, a jet, a vent).
/// Its extent is given in the two tangential coordinates of the face, in axis order:
/// left/right faces (x): (y, z); front/back (y): (x, z); bottom/top (z): (x, y). In 2-D the y
/// range is ignored. A boundary cell belongs to the region when its face centre lies inside.
struct BoundaryRegion {
  BoundaryType type = BoundaryType::inflow; ///< `.type` (not periodic)
  std::array<double, 2> lo{0.0, 0.0};       ///< `.lo`, m: lower corner (tangential coords)
  std::array<double, 2> hi{0.0, 0.0};       ///< `.hi`, m: upper corner
  InflowProfile inflow;                     ///< `.velocity`, `.mode`, ...: type inflow only
  double porosity = 0.4;      ///< `.porosity`: ghost porosity of inflow cells [Hoomans96 §3.5]
  double pressure = 101325.0; ///< `.pressure`, Pa: type pressure only
};

/// One face of the domain: its type, and regions overriding it.
struct GasBoundary {
  BoundaryType type = BoundaryType::wall_no_slip; ///< `.type`
  InflowProfile inflow;                           ///< `.velocity`, `.mode`, ...: inflow only
  double porosity = 0.4;      ///< `.porosity`: ghost porosity of inflow cells (distributor)
  double pressure = 101325.0; ///< `.pressure`, Pa: prescribed pressure on the face
  std::vector<BoundaryRegion> regions; ///< `.regions`: applied in order, later ones win
};

/// Domain faces, in the order of GasSettings::boundary; the name is the case-file key.
enum Side { left = 0, right, front, back, bottom, top };
inline constexpr std::array<const char*, 6> side_names{"left", "right",  "front",
                                                       "back", "bottom", "top"};

struct GasSettings {
  int dimension = 3;                 ///< `gas.dimension`: 2 (x-z plane) or 3
  std::array<int, 3> cells{8, 8, 8}; ///< `gas.cells`: nx, ny, nz (ny ignored = 1 in 2-D)
  Vec3 lo{0.0, 0.0, 0.0};            ///< `gas.lo`, m: lower domain corner
  Vec3 hi{0.1, 0.1, 0.1};            ///< `gas.hi`, m: upper corner (hi.y ignored in 2-D)
  double depth = 0.01;               ///< `gas.depth`, m: 2-D only, thickness in y
  double time_step = 0.0;    ///< `gas.time_step`, s: flow time step DT of a soft-sphere run (the
                             ///< DEM sub-steps inside it); 0 = "auto" = 1e-4 s [Hoomans96 §5.3].
                             ///< Hard-sphere runs: DT is simulation.time_step and this must be 0.
  double viscosity = 1.8e-5; ///< `gas.viscosity`, Pa s (kg m^-1 s^-1)
  PressureModel model = PressureModel::A;           ///< `gas.model`: "A" | "B"
  EquationOfState eos = EquationOfState::ideal_gas; ///< `gas.eos`: "ideal_gas" | "incompressible"
  double molar_mass = 28.8e-3;          ///< `gas.molar_mass`, kg/mol [Hoomans96 §3.2.1]
  double temperature = 293.0;           ///< `gas.temperature`, K
  double density = 1.2;                 ///< `gas.density`, kg/m^3: incompressible only
  Vec3 gravity{0.0, 0.0, -9.81};        ///< `gas.gravity`, m/s^2
  std::array<GasBoundary, 6> boundary;  ///< `gas.boundary.<left|right|front|back|bottom|top>`;
                                        ///< in 2-D front/back are free-slip walls, whatever set
  double initial_pressure = 101325.0;   ///< `gas.initial_pressure`, Pa (also the reference)
  Vec3 initial_velocity{0.0, 0.0, 0.0}; ///< `gas.initial_velocity`, m/s (interstitial)

  // Pressure-correction iterations per flow step (`gas.solver.*`).
  double tolerance = 1e-8; ///< `gas.solver.tolerance`: mass residual, sum|cell imbalance| dt /
                           ///< total gas mass (dimensionless)
  double velocity_tolerance = 1e-6; ///< `gas.solver.velocity_tolerance`, m/s: estimated max
                                    ///< distance of the velocity from the converged solution
                                    ///< (docs/gas.md)
  int max_iterations = 100;         ///< `gas.solver.max_iterations`
  double velocity_relaxation = 1.0; ///< `gas.solver.velocity_relaxation`, (0, 1]
  double pressure_relaxation = 1.0; ///< `gas.solver.pressure_relaxation`, (0, 1]
  double linear_tolerance = 1e-10;  ///< `gas.solver.linear_tolerance`: relative residual of the
                                    ///< linear solves (Gauss-Seidel momentum, hypre pressure)
  int linear_max_iterations = 200;  ///< `gas.solver.linear_max_iterations`
  /// `gas.solver.max_courant`: largest |u| DT / h on any face after a flow step; above it the
  /// gas crosses more than this many cells per step (the explicit porosity and coupling update
  /// loses accuracy, the run has usually gone wrong): the run stops as unstable.
  double max_courant = 1.0;
};

/// Throws fluidem::InputError naming the key of the first bad setting.
void validate(const GasSettings& s);

/// Name <-> enum for the case-file reader; the parsers throw InputError naming `key` and
/// listing the valid names.
std::string to_string(BoundaryType t);
std::string to_string(InflowMode m);
BoundaryType boundary_type_from_string(const std::string& name, const std::string& key);
InflowMode inflow_mode_from_string(const std::string& name, const std::string& key);
PressureModel pressure_model_from_string(const std::string& name, const std::string& key);
EquationOfState eos_from_string(const std::string& name, const std::string& key);

/// Universal gas constant, J mol^-1 K^-1.
inline constexpr double gas_constant = 8.314462618;

} // namespace fluidem::gas
