// The case as data: every input of a run, in SI units, after parsing and defaults.
// Filled by io/case_reader, written back by io/case_writer (case.resolved.toml), consumed by
// every module. No physics here. Key names below are the case-file keys (docs/case-file.md).
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/body_force.hpp"
#include "core/coarse_graining.hpp"
#include "core/coupling_settings.hpp"
#include "core/error.hpp"
#include "core/gas_settings.hpp"
#include "core/noncontact_settings.hpp"

namespace fluidem {

/// Contact material of a species or a wall [Zhu07 Table 1; Deen07 eq. 11-21, 43].
struct MaterialSpec {
  double youngs_modulus = 1.0e7;       ///< E, Pa; +inf: a rigid wall (walls only)
  double poisson_ratio = 0.25;         ///< nu, - (from shear_modulus when that is given)
  std::optional<double> shear_modulus; ///< G, Pa, when given instead of nu (nu = E/(2G) - 1)
  double restitution = 0.9;            ///< e_n in [0,1] (soft spheres: (0, 1])
  double friction = 0.3;               ///< Coulomb mu >= 0; +inf: never sliding
  double tangential_restitution = 0.0; ///< beta_0 in [0,1] [Deen07 eq. 19, 43]
  double rolling_friction = 0.0;       ///< mu_r >= 0, dimensionless (torque = mu_r R* |F_n|)
};

/// G of a material: the given one, or E / (2 (1 + nu)) (+inf for a rigid wall).
inline double shear_modulus_of(const MaterialSpec& m) {
  return m.shear_modulus ? *m.shear_modulus : m.youngs_modulus / (2.0 * (1.0 + m.poisson_ratio));
}

struct SpeciesSpec {
  std::string name;
  double diameter = 0.0; ///< m, > 0
  double density = 0.0;  ///< kg/m^3, > 0
  double charge = 0.0;   ///< C per particle ([electrostatics])
  /// Liquid volume per particle / particle volume ([liquid_bridge]); 0: dry.
  double liquid_fraction = 0.0;
  MaterialSpec material;
};

/// The six faces of the box, in this order everywhere.
enum class Face : int { XLo = 0, XHi, YLo, YHi, ZLo, ZHi };
inline constexpr std::array<const char*, 6> kFaceNames = {"x_lo", "x_hi", "y_lo",
                                                          "y_hi", "z_lo", "z_hi"};

struct DomainSpec {
  std::array<double, 3> lo{0, 0, 0}; ///< m
  std::array<double, 3> hi{1, 1, 1}; ///< m
  std::array<bool, 3> periodic{false, false, false};
  /// Material of each face (ignored on periodic axes); [walls] sets all, [walls.x_lo] one.
  std::array<MaterialSpec, 6> wall_material{};
};

enum class Placement { Random, Lattice, File };

/// A particle-size distribution of one [[insert]] block (`size_distribution`,
/// docs/case-file.md): the diameters of the block's particles, drawn from `seed`; the material
/// stays the species'. Sampled by particles/size_distribution.hpp.
struct SizeDistributionSpec {
  enum class Kind { Normal, LogNormal, Table, Discrete };
  enum class Basis { Number, Mass };
  Kind kind = Kind::Normal;
  Basis basis = Basis::Number;    ///< what the parameters describe: counts, or mass (volume)
  double mean = 0.0;              ///< normal: mean, m
  double std = 0.0;               ///< normal: standard deviation, m
  double median = 0.0;            ///< log_normal: geometric mean d_g, m
  double geometric_std = 0.0;     ///< log_normal: sigma_g > 1
  double min = 0.0;               ///< normal, log_normal: truncation, m (resolved: always set)
  double max = 0.0;               ///< m
  std::vector<double> diameters;  ///< table, discrete: m, increasing
  std::vector<double> cumulative; ///< table: CDF at the diameters, 0 ... 1
  std::vector<double> fractions;  ///< discrete: fraction of each diameter, summing to 1
};

struct InsertSpec {
  std::string species;               ///< name of a [[species]]
  long count = 0;                    ///< particles to insert (ignored for File placement)
  std::array<double, 3> region_lo{}; ///< m; defaults to the domain
  std::array<double, 3> region_hi{}; ///< m
  Placement placement = Placement::Random;
  std::string file;                        ///< LAMMPS data file (id type diameter density x y z)
  std::array<double, 3> velocity{0, 0, 0}; ///< m/s
  double velocity_spread = 0.0;            ///< m/s, uniform in [-s, s] per component
  /// rad/s; 2-D (discs in the x-z plane): only the y component (spin in the plane)
  std::array<double, 3> angular_velocity{0, 0, 0};
  /// The particles are held in place (infinite mass and inertia, ParticleStore::fix)
  bool fixed = false;
  std::uint64_t seed = 1;
  /// C per particle of this insert; empty: the species' charge.
  std::optional<double> charge;
  /// The diameters of this block's particles; empty: the species' diameter.
  std::optional<SizeDistributionSpec> size_distribution;
};

/// One contact sub-model as the case names it: its name (the case-file string; empty: the kind's
/// default) and the values of its coefficients (case key in [contact] -> value, SI units; a
/// coefficient left "auto" is absent). Which models exist, which keys each takes, their units,
/// ranges, defaults and mixing rules are declared with the models (contact/models/,
/// docs/contact.md): core does not know them.
struct ContactModelSpec {
  std::string name;
  std::map<std::string, double> coefficients;
};

struct ContactSpec {
  ContactModelSpec normal;     ///< default: the model declared as the normal default
  ContactModelSpec tangential; ///< (likewise)
  ContactModelSpec rolling;    ///< (likewise)
  std::optional<double> characteristic_velocity; ///< m/s for impact-speed durations; empty = auto
  double max_overlap = 0.1;                      ///< instability guard: overlap / smaller diameter
};

/// The particle engine: time-driven soft spheres (DEM) or event-driven hard spheres.
enum class Engine { SoftSphere, HardSphere };

struct SimulationSpec {
  Engine engine = Engine::SoftSphere;         ///< "soft_sphere" | "hard_sphere"
  int dimension = 3;                          ///< 2: discs moving in the x-z plane; 3: spheres
  double end_time = 0.0;                      ///< s, > 0
  std::optional<double> time_step;            ///< s; empty = "auto"
  double time_step_fraction = 0.02;           ///< auto dt = fraction x shortest contact duration
  bool force_time_step = false;               ///< allow dt above the stability limit
  std::array<double, 3> gravity{0, 0, -9.81}; ///< m/s^2
  double insertion_overlap_tolerance = 0.01;  ///< allowed initial overlap / smaller diameter
};

/// Event-driven hard-sphere engine [Hoomans96 §2-3; Deen07 §2.1, §4]. The flow time step DT is
/// simulation.time_step ("auto" = 1e-4 s, as in [Hoomans96 Table 2]).
struct HardSphereSpec {
  /// TC model (Luding & McNamara 1998) against inelastic collapse: a collision of a particle
  /// within this time of its previous collision dissipates nothing (e_n = 1, smooth). s, >= 0;
  /// 0 = off.
  double tc_time = 1.0e-6;
  /// Collisions whose normal impact speed is below this dissipate nothing either (the
  /// restitution of real spheres tends to 1 at vanishing impact speed; McNamara & Falcon 2005).
  /// Keeps a bed at rest under gravity from collapsing into ever faster micro-collisions.
  /// m/s, >= 0; empty ("auto") = sqrt(2 |g| 1e-3 d_min), the speed gained in a fall through a
  /// thousandth of the smallest diameter (8.9 mm/s for 4 mm particles; 0 without gravity).
  std::optional<double> elastic_below;
  /// Guard: more events than this per particle within one DT stops the run (exit 3). >= 1.
  double max_events_per_particle = 1000.0;
};

/// A named point where the gas pressure is recorded (`[[output.probe]]`, probes.csv).
struct ProbeSpec {
  std::string name;                 ///< column name in probes.csv
  std::array<double, 3> position{}; ///< m; inside the gas domain
};

/// A named sphere (a circle in the x-z plane in 2-D) over which the collision frequency and the
/// local void fraction are computed (`[[output.collision_region]]`, columns of collisions.csv)
/// [Chang08 Table 1, regions GC and CC].
struct CollisionRegionSpec {
  std::string name;
  std::array<double, 3> centre{}; ///< m; inside the domain
  double radius = 0.0;            ///< m, > 0
};

/// Discrete-to-continuum averaging (`[output.continuum]`, OUT/continuum.h5) [Zhu07 Tables 5-6].
enum class ContinuumMethod { Volume, Weighted };

struct ContinuumOutputSpec {
  std::array<int, 3> cells{1, 1, 1};                ///< averaging cells over the domain
  ContinuumMethod method = ContinuumMethod::Volume; ///< "volume" | "weighted"
  double width = 0.0;    ///< m, Gaussian width of the weighted method (required there)
  double cutoff = 3.0;   ///< weighted: the Gaussian is cut at cutoff x width
  double interval = 0.0; ///< s, averaging interval; 0 (key absent) = output.frame_interval
  int stride = 1;        ///< average every stride-th step of the interval
};

struct OutputSpec {
  double frame_interval = 0.01;   ///< s between particle (and gas field) frames
  double series_interval = 0.001; ///< s between rows of series.csv (and probes.csv)
  /// s between checkpoints (OUT/checkpoint.h5); 0 (key absent): 10 frame intervals.
  double checkpoint_interval = 0.0;
  /// Number of horizontal layers the initial bed is split into (0 = off): each particle keeps
  /// the index of the band its centre started in (ParticleStore::layer), written to particles.h5.
  int layers = 0;
  std::vector<ProbeSpec> probes; ///< pressure probes (coupled runs only)
  /// Collision statistics (analysis/collision_statistics.hpp): OUT/collisions.csv every series
  /// interval and OUT/collision_overlap.csv at the end.
  bool collisions = false;
  std::vector<CollisionRegionSpec> collision_regions; ///< only with collisions = true
  std::optional<ContinuumOutputSpec> continuum;       ///< continuum averages (empty: off)
  /// Run `fluidem analyse OUT` at the end of the run (OUT/analysis/: spectra, velocity
  /// distributions, segregation, bed and collision summaries; docs/analysis.md).
  bool analyse = false;
};

struct NeighbourSpec {
  std::optional<double>
      skin; ///< m; empty = "auto": from the speeds at each build (NeighbourList::AutoSkin)
  /// The particles are sorted in space (neighbour/spatial_order.hpp) at every
  /// sort_interval-th rebuild of the neighbour list (of either engine); 0 = never.
  int sort_interval = 20;
};

/// [parallel]: how a run is shared out between MPI ranks (docs/parallel.md).
struct ParallelSpec {
  /// The soft-sphere engine's rank-independent mode (full neighbour rows in partner-id order:
  /// the same bits on any number of ranks): empty = "auto", on when mpirun started the run.
  std::optional<bool> rank_independent;
  /// The ranks' process grid {px, py, pz}; {0, 0, 0} = "auto" (columns first).
  std::array<int, 3> process_grid{0, 0, 0};
  /// Neighbour-list builds between moves of the cut planes to the measured cost; 0: never.
  int balance_interval = 20;
};

/// The whole case, plus where each key came from (for error messages).
struct CaseSpec {
  std::string source_file; ///< path of the case file as given
  SimulationSpec simulation;
  OutputSpec output;
  DomainSpec domain;
  std::vector<SpeciesSpec> species;
  std::vector<InsertSpec> inserts;
  ContactSpec contact;
  NeighbourSpec neighbour;
  ParallelSpec parallel;
  HardSphereSpec hardsphere;
  /// The gas phase (`[gas]`); empty = a purely granular run.
  std::optional<gas::GasSettings> gas;
  /// Particle-gas coupling (`[coupling]`); used when `gas` is set.
  coupling::CouplingSettings coupling;
  /// A spatially varying body force on the particles (`[body_force]`); empty = none.
  std::optional<BodyForceSpec> body_force;
  /// Non-contact forces between particles ([van_der_waals], [electrostatics]).
  NonContactSpec noncontact;
  /// Coarse-grained parcels (`[coarse_graining]`): the species are the real particles, the run
  /// simulates parcels of `ratio` of them (integrate/coarse_graining.hpp).
  CoarseGrainingSpec coarse_graining;

  /// Dotted key path -> location, e.g. "contact.stiffness", "species[1].restitution",
  /// "insert[0].count", "walls.z_lo.friction". Filled by the reader for every key it saw.
  std::map<std::string, SourceLocation> locations;

  /// Location of a key, or of its nearest enclosing table, or just the file.
  SourceLocation where(const std::string& key) const;
  /// Index of the species with this name, or -1.
  int species_index(const std::string& name) const;
};

/// Each species' liquid_fraction, in species order.
std::vector<double> liquid_fractions(const CaseSpec& spec);

const char* to_string(Engine e);
const char* to_string(Placement p);
const char* to_string(ContinuumMethod m);

} // namespace fluidem
