#include "io/case_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <toml++/toml.h>
#include <unordered_map>
#include <utility>

#include "contact/contact_models.hpp"
#include "core/input_file.hpp"
#include "io/case_writer.hpp"
#include "io/key_suggest.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;
using Keys = std::vector<std::string>;

constexpr const char* kSetFile = "--set";

// ---------------------------------------------------------------------------------------------
// The schema: valid keys of every table.

const Keys& root_keys() {
  static const Keys k = {
      "simulation",      "output",     "domain",        "walls",          "species",
      "insert",          "contact",    "neighbour",     "hardsphere",     "gas",
      "coupling",        "body_force", "van_der_waals", "electrostatics", "liquid_bridge",
      "coarse_graining", "parallel"};
  return k;
}
const Keys& simulation_keys() {
  static const Keys k = {"engine",
                         "dimension",
                         "end_time",
                         "time_step",
                         "time_step_fraction",
                         "force_time_step",
                         "gravity",
                         "insertion_overlap_tolerance"};
  return k;
}
const Keys& output_keys() {
  static const Keys k = {"frame_interval",   "series_interval", "checkpoint_interval",
                         "layers",           "probe",           "collisions",
                         "collision_region", "continuum",       "analyse"};
  return k;
}
const Keys& continuum_keys() {
  static const Keys k = {"cells", "method", "width", "cutoff", "interval", "stride"};
  return k;
}
const Keys& collision_region_keys() {
  static const Keys k = {"name", "centre", "radius"};
  return k;
}
const Keys& probe_keys() {
  static const Keys k = {"name", "position"};
  return k;
}
const Keys& domain_keys() {
  static const Keys k = {"lo", "hi", "periodic"};
  return k;
}
const Keys& material_keys() {
  static const Keys k = {"youngs_modulus",  "poisson_ratio", "shear_modulus",
                         "restitution",     "friction",      "tangential_restitution",
                         "rolling_friction"};
  return k;
}
const Keys& face_keys() {
  static const Keys k(kFaceNames.begin(), kFaceNames.end());
  return k;
}
const Keys& walls_keys() {
  static const Keys k = [] {
    Keys all = material_keys();
    all.insert(all.end(), face_keys().begin(), face_keys().end());
    return all;
  }();
  return k;
}
const Keys& species_keys() {
  static const Keys k = [] {
    Keys all = {"name", "diameter", "density", "charge", "liquid_fraction"};
    all.insert(all.end(), material_keys().begin(), material_keys().end());
    return all;
  }();
  return k;
}
const Keys& insert_keys() {
  static const Keys k = {"species", "count",    "placement",       "file",
                         "region",  "velocity", "velocity_spread", "angular_velocity",
                         "fixed",   "seed",     "charge",          "size_distribution"};
  return k;
}
/// [[insert]] size_distribution: every kind's keys (read_size_distribution says which belong to
/// which kind).
const Keys& size_distribution_keys() {
  static const Keys k = {"kind", "basis", "mean",      "std",        "median",   "geometric_std",
                         "min",  "max",   "diameters", "cumulative", "fractions"};
  return k;
}
const Keys& region_keys() {
  static const Keys k = {"lo", "hi"};
  return k;
}
/// [contact]: the kinds' model names, the keys of every model's coefficients (declared with the
/// models, contact/models/), and the keys of every model.
const Keys& contact_keys() {
  static const Keys k = [] {
    Keys all = {"normal", "tangential", "rolling"};
    const auto& coefficients = contact_models::coefficient_keys();
    all.insert(all.end(), coefficients.begin(), coefficients.end());
    all.insert(all.end(), {"characteristic_velocity", "max_overlap"});
    return all;
  }();
  return k;
}
const Keys& neighbour_keys() {
  static const Keys k = {"skin", "sort_interval"};
  return k;
}
const Keys& parallel_keys() {
  static const Keys k = {"rank_independent", "process_grid", "balance_interval"};
  return k;
}
const Keys& hardsphere_keys() {
  static const Keys k = {"tc_time", "elastic_below", "max_events_per_particle"};
  return k;
}
const Keys& coarse_graining_keys() {
  static const Keys k = {"ratio", "contact_scaling", "drag_diameter"};
  return k;
}
const Keys& van_der_waals_keys() {
  static const Keys k = {"hamaker", "min_separation", "range", "wall_hamaker"};
  return k;
}
const Keys& electrostatics_keys() {
  static const Keys k = {"cutoff", "relative_permittivity", "conducting_walls"};
  return k;
}
const Keys& liquid_bridge_keys() {
  static const Keys k = {"surface_tension", "contact_angle", "viscosity", "min_gap", "walls"};
  return k;
}
const Keys& body_force_keys() {
  static const Keys k = {"type", "amplitude", "wavelength", "origin"};
  return k;
}
const Keys& gas_keys() {
  static const Keys k = {"cells",
                         "time_step",
                         "viscosity",
                         "model",
                         "eos",
                         "molar_mass",
                         "temperature",
                         "density",
                         "initial_pressure",
                         "initial_velocity",
                         "solver",
                         "boundary"};
  return k;
}
const Keys& gas_solver_keys() {
  static const Keys k = {
      "tolerance",           "velocity_tolerance", "max_iterations",        "velocity_relaxation",
      "pressure_relaxation", "linear_tolerance",   "linear_max_iterations", "max_courant"};
  return k;
}
const Keys& gas_side_keys() {
  static const Keys k(gas::side_names.begin(), gas::side_names.end());
  return k;
}
/// Keys of an inflow or pressure boundary: a face or a region of a face.
const Keys& inflow_keys() {
  static const Keys k = {"velocity",  "mode",  "background", "start",    "duration", "amplitude",
                         "frequency", "times", "velocities", "porosity", "pressure"};
  return k;
}
const Keys& gas_face_keys() {
  static const Keys k = [] {
    Keys all = {"type"};
    all.insert(all.end(), inflow_keys().begin(), inflow_keys().end());
    all.push_back("region");
    return all;
  }();
  return k;
}
const Keys& gas_region_keys() {
  static const Keys k = [] {
    Keys all = {"type", "lo", "hi"};
    all.insert(all.end(), inflow_keys().begin(), inflow_keys().end());
    return all;
  }();
  return k;
}
/// Keys of the gas settings that are derived from the particle side, so that the two domains
/// can never disagree; each with where it is set instead.
const std::vector<std::pair<std::string, std::string>>& gas_derived_keys() {
  static const std::vector<std::pair<std::string, std::string>> k = {
      {"dimension", "the gas dimension is simulation.dimension"},
      {"lo", "the gas domain is the particle domain, domain.lo and domain.hi"},
      {"hi", "the gas domain is the particle domain, domain.lo and domain.hi"},
      {"depth", "the 2-D gas depth is domain.hi[1] - domain.lo[1]"},
      {"gravity", "the gas gravity is simulation.gravity"},
      {"periodic", "a periodic axis is set by domain.periodic"}};
  return k;
}
const Keys& coupling_keys() {
  static const Keys k = {"drag",
                         "porosity",
                         "cube_factor",
                         "scheme",
                         "d_mean",
                         "hold_gas_at_rest",
                         "mode",
                         "particle_force",
                         "frozen_velocity",
                         "frozen_velocity_gradient",
                         "forces",
                         "smoothing_length"};
  return k;
}
const Keys& coupling_force_keys() {
  static const Keys k = {
      "virtual_mass", "virtual_mass_coefficient", "basset", "basset_window", "saffman", "magnus",
      "torque"};
  return k;
}
/// Keys of a top-level table section (species and insert are arrays of tables).
const Keys& section_keys(const std::string& section) {
  if (section == "gas") return gas_keys();
  if (section == "coupling") return coupling_keys();
  if (section == "simulation") return simulation_keys();
  if (section == "output") return output_keys();
  if (section == "domain") return domain_keys();
  if (section == "walls") return walls_keys();
  if (section == "species") return species_keys();
  if (section == "insert") return insert_keys();
  if (section == "contact") return contact_keys();
  if (section == "hardsphere") return hardsphere_keys();
  if (section == "parallel") return parallel_keys();
  if (section == "coarse_graining") return coarse_graining_keys();
  if (section == "body_force") return body_force_keys();
  if (section == "van_der_waals") return van_der_waals_keys();
  if (section == "electrostatics") return electrostatics_keys();
  if (section == "liquid_bridge") return liquid_bridge_keys();
  return neighbour_keys();
}

bool contains(const Keys& keys, const std::string& k) {
  return std::find(keys.begin(), keys.end(), k) != keys.end();
}

/// Keys of the sub-table `sub` of the table at schema path `parent` ("walls", "gas.boundary"),
/// or nullptr when `sub` is a value (or an array of tables).
const Keys* subtable_keys(const std::string& parent, const std::string& sub) {
  if (parent == "walls" && contains(face_keys(), sub)) return &material_keys();
  if (parent == "insert" && sub == "region") return &region_keys();
  if (parent == "insert" && sub == "size_distribution") return &size_distribution_keys();
  if (parent == "gas" && sub == "solver") return &gas_solver_keys();
  if (parent == "coupling" && sub == "forces") return &coupling_force_keys();
  if (parent == "output" && sub == "continuum") return &continuum_keys();
  if (parent == "gas" && sub == "boundary") return &gas_side_keys();
  if (parent == "gas.boundary" && contains(gas_side_keys(), sub)) return &gas_face_keys();
  return nullptr;
}

/// True for the arrays of tables below the top level ([[output.probe]],
/// [[gas.boundary.FACE.region]]).
bool is_table_array(const std::string& parent, const std::string& key) {
  if (parent == "output") return key == "probe" || key == "collision_region";
  return parent.rfind("gas.boundary.", 0) == 0 && key == "region";
}

std::string in_quotes(const std::string& s) {
  return "\"" + s + "\"";
}

std::string join_quoted(const Keys& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + in_quotes(names[i]);
  return s;
}

std::string suggestion(const std::string& prefix, const std::string& key, const Keys& valid) {
  return "unknown key (did you mean " + in_quotes(prefix + nearest_key(key, valid)) + "?)";
}

/// "a string "abc"", "the integer 3", ... for wrong-type messages.
std::string describe(const toml::node& n) {
  switch (n.type()) {
  case toml::node_type::string: {
    std::string s = *n.value<std::string>();
    if (s.size() > 40) s = s.substr(0, 37) + "...";
    return "the string " + in_quotes(s);
  }
  case toml::node_type::integer:
    return "the integer " + std::to_string(*n.value<std::int64_t>());
  case toml::node_type::floating_point:
    return "the number " + format_double(*n.value<double>());
  case toml::node_type::boolean:
    return *n.value<bool>() ? "true" : "false";
  case toml::node_type::array:
    return "an array of " + std::to_string(n.as_array()->size()) + " element" +
           (n.as_array()->size() == 1 ? "" : "s");
  case toml::node_type::table:
    return "a table";
  case toml::node_type::date:
    return "a date";
  case toml::node_type::time:
    return "a time";
  case toml::node_type::date_time:
    return "a date-time";
  default:
    return "nothing";
  }
}

// ---------------------------------------------------------------------------------------------
// Number rules: the allowed range of a real-valued key, and its unit.

enum class Bound {
  Any,
  Positive,
  NonNegative,
  NonNegativeOrInf, ///< >= 0, or +inf (friction: never sliding)
  AtLeastOne,
  Unit,
  Poisson,
  OpenUnit,
  HalfOpenUnit
};

struct NumRule {
  Bound bound;
  const char* unit; ///< "" when dimensionless
};

bool in_bound(double x, Bound b) {
  switch (b) {
  case Bound::Any:
    return true;
  case Bound::Positive:
    return x > 0;
  case Bound::NonNegative:
  case Bound::NonNegativeOrInf:
    return x >= 0;
  case Bound::AtLeastOne:
    return x >= 1;
  case Bound::Unit:
    return x >= 0 && x <= 1;
  case Bound::Poisson:
    return x >= 0 && x < 0.5;
  case Bound::OpenUnit:
    return x > 0 && x < 1;
  case Bound::HalfOpenUnit:
    return x > 0 && x <= 1;
  }
  return false;
}

std::string allowed(NumRule r) {
  std::string s;
  switch (r.bound) {
  case Bound::Any:
    s = "a finite number";
    break;
  case Bound::Positive:
    s = "a number > 0";
    break;
  case Bound::NonNegative:
    s = "a number >= 0";
    break;
  case Bound::NonNegativeOrInf:
    s = "a number >= 0, or inf";
    break;
  case Bound::AtLeastOne:
    s = "a number >= 1";
    break;
  case Bound::Unit:
    s = "a number in [0, 1]";
    break;
  case Bound::Poisson:
    s = "a number in [0, 0.5)";
    break;
  case Bound::OpenUnit:
    s = "a number in (0, 1)";
    break;
  case Bound::HalfOpenUnit:
    s = "a number in (0, 1]";
    break;
  }
  if (*r.unit) s += std::string(", in ") + r.unit;
  return s;
}

const NumRule kLength{Bound::Positive, "m"};
const NumRule kTime{Bound::Positive, "s"};

// ---------------------------------------------------------------------------------------------
// Gas boundaries: which type and mode each key of a face or region belongs to.

/// The group of a boundary key (gas::BoundaryKeys; the types declare which groups they take,
/// core/gas_boundary/); no_keys for keys of every type.
unsigned boundary_key_group(const std::string& key) {
  if (key == "porosity") return gas::porosity_key;
  if (key == "pressure") return gas::pressure_key;
  if (key == "mode" || key == "velocity" || key == "background" || key == "start" ||
      key == "duration" || key == "amplitude" || key == "frequency" || key == "times" ||
      key == "velocities")
    return gas::inflow_keys;
  return gas::no_keys;
}

/// `type = "a"` (or `type = "a" or "b"`): the types a case may choose that take `group`.
std::string types_taking(unsigned group) {
  std::string s;
  for (std::size_t t = 0; t < gas::boundary_type_count; ++t) {
    const gas::BoundaryKind& k = gas::boundary_kind(static_cast<gas::BoundaryType>(t));
    if (k.chosen_in_case && (k.keys & group) != 0)
      s += (s.empty() ? "type = " : " or ") + in_quotes(k.name);
  }
  return s;
}

/// The boundary types a case may name in `.type` (periodic follows domain.periodic), in
/// declaration order.
const std::vector<gas::BoundaryType>& settable_boundary_types() {
  static const std::vector<gas::BoundaryType> types = [] {
    std::vector<gas::BoundaryType> v;
    for (std::size_t k = 0; k < gas::boundary_type_count; ++k)
      if (gas::boundary_kind(static_cast<gas::BoundaryType>(k)).chosen_in_case)
        v.push_back(static_cast<gas::BoundaryType>(k));
    return v;
  }();
  return types;
}

/// The type (and mode) a boundary key is used with; "" for keys of every type.
std::string boundary_key_needs(const std::string& key) {
  const unsigned group = boundary_key_group(key);
  if (group == gas::no_keys) return "";
  const std::string types = types_taking(group);
  if (key == "velocity") return types + " and mode = \"constant\", \"pulse\" or \"pulsation\"";
  if (key == "background" || key == "start" || key == "duration")
    return types + " and mode = \"pulse\"";
  if (key == "amplitude" || key == "frequency") return types + " and mode = \"pulsation\"";
  if (key == "times" || key == "velocities") return types + " and mode = \"table\"";
  return types;
}

bool boundary_key_applies(const std::string& key, gas::BoundaryType t, gas::InflowMode m) {
  const unsigned group = boundary_key_group(key);
  if (group == gas::no_keys) return true;
  if ((gas::boundary_kind(t).keys & group) == 0) return false;
  if (key == "velocity") return m != gas::InflowMode::table;
  if (key == "background" || key == "start" || key == "duration")
    return m == gas::InflowMode::pulse;
  if (key == "amplitude" || key == "frequency") return m == gas::InflowMode::pulsation;
  if (key == "times" || key == "velocities") return m == gas::InflowMode::table;
  return true;
}

/// The case-file key of a key named by gas::validate(): "regions[i]" is "region[i]", and the
/// derived settings are the [simulation] and [domain] keys they come from.
std::string case_key_of_gas_setting(std::string key) {
  if (key == "gas.dimension") return "simulation.dimension";
  if (key == "gas.gravity") return "simulation.gravity";
  if (key == "gas.lo" || key == "gas.hi" || key == "gas.depth") return "domain.hi";
  const std::string from = ".regions[";
  for (auto pos = key.find(from); pos != std::string::npos; pos = key.find(from, pos))
    key.replace(pos, from.size(), ".region[");
  return key;
}

// ---------------------------------------------------------------------------------------------
// Command-line overrides: "path=value" applied to the parsed table before validation.

struct Seg {
  std::string name;
  std::optional<std::size_t> index;
  std::string text; ///< as typed
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::vector<Seg> parse_key_path(const std::string& key) {
  const SourceLocation set{kSetFile, 0, 0};
  const std::string malformed =
      "malformed key (allowed: section.key, species[0].key, species.NAME.key, insert[0].key, "
      "walls.FACE.key)";
  std::vector<Seg> segs;
  std::size_t start = 0;
  while (true) {
    const auto dot = key.find('.', start);
    const std::string part =
        key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    Seg seg{part, std::nullopt, part};
    const auto bracket = part.find('[');
    if (bracket != std::string::npos) {
      const std::string digits = part.substr(bracket + 1, part.size() - bracket - 2);
      if (part.back() != ']' || digits.empty() || digits.size() > 9 ||
          !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        throw InputError(set, key, malformed);
      seg.name = part.substr(0, bracket);
      seg.index = static_cast<std::size_t>(std::stoul(digits));
    }
    if (seg.name.empty()) throw InputError(set, key, malformed);
    segs.push_back(seg);
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return segs;
}

/// Child table `name` of `parent`, created when missing.
toml::table& child_table(toml::table& parent, const std::string& name, const std::string& key,
                         const std::string& shown) {
  if (!parent.contains(name)) parent.insert(name, toml::table{});
  toml::table* t = parent.get_as<toml::table>(name);
  if (t == nullptr)
    throw InputError(SourceLocation{kSetFile, 0, 0}, key,
                     "cannot set a key inside " + shown +
                         ", which is not a table in the case file");
  return *t;
}

/// Applies one override to `root`; returns the canonical key path it set ("species[0].friction").
std::string apply_override(toml::table& root, const std::string& text) {
  const SourceLocation set{kSetFile, 0, 0};
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    throw InputError(set, trim(text), "expected key=value (e.g. simulation.end_time=0.5)");
  const std::string key = trim(text.substr(0, eq));
  const std::string raw = trim(text.substr(eq + 1));
  const std::vector<Seg> segs = parse_key_path(key);

  // Prefix of the key as typed, up to (not including) segment `level`.
  auto typed = [&](std::size_t level) {
    std::string s;
    for (std::size_t i = 0; i < level; ++i) s += segs[i].text + ".";
    return s;
  };
  auto check = [&](std::size_t level, const std::string& schema, const Keys& valid) {
    if (is_table_array(schema, segs[level].name))
      throw InputError(set, key,
                       typed(level) + segs[level].name +
                           " is an array of tables, which --set cannot change (edit the case "
                           "file)");
    if (segs[level].index)
      throw InputError(set, key, typed(level) + segs[level].text + ": not an array");
    if (!contains(valid, segs[level].name))
      throw InputError(set, key, suggestion(typed(level), segs[level].name, valid));
  };

  const std::string& section = segs[0].name;
  if (!contains(root_keys(), section))
    throw InputError(set, key, suggestion("", section, root_keys()));

  toml::table* tbl = nullptr;
  std::string canon;
  std::size_t level = 0;
  if (section == "species" || section == "insert") {
    toml::array* arr = root.get_as<toml::array>(section);
    const std::size_t n = arr ? arr->size() : 0;
    std::size_t idx = 0;
    if (segs[0].index) {
      idx = *segs[0].index;
      level = 1;
    } else if (section == "species" && segs.size() >= 3 && !segs[1].index) {
      Keys names;
      bool found = false;
      for (std::size_t i = 0; i < n; ++i) {
        const auto* t = (*arr)[i].as_table();
        const auto name = t ? t->get_as<std::string>("name") : nullptr;
        if (name == nullptr) continue;
        names.push_back(name->get());
        if (!found && name->get() == segs[1].name) {
          idx = i;
          found = true;
        }
      }
      if (!found)
        throw InputError(set, key,
                         "no species named " + in_quotes(segs[1].name) +
                             (names.empty() ? " (the case has no named [[species]])"
                                            : " (allowed: " + join_quoted(names) + ")"));
      level = 2;
    } else {
      throw InputError(set, key,
                       "needs an index (allowed: " + section + "[N].key, e.g. " + section + "[0]." +
                           (section == "species" ? "friction, or species.NAME.key)" : "count)"));
    }
    if (idx >= n)
      throw InputError(set, key,
                       "index out of range (the case has " + std::to_string(n) + " [[" + section +
                           "]]" + (n ? ", allowed: 0 to " + std::to_string(n - 1) : "") + ")");
    tbl = (*arr)[idx].as_table();
    canon = section + "[" + std::to_string(idx) + "]";
    if (tbl == nullptr) throw InputError(set, key, canon + " is not a table in the case file");
  } else {
    if (segs[0].index) throw InputError(set, key, section + ": not an array");
    tbl = &child_table(root, section, key, section);
    canon = section;
    level = 1;
  }
  if (level >= segs.size())
    throw InputError(set, key,
                     "names a table, not a key (allowed: " + typed(level) +
                         section_keys(section)[0] + ", ...)");

  // The key inside the section, and inside its sub-tables (walls faces, insert regions,
  // gas.solver, gas.boundary.FACE).
  std::string schema = section;
  check(level, schema, section_keys(section));
  while (level + 1 < segs.size()) {
    const std::string& sub = segs[level].name;
    const Keys* inner = subtable_keys(schema, sub);
    if (inner == nullptr)
      throw InputError(set, key, "unknown key (" + typed(level + 1) + " is a value, not a table)");
    tbl = &child_table(*tbl, sub, key, canon + "." + sub);
    canon += "." + sub;
    schema += "." + sub;
    ++level;
    check(level, schema, *inner);
  }
  const std::string& leaf = segs[level].name;
  canon += "." + leaf;

  // The value: TOML if it parses as one, else a bare string.
  std::optional<toml::table> doc;
  try {
    doc = toml::parse("v = " + raw, std::string_view(kSetFile));
  } catch (const toml::parse_error&) {
    doc.reset();
  }
  if (doc && doc->size() == 1 && doc->contains("v")) {
    doc->get("v")->visit([&](const auto& v) { tbl->insert_or_assign(leaf, v); });
  } else {
    tbl->insert_or_assign(leaf, raw);
  }
  return canon;
}

// ---------------------------------------------------------------------------------------------
// The validating reader.

struct Entry {
  const toml::node* node;
  SourceLocation where;
};

bool before(const toml::source_position& a, const toml::source_position& b) {
  return a.line < b.line || (a.line == b.line && a.column < b.column);
}

class Reader {
public:
  Reader(CaseSpec& spec, std::string file, fs::path base, std::set<std::string> overridden)
      : spec_(spec), file_(std::move(file)), base_(std::move(base)),
        overridden_(std::move(overridden)) {}

  void read(const toml::table& root) {
    const SourceLocation file_loc{file_, 0, 0};
    check_keys(root, "", root_keys());
    read_simulation(section(root, "simulation"));
    const toml::table* output = section(root, "output");
    read_output(output);
    const auto domain = section(root, "domain");
    if (!domain)
      throw InputError(file_loc, "domain",
                       "missing required table [domain] (a box with lo and hi, in m)");
    read_domain(*domain);
    read_walls(section(root, "walls"));
    read_species(root);
    read_inserts(root);
    read_contact(section(root, "contact"));
    read_neighbour(section(root, "neighbour"));
    read_parallel(section(root, "parallel"));
    read_hardsphere(section(root, "hardsphere"));
    read_coarse_graining(section(root, "coarse_graining"));
    read_body_force(section(root, "body_force"));
    read_van_der_waals(section(root, "van_der_waals"));
    read_electrostatics(section(root, "electrostatics"));
    read_liquid_bridge(section(root, "liquid_bridge"));
    read_gas(root);
    read_coupling(section(root, "coupling"));
    read_probes(output);
    read_collision_regions(output);
    read_continuum(output);
  }

private:
  CaseSpec& spec_;
  std::string file_;
  fs::path base_;
  std::set<std::string> overridden_;

  bool is_override(const std::string& path) const {
    for (const auto& o : overridden_) {
      if (path == o) return true;
      if (path.size() > o.size() && path.compare(0, o.size(), o) == 0 &&
          (path[o.size()] == '.' || path[o.size()] == '['))
        return true;
    }
    return false;
  }

  SourceLocation loc(const std::string& path, const toml::source_position& p) const {
    if (is_override(path) || p.line == 0) return SourceLocation{kSetFile, 0, 0};
    return SourceLocation{file_, static_cast<long>(p.line), static_cast<long>(p.column)};
  }

  /// Looks up `key` in `t`; records and returns its location ("prefix" + key).
  std::optional<Entry> find(const toml::table& t, const std::string& key, const std::string& path) {
    const auto it = t.find(key);
    if (it == t.end()) return std::nullopt;
    // A "[table]" header starts before its key; a "key = value" starts at the key.
    auto pos = it->first.source().begin;
    const auto node_pos = it->second.source().begin;
    if (node_pos.line > 0 && before(node_pos, pos)) pos = node_pos;
    const SourceLocation where = loc(path, pos);
    spec_.locations[path] = where;
    return Entry{&it->second, where};
  }

  /// Throws for the first (in file order) key of `t` that is not in `valid`.
  void check_keys(const toml::table& t, const std::string& prefix, const Keys& valid) {
    const toml::key* bad = nullptr;
    for (auto&& [k, v] : t) {
      if (contains(valid, std::string(k.str()))) continue;
      if (bad == nullptr || before(k.source().begin, bad->source().begin)) bad = &k;
    }
    if (bad == nullptr) return;
    const std::string name(bad->str());
    throw InputError(loc(prefix + name, bad->source().begin), prefix + name,
                     suggestion("", name, valid));
  }

  /// A top-level table section; nullptr when absent. Checks its keys.
  const toml::table* section(const toml::table& root, const std::string& name) {
    return table(root, name, name, section_keys(name));
  }

  const toml::table* table(const toml::table& parent, const std::string& key,
                           const std::string& path, const Keys& valid) {
    const auto e = find(parent, key, path);
    if (!e) return nullptr;
    const toml::table* t = e->node->as_table();
    if (t == nullptr)
      throw InputError(e->where, path, "expected a table, got " + describe(*e->node));
    check_keys(*t, path + ".", valid);
    return t;
  }

  SourceLocation table_loc(const toml::table* t, const std::string& path) const {
    if (t == nullptr) return SourceLocation{file_, 0, 0};
    return loc(path, t->source().begin);
  }

  [[noreturn]] void missing(const toml::table* t, const std::string& table_path,
                            const std::string& table_shown, const std::string& key,
                            const std::string& what_allowed) const {
    throw InputError(table_loc(t, table_path), table_path + "." + key,
                     "missing required key in " + table_shown + " (" + what_allowed + ")");
  }

  // --- values -----------------------------------------------------------------------------

  double number(const Entry& e, const std::string& path, NumRule r) const {
    const toml::node& n = *e.node;
    double x = 0;
    if (n.is_floating_point())
      x = *n.value<double>();
    else if (n.is_integer())
      x = static_cast<double>(*n.value<std::int64_t>());
    else
      throw InputError(e.where, path,
                       "expected a number, got " + describe(n) + " (allowed: " + allowed(r) + ")");
    const bool inf_allowed = r.bound == Bound::NonNegativeOrInf && x > 0.0;
    if (std::isnan(x) || (std::isinf(x) && !inf_allowed) || !in_bound(x, r.bound))
      throw InputError(e.where, path,
                       format_double(x) + " is out of range (allowed: " + allowed(r) + ")");
    return x;
  }

  void opt_number(const toml::table* t, const std::string& prefix, const std::string& key,
                  NumRule r, double& out) {
    if (t == nullptr) return;
    const std::string path = prefix + "." + key;
    if (const auto e = find(*t, key, path)) out = number(*e, path, r);
  }

  double req_number(const toml::table* t, const std::string& prefix, const std::string& shown,
                    const std::string& key, NumRule r) {
    const std::string path = prefix + "." + key;
    const auto e = t ? find(*t, key, path) : std::nullopt;
    if (!e) missing(t, prefix, shown, key, allowed(r));
    return number(*e, path, r);
  }

  /// A number or the string "auto" (-> empty).
  void auto_number(const toml::table* t, const std::string& prefix, const std::string& key,
                   NumRule r, std::optional<double>& out) {
    if (t == nullptr) return;
    const std::string path = prefix + "." + key;
    const auto e = find(*t, key, path);
    if (!e) return;
    if (const auto s = e->node->value_exact<std::string>()) {
      if (*s != "auto")
        throw InputError(e->where, path,
                         "expected a number or \"auto\", got " + describe(*e->node) +
                             " (allowed: " + allowed(r) + ", or \"auto\")");
      out.reset();
      return;
    }
    if (!e->node->is_number())
      throw InputError(e->where, path,
                       "expected a number or \"auto\", got " + describe(*e->node) +
                           " (allowed: " + allowed(r) + ", or \"auto\")");
    out = number(*e, path, r);
  }

  std::int64_t integer(const Entry& e, const std::string& path, std::int64_t lo,
                       const std::string& what_allowed) const {
    const auto v = e.node->value_exact<std::int64_t>();
    if (!v)
      throw InputError(e.where, path,
                       "expected an integer, got " + describe(*e.node) +
                           " (allowed: " + what_allowed + ")");
    if (*v < lo)
      throw InputError(e.where, path,
                       std::to_string(*v) + " is out of range (allowed: " + what_allowed + ")");
    return *v;
  }

  void opt_bool(const toml::table* t, const std::string& prefix, const std::string& key,
                bool& out) {
    if (t == nullptr) return;
    const std::string path = prefix + "." + key;
    const auto e = find(*t, key, path);
    if (!e) return;
    const auto v = e->node->value_exact<bool>();
    if (!v)
      throw InputError(e->where, path,
                       "expected a boolean, got " + describe(*e->node) +
                           " (allowed: true or false)");
    out = *v;
  }

  std::string str_value(const Entry& e, const std::string& path, const std::string& what) const {
    const auto v = e.node->value_exact<std::string>();
    if (!v)
      throw InputError(e.where, path,
                       "expected a string, got " + describe(*e.node) + " (allowed: " + what + ")");
    return *v;
  }

  template <class E>
  void opt_enum(const toml::table* t, const std::string& prefix, const std::string& key,
                const std::vector<std::pair<std::string, E>>& names, E& out) {
    if (t == nullptr) return;
    const std::string path = prefix + "." + key;
    const auto e = find(*t, key, path);
    if (!e) return;
    Keys valid;
    for (const auto& [name, value] : names) valid.push_back(name);
    const std::string s = str_value(*e, path, "one of " + join_quoted(valid));
    for (const auto& [name, value] : names) {
      if (name == s) {
        out = value;
        return;
      }
    }
    throw InputError(e->where, path,
                     "unknown value " + in_quotes(s) + " (allowed: " + join_quoted(valid) + ")");
  }

  /// An array of three numbers.
  std::array<double, 3> vec3(const Entry& e, const std::string& path, NumRule r) const {
    return vec<3>(e, path, r);
  }

  /// An array of N numbers.
  template <std::size_t N>
  std::array<double, N> vec(const Entry& e, const std::string& path, NumRule r) const {
    const std::string what = "an array of " + std::to_string(N) + " numbers" +
                             std::string(*r.unit ? ", in " : "") + r.unit;
    const toml::array* a = e.node->as_array();
    if (a == nullptr || a->size() != N)
      throw InputError(e.where, path,
                       "expected " + what + ", got " + describe(*e.node) + " (allowed: " + what +
                           ")");
    std::array<double, N> out{};
    for (std::size_t i = 0; i < N; ++i) {
      const toml::node& n = *a->get(i);
      const std::string elem = path + "[" + std::to_string(i) + "]";
      const SourceLocation where =
          n.source().begin.line > 0 ? loc(path, n.source().begin) : e.where;
      out[i] = number(Entry{&n, where}, elem, r);
    }
    return out;
  }

  /// An array of any number (>= 1) of numbers.
  void opt_numbers(const toml::table* t, const std::string& prefix, const std::string& key,
                   NumRule r, std::vector<double>& out) {
    if (t == nullptr) return;
    const std::string path = prefix + "." + key;
    const auto e = find(*t, key, path);
    if (!e) return;
    const std::string what = "an array of numbers" + std::string(*r.unit ? ", in " : "") + r.unit;
    const toml::array* a = e->node->as_array();
    if (a == nullptr || a->empty())
      throw InputError(e->where, path,
                       "expected " + what + ", got " + describe(*e->node) + " (allowed: " + what +
                           ")");
    out.clear();
    for (std::size_t i = 0; i < a->size(); ++i) {
      const toml::node& n = *a->get(i);
      const SourceLocation where =
          n.source().begin.line > 0 ? loc(path, n.source().begin) : e->where;
      out.push_back(number(Entry{&n, where}, path + "[" + std::to_string(i) + "]", r));
    }
  }

  void opt_vec3(const toml::table* t, const std::string& prefix, const std::string& key, NumRule r,
                std::array<double, 3>& out) {
    if (t == nullptr) return;
    const std::string path = prefix + "." + key;
    if (const auto e = find(*t, key, path)) out = vec3(*e, path, r);
  }

  /// Checks hi > lo on every axis.
  void check_box(const SourceLocation& where, const std::string& hi_path,
                 const std::array<double, 3>& lo, const std::array<double, 3>& hi) const {
    static const char* axis = "xyz";
    for (std::size_t i = 0; i < 3; ++i) {
      if (!(hi[i] > lo[i]))
        throw InputError(where, hi_path,
                         std::string("hi[") + std::to_string(i) + "] = " + format_double(hi[i]) +
                             " is not greater than lo[" + std::to_string(i) +
                             "] = " + format_double(lo[i]) + " on the " + axis[i] +
                             " axis (allowed: hi > lo on every axis)");
    }
  }

  /// The material keys of `t` (prefix: "species[i]", "walls" or "walls.FACE") over `m` (the
  /// defaults, or a face's [walls] values). Walls may be rigid (youngs_modulus = "rigid").
  void read_material(const toml::table* t, const std::string& prefix, MaterialSpec& m) {
    const bool wall = prefix.starts_with("walls");
    const NumRule modulus{Bound::Positive, "Pa"};
    std::optional<Entry> e_entry, nu_entry, g_entry;
    if (t != nullptr) {
      e_entry = find(*t, "youngs_modulus", prefix + ".youngs_modulus");
      nu_entry = find(*t, "poisson_ratio", prefix + ".poisson_ratio");
      g_entry = find(*t, "shear_modulus", prefix + ".shear_modulus");
    }
    if (e_entry) {
      const std::string path = prefix + ".youngs_modulus";
      const std::string rule = allowed(modulus) + (wall ? ", or \"rigid\" (infinitely stiff)"
                                                        : " (only walls can be "
                                                          "\"rigid\")");
      if (const auto s = e_entry->node->value_exact<std::string>()) {
        if (!wall || *s != "rigid")
          throw InputError(e_entry->where, path,
                           "expected a number, got " + describe(*e_entry->node) +
                               " (allowed: " + rule + ")");
        m.youngs_modulus = std::numeric_limits<double>::infinity();
      } else {
        m.youngs_modulus = number(*e_entry, path, modulus);
      }
    }
    if (nu_entry && g_entry)
      throw InputError(g_entry->where, prefix + ".shear_modulus",
                       "not allowed together with poisson_ratio (at " + nu_entry->where.str() +
                           "): give one of them (G = E / (2 (1 + nu)))");
    if (nu_entry) {
      m.poisson_ratio = number(*nu_entry, prefix + ".poisson_ratio", {Bound::Poisson, ""});
      m.shear_modulus.reset();
    }
    if (g_entry) m.shear_modulus = number(*g_entry, prefix + ".shear_modulus", modulus);
    if (m.shear_modulus) {
      // nu from E and G; a face that inherits G from [walls] and overrides E is checked too.
      const auto& at = g_entry ? g_entry : e_entry;
      const SourceLocation where = at ? at->where : spec_.where(prefix + ".shear_modulus");
      const std::string path =
          prefix + (g_entry || !e_entry ? ".shear_modulus" : ".youngs_modulus");
      const double g = *m.shear_modulus, e = m.youngs_modulus;
      if (std::isinf(e))
        throw InputError(where, path,
                         "a rigid wall (youngs_modulus = \"rigid\") takes no shear_modulus: it has "
                         "no compliance (allowed: a finite youngs_modulus with the shear_modulus, "
                         "or \"rigid\" alone)");
      const double nu = e / (2.0 * g) - 1.0;
      if (!(nu >= 0.0 && nu < 0.5))
        throw InputError(where, path,
                         "shear_modulus G = " + format_double(g) +
                             " Pa with youngs_modulus E = " + format_double(e) +
                             " Pa gives poisson_ratio E/(2G) - 1 = " + format_double(nu) +
                             " (allowed: G in (E/3, E/2], i.e. poisson_ratio in "
                             "[0, 0.5))");
      m.poisson_ratio = nu;
    }
    opt_number(t, prefix, "restitution", {Bound::Unit, ""}, m.restitution);
    opt_number(t, prefix, "friction", {Bound::NonNegativeOrInf, ""}, m.friction);
    opt_number(t, prefix, "tangential_restitution", {Bound::Unit, ""}, m.tangential_restitution);
    opt_number(t, prefix, "rolling_friction", {Bound::NonNegative, ""}, m.rolling_friction);
  }

  /// The array of tables `name` ([[species]], [[insert]]), at least one element.
  const toml::array& table_array(const toml::table& root, const std::string& name,
                                 const std::string& what) {
    const SourceLocation file_loc{file_, 0, 0};
    const auto e = find(root, name, name);
    const std::string need = "at least one [[" + name + "]] table, " + what;
    if (!e) throw InputError(file_loc, name, "missing required [[" + name + "]] (" + need + ")");
    const toml::array* a = e->node->as_array();
    if (a == nullptr)
      throw InputError(e->where, name,
                       "expected an array of tables [[" + name + "]], got " + describe(*e->node) +
                           " (allowed: " + need + ")");
    if (a->empty()) throw InputError(e->where, name, "is empty (allowed: " + need + ")");
    check_table_elements(*a, *e, name, section_keys(name), need);
    return *a;
  }

  /// Checks that every element of the array of tables at `path` is a table with `valid` keys;
  /// records the location of each, "path[i]".
  void check_table_elements(const toml::array& a, const Entry& e, const std::string& path,
                            const Keys& valid, const std::string& need) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      const toml::node& n = *a.get(i);
      const std::string ip = path + "[" + std::to_string(i) + "]";
      if (!n.is_table())
        throw InputError(n.source().begin.line > 0 ? loc(ip, n.source().begin) : e.where, ip,
                         "expected a table, got " + describe(n) + " (allowed: " + need + ")");
      spec_.locations[ip] = n.source().begin.line > 0 ? loc(ip, n.source().begin) : e.where;
      check_keys(*n.as_table(), ip + ".", valid);
    }
  }

  /// The optional array of tables `key` of `parent` (e.g. [[output.probe]]); nullptr when absent.
  const toml::array* opt_table_array(const toml::table& parent, const std::string& key,
                                     const std::string& path, const std::string& shown,
                                     const Keys& valid, const std::string& what) {
    const auto e = find(parent, key, path);
    if (!e) return nullptr;
    const std::string need = "[[" + shown + "]] tables, " + what;
    const toml::array* a = e->node->as_array();
    if (a == nullptr)
      throw InputError(e->where, path,
                       "expected an array of tables [[" + shown + "]], got " + describe(*e->node) +
                           " (allowed: " + need + ")");
    check_table_elements(*a, *e, path, valid, need);
    return a;
  }

  /// An integer in [lo, INT_MAX].
  int int_value(const Entry& e, const std::string& path, int lo, const std::string& what) const {
    const std::int64_t v = integer(e, path, lo, what);
    if (v > std::numeric_limits<int>::max())
      throw InputError(e.where, path,
                       std::to_string(v) + " is out of range (allowed: " + what + ")");
    return static_cast<int>(v);
  }

  // --- sections ---------------------------------------------------------------------------

  void read_simulation(const toml::table* t) {
    SimulationSpec& s = spec_.simulation;
    const std::string p = "simulation";
    opt_enum<Engine>(t, p, "engine",
                     {{"soft_sphere", Engine::SoftSphere}, {"hard_sphere", Engine::HardSphere}},
                     s.engine);
    if (t != nullptr) {
      if (const auto e = find(*t, "dimension", p + ".dimension")) {
        const auto d =
            integer(*e, p + ".dimension", std::numeric_limits<std::int64_t>::min(), "2 or 3");
        if (d != 2 && d != 3)
          throw InputError(e->where, p + ".dimension",
                           std::to_string(d) + " is not a valid dimension (allowed: 2 or 3)");
        s.dimension = static_cast<int>(d);
      }
    }
    s.end_time = req_number(t, p, "[simulation]", "end_time", kTime);
    auto_number(t, p, "time_step", kTime, s.time_step);
    opt_number(t, p, "time_step_fraction", {Bound::HalfOpenUnit, ""}, s.time_step_fraction);
    opt_bool(t, p, "force_time_step", s.force_time_step);
    opt_vec3(t, p, "gravity", {Bound::Any, "m/s^2"}, s.gravity);
    opt_number(t, p, "insertion_overlap_tolerance", {Bound::NonNegative, ""},
               s.insertion_overlap_tolerance);
    if (s.dimension == 2 && s.gravity[1] != 0.0)
      throw InputError(spec_.where("simulation.gravity"), "simulation.gravity",
                       "y component " + format_double(s.gravity[1]) +
                           " is not 0 in dimension 2 (allowed: gravity in the x-z plane, "
                           "[gx, 0, gz])");
  }

  void read_output(const toml::table* t) {
    opt_number(t, "output", "frame_interval", kTime, spec_.output.frame_interval);
    opt_number(t, "output", "series_interval", kTime, spec_.output.series_interval);
    opt_number(t, "output", "checkpoint_interval", kTime, spec_.output.checkpoint_interval);
    if (t != nullptr)
      if (const auto e = find(*t, "layers", "output.layers"))
        spec_.output.layers = int_value(*e, "output.layers", 0, "an integer >= 0 (0: off)");
    opt_bool(t, "output", "collisions", spec_.output.collisions);
    opt_bool(t, "output", "analyse", spec_.output.analyse);
  }

  void read_domain(const toml::table& t) {
    DomainSpec& d = spec_.domain;
    const NumRule any_m{Bound::Any, "m"};
    for (const char* key : {"lo", "hi"}) {
      const std::string path = std::string("domain.") + key;
      const auto e = find(t, key, path);
      if (!e) missing(&t, "domain", "[domain]", key, "an array of 3 numbers, in m");
      (std::string(key) == "lo" ? d.lo : d.hi) = vec3(*e, path, any_m);
    }
    check_box(spec_.where("domain.hi"), "domain.hi", d.lo, d.hi);
    for (std::size_t i = 0; i < 3; ++i) {
      // Both ends finite but the width is not (lo = -1e308, hi = 1e308): insertion and the
      // neighbour grid divide the width into cells.
      if (!std::isfinite(d.hi[i] - d.lo[i]))
        throw InputError(spec_.where("domain.hi"), "domain.hi",
                         "the width hi[" + std::to_string(i) + "] - lo[" + std::to_string(i) +
                             "] = " + format_double(d.hi[i]) + " - " + format_double(d.lo[i]) +
                             " is not a finite number (allowed: a box of finite width, in m)");
    }
    if (const auto e = find(t, "periodic", "domain.periodic")) {
      const std::string what = "an array of 3 booleans";
      const toml::array* a = e->node->as_array();
      if (a == nullptr || a->size() != 3)
        throw InputError(e->where, "domain.periodic",
                         "expected " + what + ", got " + describe(*e->node) + " (allowed: " + what +
                             ")");
      for (std::size_t i = 0; i < 3; ++i) {
        const auto v = a->get(i)->value_exact<bool>();
        if (!v)
          throw InputError(e->where, "domain.periodic",
                           "element " + std::to_string(i) + " is " + describe(*a->get(i)) +
                               " (allowed: " + what + ")");
        d.periodic[i] = *v;
      }
    }
  }

  void read_walls(const toml::table* t) {
    MaterialSpec base;
    read_material(t, "walls", base);
    for (std::size_t f = 0; f < kFaceNames.size(); ++f) {
      const std::string face = kFaceNames[f];
      MaterialSpec m = base;
      if (t != nullptr) {
        const toml::table* ft = table(*t, face, "walls." + face, material_keys());
        read_material(ft, "walls." + face, m);
      }
      spec_.domain.wall_material[f] = m;
    }
  }

  void read_species(const toml::table& root) {
    const toml::array& arr =
        table_array(root, "species", "each with a name, a diameter and a density");
    std::unordered_map<std::string, int> index; // names seen: the check is linear in the count
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const toml::table* t = arr.get(i)->as_table();
      const std::string p = "species[" + std::to_string(i) + "]";
      SpeciesSpec s;
      const auto name = find(*t, "name", p + ".name");
      const std::string name_rule = "a non-empty name, unique among the [[species]]";
      if (!name) missing(t, p, "[[species]] " + p, "name", name_rule);
      s.name = str_value(*name, p + ".name", name_rule);
      if (s.name.empty())
        throw InputError(name->where, p + ".name", "is empty (allowed: " + name_rule + ")");
      const auto [seen, fresh] = index.emplace(s.name, static_cast<int>(i));
      const int other = seen->second;
      if (!fresh)
        throw InputError(name->where, p + ".name",
                         "duplicate species name " + in_quotes(s.name) + ", also species[" +
                             std::to_string(other) + "] at " +
                             spec_.where("species[" + std::to_string(other) + "].name").str() +
                             " (allowed: " + name_rule + ")");
      s.diameter = req_number(t, p, "[[species]] " + p, "diameter", kLength);
      s.density = req_number(t, p, "[[species]] " + p, "density", {Bound::Positive, "kg/m^3"});
      opt_number(t, p, "charge", {Bound::Any, "C"}, s.charge);
      opt_number(t, p, "liquid_fraction", {Bound::NonNegative, ""}, s.liquid_fraction);
      // Willett's fit holds for bridge volumes 1e-5 <= V/R^3 <= 0.1: with the liquid shared
      // among 1 to 12 bridges between equal spheres, V/R^3 lies in [0.7, 8.4] x the fraction.
      if (s.liquid_fraction != 0.0 && (s.liquid_fraction < 2e-5 || s.liquid_fraction > 0.01))
        throw InputError(spec_.where(p + ".liquid_fraction"), p + ".liquid_fraction",
                         format_double(s.liquid_fraction) +
                             " is out of range (allowed: 0 (dry), or 2e-5 to 0.01 of the particle "
                             "volume, where the bridges stay in the range of Willett's capillary "
                             "force, 1e-5 <= V/R^3 <= 0.1)");
      read_material(t, p, s.material);
      spec_.species.push_back(s);
    }
  }

  void read_inserts(const toml::table& root) {
    const toml::array& arr =
        table_array(root, "insert", "each naming a species and a count or a file");
    Keys names;
    for (const auto& s : spec_.species) names.push_back(s.name);
    const NumRule any_m{Bound::Any, "m"};
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const toml::table* t = arr.get(i)->as_table();
      const std::string p = "insert[" + std::to_string(i) + "]";
      const std::string shown = "[[insert]] " + p;
      InsertSpec in;

      const auto species = find(*t, "species", p + ".species");
      const std::string species_rule = "one of " + join_quoted(names);
      if (!species) missing(t, p, shown, "species", "the name of a [[species]]: " + species_rule);
      in.species = str_value(*species, p + ".species", species_rule);
      if (spec_.species_index(in.species) < 0)
        throw InputError(species->where, p + ".species",
                         "unknown species " + in_quotes(in.species) + " (allowed: " + species_rule +
                             ")");

      opt_enum<Placement>(t, p, "placement",
                          {{"random", Placement::Random},
                           {"lattice", Placement::Lattice},
                           {"file", Placement::File}},
                          in.placement);
      const bool from_file = in.placement == Placement::File;

      const auto count = find(*t, "count", p + ".count");
      if (from_file && count)
        throw InputError(count->where, p + ".count",
                         "not allowed with placement = \"file\" (the file lists the particles)");
      if (!from_file) {
        if (!count) missing(t, p, shown, "count", "an integer >= 1");
        // At most INT_MAX: insertion counts attempts as a multiple of the count.
        in.count = int_value(*count, p + ".count", 1, "an integer >= 1, at most 2147483647");
      }

      const auto file = find(*t, "file", p + ".file");
      if (!from_file && file)
        throw InputError(file->where, p + ".file",
                         std::string("not allowed with placement = \"") + to_string(in.placement) +
                             "\" (only with placement = \"file\")");
      if (from_file) {
        const std::string rule =
            "a LAMMPS data file, relative to the case file's folder or absolute";
        if (!file) missing(t, p, shown, "file", rule + ", required with placement = \"file\"");
        const std::string given = str_value(*file, p + ".file", rule);
        if (given.empty())
          throw InputError(file->where, p + ".file", "is empty (allowed: " + rule + ")");
        fs::path path(given);
        if (path.is_relative()) path = base_ / path;
        std::error_code ec;
        path = fs::absolute(path, ec).lexically_normal();
        if (ec)
          throw InputError(file->where, p + ".file",
                           "file not found: " + path.string() + " (allowed: " + rule + ")");
        if (const auto problem = input_file_problem(path.string()))
          throw InputError(file->where, p + ".file",
                           (*problem == "does not exist" ? "file not found: " + path.string()
                                                         : path.string() + " " + *problem) +
                               " (allowed: " + rule + ")");
        in.file = path.string();
      }

      in.region_lo = spec_.domain.lo;
      in.region_hi = spec_.domain.hi;
      if (const toml::table* region = table(*t, "region", p + ".region", region_keys())) {
        opt_vec3(region, p + ".region", "lo", any_m, in.region_lo);
        opt_vec3(region, p + ".region", "hi", any_m, in.region_hi);
        const SourceLocation where = spec_.where(p + ".region.hi");
        check_box(where, p + ".region.hi", in.region_lo, in.region_hi);
        for (std::size_t a = 0; a < 3; ++a) {
          const bool lo_out = in.region_lo[a] < spec_.domain.lo[a];
          const bool hi_out = in.region_hi[a] > spec_.domain.hi[a];
          if (lo_out || hi_out) {
            const std::string which = lo_out ? "lo" : "hi";
            const double v = lo_out ? in.region_lo[a] : in.region_hi[a];
            throw InputError(spec_.where(p + ".region." + which), p + ".region." + which,
                             which + "[" + std::to_string(a) + "] = " + format_double(v) +
                                 " is outside the domain (allowed: a box inside the domain, " +
                                 format_double(spec_.domain.lo[a]) + " <= x <= " +
                                 format_double(spec_.domain.hi[a]) + " on this axis)");
          }
        }
      }
      opt_vec3(t, p, "velocity", {Bound::Any, "m/s"}, in.velocity);
      opt_number(t, p, "velocity_spread", {Bound::NonNegative, "m/s"}, in.velocity_spread);
      opt_vec3(t, p, "angular_velocity", {Bound::Any, "rad/s"}, in.angular_velocity);
      // Discs moving in the x-z plane turn about y only: a spin about x or z would tilt them
      // out of the plane, which the 2-D run cannot represent.
      if (spec_.simulation.dimension == 2 &&
          (in.angular_velocity[0] != 0.0 || in.angular_velocity[2] != 0.0))
        throw InputError(spec_.where(p + ".angular_velocity"), p + ".angular_velocity",
                         "[" + format_double(in.angular_velocity[0]) + ", " +
                             format_double(in.angular_velocity[1]) + ", " +
                             format_double(in.angular_velocity[2]) +
                             "] rad/s: in a 2-D run the discs move in the x-z plane and turn "
                             "about y only (allowed: [0, w_y, 0])");
      opt_bool(t, p, "fixed", in.fixed);
      if (t->contains("charge")) {
        double q = 0.0;
        opt_number(t, p, "charge", {Bound::Any, "C"}, q);
        in.charge = q;
      }
      if (in.fixed) { // a fixed particle never moves: no initial motion to give it
        const auto moving = [](const std::array<double, 3>& v) {
          return v[0] != 0.0 || v[1] != 0.0 || v[2] != 0.0;
        };
        const char* key = moving(in.velocity)           ? "velocity"
                          : in.velocity_spread > 0.0    ? "velocity_spread"
                          : moving(in.angular_velocity) ? "angular_velocity"
                                                        : nullptr;
        if (key)
          throw InputError(spec_.where(p + "." + key), p + "." + key,
                           std::string("must be 0 with fixed = true (fixed particles never move "
                                       "or turn)"));
      }
      if (const auto seed = find(*t, "seed", p + ".seed"))
        in.seed = static_cast<std::uint64_t>(integer(*seed, p + ".seed", 0, "an integer >= 0"));
      const std::string sd = p + ".size_distribution";
      if (const toml::table* d = table(*t, "size_distribution", sd, size_distribution_keys())) {
        if (from_file)
          throw InputError(spec_.where(sd), sd,
                           "not allowed with placement = \"file\" (the file gives each "
                           "particle's diameter; allowed: placement = \"random\" or "
                           "\"lattice\")");
        in.size_distribution = read_size_distribution(*d, sd);
      }
      spec_.inserts.push_back(in);
    }
  }

  /// An [[insert]] size_distribution (docs/case-file.md): its kind's keys, every diameter the
  /// distribution can reach positive, min < max, a table's diameters increasing with its CDF
  /// non-decreasing from 0 to 1, discrete fractions summing to 1 (both within 1e-6; the sampler
  /// divides by the sum).
  SizeDistributionSpec read_size_distribution(const toml::table& t, const std::string& p) {
    using Kind = SizeDistributionSpec::Kind;
    using Basis = SizeDistributionSpec::Basis;
    SizeDistributionSpec d;
    const std::string shown = "[insert.size_distribution] of " + p;
    const auto kind = find(t, "kind", p + ".kind");
    const Keys kinds = {"normal", "log_normal", "table", "discrete"};
    if (!kind) missing(&t, p, shown, "kind", "one of " + join_quoted(kinds));
    opt_enum<Kind>(&t, p, "kind",
                   {{"normal", Kind::Normal},
                    {"log_normal", Kind::LogNormal},
                    {"table", Kind::Table},
                    {"discrete", Kind::Discrete}},
                   d.kind);
    opt_enum<Basis>(&t, p, "basis", {{"number", Basis::Number}, {"mass", Basis::Mass}}, d.basis);
    const std::string kind_name = *kind->node->value_exact<std::string>();
    const Keys own = d.kind == Kind::Normal      ? Keys{"mean", "std", "min", "max"}
                     : d.kind == Kind::LogNormal ? Keys{"median", "geometric_std", "min", "max"}
                     : d.kind == Kind::Table     ? Keys{"diameters", "cumulative"}
                                                 : Keys{"diameters", "fractions"};
    for (auto&& [k, v] : t) {
      const std::string name(k.str());
      if (name == "kind" || name == "basis" || contains(own, name)) continue;
      throw InputError(loc(p + "." + name, k.source().begin), p + "." + name,
                       "not a key of kind = " + in_quotes(kind_name) + " (allowed: kind, basis, " +
                           join_quoted(own) + ")");
    }
    const NumRule length{Bound::Positive, "m"};
    if (d.kind == Kind::Normal || d.kind == Kind::LogNormal) {
      const bool normal = d.kind == Kind::Normal;
      if (normal) {
        d.mean = req_number(&t, p, shown, "mean", length);
        d.std = req_number(&t, p, shown, "std", length);
        d.min = d.mean - 3.0 * d.std, d.max = d.mean + 3.0 * d.std;
      } else {
        d.median = req_number(&t, p, shown, "median", length);
        const std::string gp = p + ".geometric_std";
        const auto g = find(t, "geometric_std", gp);
        if (!g) missing(&t, p, shown, "geometric_std", "a number > 1");
        d.geometric_std = number(*g, gp, {Bound::AtLeastOne, ""});
        if (!(d.geometric_std > 1.0))
          throw InputError(g->where, gp,
                           format_double(d.geometric_std) +
                               " is out of range (allowed: a number > 1; 1 is one diameter: "
                               "leave size_distribution out)");
        const double s3 = std::pow(d.geometric_std, 3.0);
        d.min = d.median / s3, d.max = d.median * s3;
      }
      const bool min_given = t.contains("min");
      opt_number(&t, p, "min", length, d.min);
      opt_number(&t, p, "max", length, d.max);
      if (!(d.min > 0.0))
        throw InputError(spec_.where(p + ".std"), p + ".std",
                         "mean - 3 std = " + format_double(d.min) +
                             " m: the distribution reaches d <= 0 (allowed: give min > 0, or a "
                             "smaller std)");
      if (!(d.max > d.min))
        throw InputError(spec_.where(p + (t.contains("max") ? ".max" : ".min")),
                         p + (t.contains("max") ? ".max" : ".min"),
                         "min = " + format_double(d.min) + " m, max = " + format_double(d.max) +
                             " m (allowed: 0 < min < max" +
                             (min_given || t.contains("max")
                                  ? std::string(")")
                                  : std::string(", defaults ") +
                                        (normal ? "mean -+ 3 std)" : "median /* sigma_g^3)")));
      return d;
    }
    const std::string second = d.kind == Kind::Table ? "cumulative" : "fractions";
    std::vector<double>& values = d.kind == Kind::Table ? d.cumulative : d.fractions;
    if (!t.contains("diameters"))
      missing(&t, p, shown, "diameters", "an array of increasing diameters > 0, in m");
    if (!t.contains(second)) missing(&t, p, shown, second, "an array of numbers, one per diameter");
    opt_numbers(&t, p, "diameters", length, d.diameters);
    opt_numbers(&t, p, second, {Bound::NonNegative, ""}, values);
    for (std::size_t i = 1; i < d.diameters.size(); ++i)
      if (!(d.diameters[i] > d.diameters[i - 1]))
        throw InputError(spec_.where(p + ".diameters"), p + ".diameters",
                         "diameters[" + std::to_string(i) + "] = " + format_double(d.diameters[i]) +
                             " m is not above diameters[" + std::to_string(i - 1) +
                             "] = " + format_double(d.diameters[i - 1]) +
                             " m (allowed: strictly increasing diameters > 0)");
    const std::string vp = p + "." + second;
    if (values.size() != d.diameters.size())
      throw InputError(spec_.where(vp), vp,
                       std::to_string(values.size()) + " values for " +
                           std::to_string(d.diameters.size()) +
                           " diameters (allowed: one per diameter)");
    if (d.kind == Kind::Table) {
      if (d.diameters.size() < 2)
        throw InputError(spec_.where(p + ".diameters"), p + ".diameters",
                         "one point (allowed: at least two points of the CDF)");
      for (std::size_t i = 1; i < values.size(); ++i)
        if (values[i] < values[i - 1])
          throw InputError(spec_.where(vp), vp,
                           "cumulative[" + std::to_string(i) + "] = " + format_double(values[i]) +
                               " is below cumulative[" + std::to_string(i - 1) +
                               "] (allowed: non-decreasing from 0 to 1)");
      if (values.front() != 0.0 || std::fabs(values.back() - 1.0) > 1e-6)
        throw InputError(spec_.where(vp), vp,
                         "runs from " + format_double(values.front()) + " to " +
                             format_double(values.back()) +
                             " (allowed: from 0 at the smallest diameter to 1 within 1e-6 at the "
                             "largest)");
    } else {
      double sum = 0.0;
      for (const double f : values) sum += f;
      if (std::fabs(sum - 1.0) > 1e-6)
        throw InputError(spec_.where(vp), vp,
                         "the fractions sum to " + format_double(sum) +
                             " (allowed: fractions >= 0 summing to 1 within 1e-6)");
    }
    return d;
  }

  /// [contact]: the sub-models and their coefficients, as the models declare them
  /// (contact/contact_models.hpp), then the keys of every model.
  void read_contact(const toml::table* t) {
    namespace cm = contact_models;
    ContactSpec& c = spec_.contact;
    const std::string p = "contact";
    for (const cm::Kind kind : cm::kKinds) {
      std::vector<std::pair<std::string, const cm::ModelInfo*>> names;
      for (const cm::ModelInfo& m : cm::models(kind)) names.emplace_back(m.name, &m);
      const cm::ModelInfo* chosen = &cm::default_model(kind);
      opt_enum<const cm::ModelInfo*>(t, p, cm::kind_key(kind), names, chosen);
      cm::of(c, kind) = ContactModelSpec{std::string(chosen->name), {}};
    }
    const cm::Chosen chosen = cm::choose(spec_);
    for (const cm::Kind kind : cm::kKinds)
      for (const cm::Coefficient& k : chosen.of(kind).coefficients)
        read_coefficient(t, chosen.of(kind), k, cm::of(c, kind).coefficients);
    // The coefficients of models not chosen: "auto" (which every model takes for a key that may
    // be "auto": nothing given), or refused.
    for (const std::string& key : cm::coefficient_keys()) {
      const auto e = t && !chosen.declaring(key) ? find(*t, key, p + "." + key) : std::nullopt;
      if (!e || (cm::auto_allowed(key) && e->node->value_exact<std::string>() == "auto")) continue;
      throw InputError(e->where, p + "." + key, cm::not_taken(key, chosen));
    }
    if (chosen.normal->refusal.empty() && !chosen.normal->takes_elastic_constants)
      check_elastic_constants_unused(*chosen.normal);
    auto_number(t, p, "characteristic_velocity", {Bound::Positive, "m/s"},
                c.characteristic_velocity);
    opt_number(t, p, "max_overlap", {Bound::OpenUnit, ""}, c.max_overlap);
  }

  /// Coefficient `k` of model `m` into `out` (absent: "auto", or not given).
  void read_coefficient(const toml::table* t, const contact_models::ModelInfo& m,
                        const contact_models::Coefficient& k, contact_models::Coefficients& out) {
    namespace cm = contact_models;
    const std::string key(k.key), path = "contact." + key;
    const auto e = t ? find(*t, key, path) : std::nullopt;
    const std::string rule = cm::allowed(k);
    if (!e) {
      if (k.given == cm::Given::Required && m.refusal.empty())
        missing(t, "contact", "[contact]", key,
                rule + ", required with " + cm::kind_key(m.kind) + " = " +
                    in_quotes(std::string(m.name)));
      return;
    }
    const bool may_be_auto = k.given != cm::Given::Required;
    const std::string allowed_values = rule + (may_be_auto ? ", or \"auto\"" : "");
    if (const auto s = e->node->value_exact<std::string>(); s && may_be_auto) {
      if (*s == "auto") return;
      throw InputError(e->where, path,
                       "expected a number or \"auto\", got " + describe(*e->node) +
                           " (allowed: " + allowed_values + ")");
    }
    if (!e->node->is_number())
      throw InputError(e->where, path,
                       std::string(may_be_auto ? "expected a number or \"auto\", got "
                                               : "expected a number, got ") +
                           describe(*e->node) + " (allowed: " + allowed_values + ")");
    const double x = e->node->is_floating_point()
                         ? *e->node->value<double>()
                         : static_cast<double>(*e->node->value<std::int64_t>());
    if (!k.range.contains(x))
      throw InputError(e->where, path,
                       format_double(x) + " is out of range (allowed: " + rule + ")");
    if (k.given == cm::Given::AutoOnly) throw InputError(e->where, path, cm::only_auto(m, k));
    out[key] = x;
  }

  /// A normal model whose stiffnesses are its own coefficients takes no elastic constants:
  /// refuse the material keys that would only act with the models that do (a shear modulus, a
  /// rigid wall) instead of ignoring them. (youngs_modulus and poisson_ratio, which every
  /// material has, are unused.)
  void check_elastic_constants_unused(const contact_models::ModelInfo& normal) const {
    const std::string why = contact_models::elastic_constants_not_taken(normal);
    for (std::size_t i = 0; i < spec_.species.size(); ++i)
      if (spec_.species[i].material.shear_modulus) {
        const std::string key = "species[" + std::to_string(i) + "].shear_modulus";
        throw InputError(spec_.where(key), key, why);
      }
    for (int f = 0; f < 6; ++f) {
      if (spec_.domain.periodic[f / 2] || (spec_.simulation.dimension == 2 && f / 2 == 1))
        continue; // no contacts on this face
      const MaterialSpec& m = spec_.domain.wall_material[f];
      // The face's own key, or the [walls] one it inherits.
      auto key_of = [&](const std::string& k) {
        const std::string face = std::string("walls.") + kFaceNames[f] + "." + k;
        return spec_.locations.contains(face) ? face : "walls." + k;
      };
      if (m.shear_modulus)
        throw InputError(spec_.where(key_of("shear_modulus")), key_of("shear_modulus"), why);
      if (std::isinf(m.youngs_modulus))
        throw InputError(spec_.where(key_of("youngs_modulus")), key_of("youngs_modulus"),
                         "= \"rigid\" " + why);
    }
  }

  void read_neighbour(const toml::table* t) {
    auto_number(t, "neighbour", "skin", kLength, spec_.neighbour.skin);
    if (t != nullptr)
      if (const auto e = find(*t, "sort_interval", "neighbour.sort_interval"))
        spec_.neighbour.sort_interval =
            int_value(*e, "neighbour.sort_interval", 0,
                      "an integer >= 0: neighbour-list rebuilds between spatial sorts, 0: never");
  }

  void read_parallel(const toml::table* t) {
    if (t == nullptr) return;
    ParallelSpec& par = spec_.parallel;
    const std::string p = "parallel";
    if (const auto e = find(*t, "rank_independent", p + ".rank_independent")) {
      const auto b = e->node->value_exact<bool>();
      const auto s = e->node->value_exact<std::string>();
      if (!b && !(s && *s == "auto"))
        throw InputError(e->where, p + ".rank_independent",
                         "expected true, false or \"auto\", got " + describe(*e->node) +
                             " (allowed: true: results that do not depend on the number of "
                             "ranks, also on one; false: the single-process engine; \"auto\": "
                             "true when mpirun started the run)");
      if (b)
        par.rank_independent = *b;
      else
        par.rank_independent.reset();
    }
    if (const auto e = find(*t, "process_grid", p + ".process_grid")) {
      const auto s = e->node->value_exact<std::string>();
      if (s && *s == "auto")
        par.process_grid = {0, 0, 0};
      else
        par.process_grid = int3(*e, p + ".process_grid",
                                "an array of 3 integers [px, py, pz] >= 1 whose product is the "
                                "number of ranks, or \"auto\"");
    }
    if (const auto e = find(*t, "balance_interval", p + ".balance_interval"))
      par.balance_interval = static_cast<int>(
          int_value(*e, p + ".balance_interval", 0,
                    "an integer >= 0: neighbour-list builds between moves of the ranks' cut "
                    "planes to the measured cost, 0: never"));
  }

  void read_hardsphere(const toml::table* t) {
    HardSphereSpec& h = spec_.hardsphere;
    opt_number(t, "hardsphere", "tc_time", {Bound::NonNegative, "s"}, h.tc_time);
    auto_number(t, "hardsphere", "elastic_below", {Bound::NonNegative, "m/s"}, h.elastic_below);
    opt_number(t, "hardsphere", "max_events_per_particle", {Bound::AtLeastOne, ""},
               h.max_events_per_particle);
  }

  /// `[coarse_graining]` [Chang08 §2.2.3] (docs/coarse-graining.md). What it does not go with
  /// is refused at set-up (integrate/coarse_graining.hpp), which knows the models.
  void read_coarse_graining(const toml::table* t) {
    if (t == nullptr) return;
    CoarseGrainingSpec& c = spec_.coarse_graining;
    const std::string p = "coarse_graining";
    opt_number(t, p, "ratio", {Bound::AtLeastOne, ""}, c.ratio);
    std::vector<std::pair<std::string, ContactScaling>> scalings;
    for (const auto s :
         {ContactScaling::chang08, ContactScaling::scale_invariant, ContactScaling::collision_time})
      scalings.emplace_back(to_string(s), s);
    opt_enum<ContactScaling>(t, p, "contact_scaling", scalings, c.contact_scaling);
    std::vector<std::pair<std::string, DragDiameter>> drags;
    for (const auto d : {DragDiameter::real, DragDiameter::parcel})
      drags.emplace_back(to_string(d), d);
    opt_enum<DragDiameter>(t, p, "drag_diameter", drags, c.drag_diameter);
  }

  /// `[body_force]`: after [domain] (the wavelength must fit a periodic box).
  void read_body_force(const toml::table* t) {
    if (t == nullptr) return;
    const std::string p = "body_force";
    BodyForceSpec b;
    const auto type = find(*t, "type", p + ".type");
    if (!type) missing(t, p, "[body_force]", "type", "\"sinusoidal_cube\"");
    opt_enum<BodyForceType>(t, p, "type", {{"sinusoidal_cube", BodyForceType::SinusoidalCube}},
                            b.type);
    b.amplitude = req_number(t, p, "[body_force]", "amplitude", {Bound::Any, "m/s^2"});
    b.wavelength = req_number(t, p, "[body_force]", "wavelength", kLength);
    opt_vec3(t, p, "origin", {Bound::Any, "m"}, b.origin);
    for (int a = 0; a < 3; ++a) {
      const auto k = static_cast<std::size_t>(a);
      if (!spec_.domain.periodic[k]) continue;
      const double length = spec_.domain.hi[k] - spec_.domain.lo[k];
      const double periods = length / b.wavelength;
      if (std::abs(periods - std::round(periods)) > 1e-9 * std::max(1.0, periods) ||
          std::round(periods) < 1.0)
        throw InputError(spec_.where(p + ".wavelength"), p + ".wavelength",
                         format_double(b.wavelength) +
                             " m does not divide the periodic box length " + format_double(length) +
                             " m along " + "xyz"[a] +
                             " (allowed: length / n for a whole number n >= 1, so that the field "
                             "is continuous across the periodic faces)");
    }
    spec_.body_force = b;
  }

  // --- non-contact forces -------------------------------------------------------------------

  /// `[van_der_waals]` [Zhu07 Table 2]: after [species].
  void read_van_der_waals(const toml::table* t) {
    if (t == nullptr) return;
    const std::string p = "van_der_waals", shown = "[van_der_waals]";
    VanDerWaalsSpec v;
    v.hamaker = req_number(t, p, shown, "hamaker", {Bound::Positive, "J"});
    v.min_separation = req_number(t, p, shown, "min_separation", kLength);
    v.range = req_number(t, p, shown, "range", kLength);
    if (v.range <= v.min_separation)
      throw InputError(spec_.where(p + ".range"), p + ".range",
                       format_double(v.range) +
                           " m is not beyond min_separation = " + format_double(v.min_separation) +
                           " m (allowed: a surface gap > min_separation, beyond which the "
                           "attraction is zero)");
    if (t->contains("wall_hamaker")) {
      double a = 0.0;
      opt_number(t, p, "wall_hamaker", {Bound::Positive, "J"}, a);
      v.wall_hamaker = a;
    }
    spec_.noncontact.van_der_waals = v;
  }

  /// `[electrostatics]` [Zhu07 Table 2]: after [domain] (the cut-off must fit a periodic box).
  void read_electrostatics(const toml::table* t) {
    if (t == nullptr) return;
    const std::string p = "electrostatics", shown = "[electrostatics]";
    ElectrostaticsSpec e;
    e.cutoff = req_number(t, p, shown, "cutoff", kLength);
    opt_number(t, p, "relative_permittivity", {Bound::AtLeastOne, ""}, e.relative_permittivity);
    for (int a = 0; a < 3; ++a) {
      const auto k = static_cast<std::size_t>(a);
      const double length = spec_.domain.hi[k] - spec_.domain.lo[k];
      if (spec_.domain.periodic[k] && !(2.0 * e.cutoff < length))
        throw InputError(spec_.where(p + ".cutoff"), p + ".cutoff",
                         format_double(e.cutoff) + " m is not below half the periodic box " +
                             "length " + format_double(length) + " m along " + "xyz"[a] +
                             " (allowed: a cut-off < L/2, so that a particle meets one image of "
                             "each other particle)");
    }
    if (const auto c = find(*t, "conducting_walls", p + ".conducting_walls")) {
      const Keys faces(kFaceNames.begin(), kFaceNames.end());
      const std::string rule = "an array of faces, each one of " + join_quoted(faces);
      const toml::array* arr = c->node->as_array();
      if (arr == nullptr)
        throw InputError(c->where, p + ".conducting_walls",
                         "expected " + rule + ", got " + describe(*c->node));
      for (const toml::node& f : *arr) {
        const auto name = f.value_exact<std::string>();
        const auto it = name ? std::find(faces.begin(), faces.end(), *name) : faces.end();
        if (it == faces.end())
          throw InputError(c->where, p + ".conducting_walls",
                           "unknown face " + describe(f) + " (allowed: " + rule + ")");
        const auto face = static_cast<std::size_t>(it - faces.begin());
        if (spec_.domain.periodic[face / 2])
          throw InputError(c->where, p + ".conducting_walls",
                           *name + " is on a periodic axis (allowed: faces of closed sides)");
        e.conducting[face] = true;
      }
    }
    spec_.noncontact.electrostatics = e;
  }

  /// `[liquid_bridge]` [Zhu07 §2.2]: after [species] (their liquid_fraction).
  void read_liquid_bridge(const toml::table* t) {
    if (t == nullptr) return;
    const std::string p = "liquid_bridge", shown = "[liquid_bridge]";
    LiquidBridgeSpec b;
    b.surface_tension = req_number(t, p, shown, "surface_tension", {Bound::Positive, "N/m"});
    double& degrees = b.contact_angle_degrees;
    opt_number(t, p, "contact_angle", {Bound::NonNegative, "degrees"}, degrees);
    if (!(degrees < 50.0))
      throw InputError(spec_.where(p + ".contact_angle"), p + ".contact_angle",
                       format_double(degrees) +
                           " degrees is out of range (allowed: 0 <= angle < 50 degrees, the "
                           "range of Willett's capillary force)");
    opt_number(t, p, "viscosity", {Bound::NonNegative, "Pa s"}, b.viscosity);
    if (b.viscosity > 0.0)
      b.min_gap = req_number(t, p, shown + " with a viscosity", "min_gap", kLength);
    else
      opt_number(t, p, "min_gap", kLength, b.min_gap);
    opt_bool(t, p, "walls", b.walls);
    bool wet = false;
    for (const SpeciesSpec& s : spec_.species) wet = wet || s.liquid_fraction > 0.0;
    if (!wet)
      throw InputError(spec_.where(p), p,
                       "no species has liquid (allowed: [liquid_bridge] with at least one "
                       "species' liquid_fraction > 0)");
    spec_.noncontact.liquid_bridge = b;
  }

  // --- gas, coupling, probes ----------------------------------------------------------------

  /// An array of three integers >= 1.
  std::array<int, 3> int3(const Entry& e, const std::string& path, const std::string& what) const {
    const toml::array* a = e.node->as_array();
    if (a == nullptr || a->size() != 3)
      throw InputError(e.where, path,
                       "expected " + what + ", got " + describe(*e.node) + " (allowed: " + what +
                           ")");
    std::array<int, 3> out{};
    for (std::size_t i = 0; i < 3; ++i) {
      const toml::node& n = *a->get(i);
      const SourceLocation where =
          n.source().begin.line > 0 ? loc(path, n.source().begin) : e.where;
      out[i] = int_value(Entry{&n, where}, path + "[" + std::to_string(i) + "]", 1, what);
    }
    return out;
  }

  void opt_int(const toml::table* t, const std::string& prefix, const std::string& key, int& out) {
    if (t == nullptr) return;
    const std::string path = prefix + "." + key;
    if (const auto e = find(*t, key, path)) out = int_value(*e, path, 1, "an integer >= 1");
  }

  /// `[gas]`: its presence makes the run coupled. The dimension, the box, the 2-D depth, gravity
  /// and periodic axes come from [simulation] and [domain], so the two phases cannot disagree.
  /// Value ranges are gas::validate()'s; its errors are reported at the key they name.
  void read_gas(const toml::table& root) {
    const auto e = find(root, "gas", "gas");
    if (!e) return;
    const toml::table* t = e->node->as_table();
    if (t == nullptr)
      throw InputError(e->where, "gas", "expected a table, got " + describe(*e->node));
    for (const auto& [key, why] : gas_derived_keys()) {
      const auto it = t->find(key);
      if (it == t->end()) continue;
      const std::string path = "gas." + key;
      throw InputError(loc(path, it->first.source().begin), path, "not a [gas] key (" + why + ")");
    }
    check_keys(*t, "gas.", gas_keys());

    const std::string p = "gas";
    const int dim = spec_.simulation.dimension;
    gas::GasSettings g;
    g.dimension = dim;
    for (int d = 0; d < 3; ++d) {
      g.lo[d] = spec_.domain.lo[d];
      g.hi[d] = spec_.domain.hi[d];
      g.gravity[d] = spec_.simulation.gravity[d];
    }
    if (dim == 2) g.depth = spec_.domain.hi[1] - spec_.domain.lo[1];

    const std::string cells_rule = dim == 2 ? "an array of 3 integers [nx, 1, nz], each >= 1"
                                            : "an array of 3 integers [nx, ny, nz], each >= 1";
    const auto cells = find(*t, "cells", p + ".cells");
    if (!cells) missing(t, p, "[gas]", "cells", cells_rule);
    g.cells = int3(*cells, p + ".cells", cells_rule);
    if (dim == 2 && g.cells[1] != 1)
      throw InputError(cells->where, p + ".cells",
                       "ny = " + std::to_string(g.cells[1]) +
                           " is not 1 in dimension 2 (allowed: " + cells_rule +
                           "; the 2-D gas is one cell thick in y)");

    // The flow time step DT: its own key in a soft-sphere run (DEM sub-steps inside it), while
    // a hard-sphere run's DT is simulation.time_step.
    if (spec_.simulation.engine == Engine::HardSphere) {
      if (const auto k = find(*t, "time_step", p + ".time_step"))
        throw InputError(k->where, p + ".time_step",
                         "not allowed with engine = \"hard_sphere\" (only with engine = "
                         "\"soft_sphere\"; the flow time step of a hard-sphere run is "
                         "simulation.time_step)");
    }
    std::optional<double> dt;
    auto_number(t, p, "time_step", kTime, dt);
    g.time_step = dt.value_or(0.0); // 0 = "auto"
    opt_number(t, p, "viscosity", {Bound::Any, "Pa s"}, g.viscosity);
    opt_enum<gas::PressureModel>(
        t, p, "model", {{"A", gas::PressureModel::A}, {"B", gas::PressureModel::B}}, g.model);
    opt_enum<gas::EquationOfState>(t, p, "eos",
                                   {{"ideal_gas", gas::EquationOfState::ideal_gas},
                                    {"incompressible", gas::EquationOfState::incompressible}},
                                   g.eos);
    const bool ideal = g.eos == gas::EquationOfState::ideal_gas;
    for (const std::string key : {"molar_mass", "temperature", "density"}) {
      if ((key == "density") != ideal) continue; // applies to this equation of state
      if (const auto k = find(*t, key, p + "." + key))
        throw InputError(
            k->where, p + "." + key,
            std::string("not allowed with eos = ") +
                (ideal ? "\"ideal_gas\"" : "\"incompressible\"") +
                " (only with eos = " + (ideal ? "\"incompressible\")" : "\"ideal_gas\")"));
    }
    opt_number(t, p, "molar_mass", {Bound::Any, "kg/mol"}, g.molar_mass);
    opt_number(t, p, "temperature", {Bound::Any, "K"}, g.temperature);
    opt_number(t, p, "density", {Bound::Any, "kg/m^3"}, g.density);
    opt_number(t, p, "initial_pressure", {Bound::Any, "Pa"}, g.initial_pressure);
    std::array<double, 3> u{g.initial_velocity.x, g.initial_velocity.y, g.initial_velocity.z};
    opt_vec3(t, p, "initial_velocity", {Bound::Any, "m/s"}, u);
    if (dim == 2 && u[1] != 0.0)
      throw InputError(spec_.where("gas.initial_velocity"), "gas.initial_velocity",
                       "y component " + format_double(u[1]) +
                           " is not 0 in dimension 2 (allowed: a velocity in the x-z plane, "
                           "[ux, 0, uz])");
    g.initial_velocity = Vec3{u[0], u[1], u[2]};

    if (const toml::table* st = table(*t, "solver", "gas.solver", gas_solver_keys())) {
      const std::string sp = "gas.solver";
      opt_number(st, sp, "tolerance", {Bound::Any, ""}, g.tolerance);
      opt_number(st, sp, "velocity_tolerance", {Bound::Any, "m/s"}, g.velocity_tolerance);
      opt_int(st, sp, "max_iterations", g.max_iterations);
      opt_number(st, sp, "velocity_relaxation", {Bound::Any, ""}, g.velocity_relaxation);
      opt_number(st, sp, "pressure_relaxation", {Bound::Any, ""}, g.pressure_relaxation);
      opt_number(st, sp, "linear_tolerance", {Bound::Any, ""}, g.linear_tolerance);
      opt_int(st, sp, "linear_max_iterations", g.linear_max_iterations);
      opt_number(st, sp, "max_courant", {Bound::Any, ""}, g.max_courant);
    }

    read_gas_boundaries(*t, g);
    validate_gas(g);
    spec_.gas = std::move(g);
  }

  /// `[gas.boundary.<side>]` and their `[[gas.boundary.<side>.region]]`.
  void read_gas_boundaries(const toml::table& t, gas::GasSettings& g) {
    const toml::table* bt = table(t, "boundary", "gas.boundary", gas_side_keys());
    static const char* axis_name = "xyz";
    for (std::size_t f = 0; f < gas::side_names.size(); ++f) {
      const std::string side = gas::side_names[f];
      const std::string fp = "gas.boundary." + side;
      const std::size_t axis = f / 2;
      gas::GasBoundary& b = g.boundary[f];
      if (g.dimension == 2 && axis == 1) {
        // The 2-D gas is one cell thick: its front and back are free-slip walls.
        b.type = gas::BoundaryType::wall_free_slip;
        if (bt == nullptr) continue;
        if (const auto e = find(*bt, side, fp))
          throw InputError(e->where, fp,
                           "not allowed in dimension 2 (front and back are free-slip walls of the "
                           "one-cell-thick gas; allowed: left, right, bottom, top)");
        continue;
      }
      const bool periodic = spec_.domain.periodic[axis];
      if (periodic) b.type = gas::BoundaryType::periodic;
      const toml::table* ft = bt ? table(*bt, side, fp, gas_face_keys()) : nullptr;
      if (ft == nullptr) continue;
      read_boundary_keys(*ft, fp, periodic ? static_cast<int>(axis) : -1, false, b.type, b.inflow,
                         b.porosity, b.pressure);

      const toml::array* regions = opt_table_array(*ft, "region", fp + ".region", fp + ".region",
                                                   gas_region_keys(), "each with a lo and a hi");
      if (regions == nullptr) continue;
      if (periodic)
        throw InputError(spec_.where(fp + ".region"), fp + ".region",
                         "not allowed on a periodic face (domain.periodic[" + std::to_string(axis) +
                             "] = true; allowed: regions of the other faces)");
      // The two tangential axes of the face, in axis order.
      const std::array<std::size_t, 2> tang = axis == 0   ? std::array<std::size_t, 2>{1, 2}
                                              : axis == 1 ? std::array<std::size_t, 2>{0, 2}
                                                          : std::array<std::size_t, 2>{0, 1};
      const std::string coords =
          std::string("(") + axis_name[tang[0]] + ", " + axis_name[tang[1]] + ")";
      for (std::size_t i = 0; i < regions->size(); ++i) {
        const toml::table* rt = regions->get(i)->as_table();
        const std::string rp = fp + ".region[" + std::to_string(i) + "]";
        gas::BoundaryRegion r;
        read_boundary_keys(*rt, rp, -1, true, r.type, r.inflow, r.porosity, r.pressure);
        for (const std::string which : {"lo", "hi"}) {
          const std::string path = rp + "." + which;
          const std::string rule =
              "an array of 2 numbers, in m: the " + coords + " coordinates of the corner";
          const auto e = find(*rt, which, path);
          if (!e) missing(rt, rp, "[[" + fp + ".region]] " + rp, which, rule);
          const std::array<double, 2> v = vec<2>(*e, path, {Bound::Any, "m"});
          for (std::size_t a = 0; a < 2; ++a) {
            const std::size_t ax = tang[a];
            if (g.dimension == 2 && ax == 1) continue; // the y range is not used in 2-D
            if (v[a] < spec_.domain.lo[ax] || v[a] > spec_.domain.hi[ax])
              throw InputError(e->where, path,
                               which + "[" + std::to_string(a) + "] = " + format_double(v[a]) +
                                   " is outside the " + side + " face (allowed: " +
                                   format_double(spec_.domain.lo[ax]) + " <= " + axis_name[ax] +
                                   " <= " + format_double(spec_.domain.hi[ax]) +
                                   "; the region's coordinates are " + coords + ")");
          }
          (which == "lo" ? r.lo : r.hi) = v;
        }
        b.regions.push_back(r);
      }
    }
  }

  /// The type and the inflow/pressure keys of a face (`periodic_axis` >= 0: a face of that
  /// periodic axis) or of a region of a face, at key path `p`. A key that does not apply to the
  /// type and mode is an error naming the type and mode that use it.
  void read_boundary_keys(const toml::table& t, const std::string& p, int periodic_axis,
                          bool region, gas::BoundaryType& type, gas::InflowProfile& in,
                          double& porosity, double& pressure) {
    using gas::BoundaryType;
    const std::vector<BoundaryType>& settable = settable_boundary_types();
    Keys names;
    for (const BoundaryType b : settable) names.push_back(gas::to_string(b));
    const std::string periodic_because = periodic_axis >= 0
                                             ? "the face is periodic because domain.periodic[" +
                                                   std::to_string(periodic_axis) + "] = true"
                                             : "";
    if (const auto e = find(t, "type", p + ".type")) {
      const std::string path = p + ".type";
      const std::string s = str_value(*e, path, "one of " + join_quoted(names));
      if (periodic_axis >= 0) {
        if (s != "periodic")
          throw InputError(e->where, path,
                           in_quotes(s) +
                               " on a periodic face (allowed: \"periodic\", or no type; " +
                               periodic_because + ")");
      } else if (s == "periodic") {
        throw InputError(e->where, path,
                         std::string(region ? "a region cannot be periodic"
                                            : "\"periodic\" is set by domain.periodic, not here") +
                             " (allowed: " + join_quoted(names) + ")");
      } else {
        const auto it = std::find(names.begin(), names.end(), s);
        if (it == names.end())
          throw InputError(e->where, path,
                           "unknown value " + in_quotes(s) + " (allowed: " + join_quoted(names) +
                               ")");
        type = settable[static_cast<std::size_t>(it - names.begin())];
      }
    }
    const bool inflow = (gas::boundary_kind(type).keys & gas::inflow_keys) != 0;
    if (inflow) {
      std::vector<std::pair<std::string, gas::InflowMode>> modes;
      for (const gas::InflowMode m : {gas::InflowMode::constant, gas::InflowMode::pulse,
                                      gas::InflowMode::pulsation, gas::InflowMode::table})
        modes.emplace_back(gas::to_string(m), m);
      opt_enum<gas::InflowMode>(&t, p, "mode", modes, in.mode);
    }

    // The first key (in file order) that does not apply.
    const toml::key* bad = nullptr;
    std::string bad_needs;
    for (auto&& [k, v] : t) {
      const std::string key(k.str());
      const std::string needs = boundary_key_needs(key);
      if (needs.empty() || boundary_key_applies(key, type, in.mode)) continue;
      if (bad == nullptr || before(k.source().begin, bad->source().begin)) {
        bad = &k;
        bad_needs = needs;
      }
    }
    if (bad != nullptr) {
      const std::string path = p + "." + std::string(bad->str());
      const std::string now = inflow ? "mode = " + in_quotes(gas::to_string(in.mode))
                                     : "type = " + in_quotes(gas::to_string(type));
      throw InputError(loc(path, bad->source().begin), path,
                       "not allowed with " + now + " (only with " + bad_needs +
                           (periodic_axis >= 0 ? "; " + periodic_because : "") + ")");
    }

    opt_number(&t, p, "velocity", {Bound::Any, "m/s"}, in.velocity);
    opt_number(&t, p, "background", {Bound::Any, "m/s"}, in.background);
    opt_number(&t, p, "start", {Bound::Any, "s"}, in.start);
    opt_number(&t, p, "duration", {Bound::Any, "s"}, in.duration);
    opt_number(&t, p, "amplitude", {Bound::Any, "m/s"}, in.amplitude);
    opt_number(&t, p, "frequency", {Bound::Any, "Hz"}, in.frequency);
    opt_numbers(&t, p, "times", {Bound::Any, "s"}, in.times);
    opt_numbers(&t, p, "velocities", {Bound::Any, "m/s"}, in.velocities);
    opt_number(&t, p, "porosity", {Bound::Any, ""}, porosity);
    opt_number(&t, p, "pressure", {Bound::Any, "Pa"}, pressure);
  }

  /// gas::validate(), its InputError re-thrown at the case-file key it names.
  void validate_gas(const gas::GasSettings& g) const {
    try {
      gas::validate(g);
    } catch (const InputError& e) {
      const std::string msg = e.what();
      const auto colon = msg.find(": ");
      if (colon == std::string::npos) throw InputError(spec_.where("gas"), "gas", msg);
      const std::string key = case_key_of_gas_setting(msg.substr(0, colon));
      throw InputError(spec_.where(key), key, msg.substr(colon + 2));
    }
  }

  /// `coupling.smoothing_length`: 0 (off) up to the domain's largest extent, m.
  void read_smoothing_length(const toml::table& t, const std::string& path, double& out) {
    const auto e = find(t, "smoothing_length", path);
    if (!e) return;
    double extent = 0.0;
    for (int d = 0; d < 3; ++d)
      extent = std::max(extent, spec_.domain.hi[static_cast<std::size_t>(d)] -
                                    spec_.domain.lo[static_cast<std::size_t>(d)]);
    const std::string rule = "0 (off) or a length in m up to the domain's largest extent, " +
                             format_double(extent) + " m (docs/smoothing.md)";
    if (e->node->is_floating_point() && !std::isfinite(*e->node->value<double>()))
      throw InputError(e->where, path,
                       format_double(*e->node->value<double>()) +
                           " is out of range (allowed: " + rule + ")");
    const double b = number(*e, path, {Bound::Any, "m"});
    if (!(b >= 0.0) || !(b <= extent))
      throw InputError(e->where, path,
                       format_double(b) + " is out of range (allowed: " + rule + ")");
    out = b;
  }

  void read_coupling(const toml::table* t) {
    if (t == nullptr) return;
    if (!spec_.gas)
      throw InputError(spec_.where("coupling"), "coupling",
                       "not allowed without [gas] (allowed: [coupling] in a coupled run, one with "
                       "a [gas] table)");
    coupling::CouplingSettings& c = spec_.coupling;
    const std::string p = "coupling";
    // The closure's name: the coupling module checks it against its registry at set-up, at this
    // key's location (coupling::drag::drag_model_of_case), so that io knows no drag law.
    if (const auto e = find(*t, "drag", p + ".drag")) {
      c.drag = str_value(*e, p + ".drag", "the name of a drag closure (docs/drag.md)");
      if (c.drag.empty())
        throw InputError(e->where, p + ".drag",
                         "an empty name (allowed: the name of a drag closure, docs/drag.md; "
                         "leave the key out for the default)");
    }
    std::vector<std::pair<std::string, coupling::PorosityMethod>> methods;
    for (const auto m : {coupling::PorosityMethod::cell, coupling::PorosityMethod::porous_cube})
      methods.emplace_back(coupling::to_string(m), m);
    opt_enum<coupling::PorosityMethod>(t, p, "porosity", methods, c.porosity.method);
    if (const auto e = find(*t, "cube_factor", p + ".cube_factor")) {
      const std::string path = p + ".cube_factor";
      if (c.porosity.method != coupling::PorosityMethod::porous_cube)
        throw InputError(e->where, path,
                         "not allowed with porosity = \"cell\" (only with porosity = "
                         "\"porous_cube\")");
      const std::string rule = "a number >= (pi/6)^(1/3) = 0.806 [Deen07 eq. 35]";
      const double a = number(*e, path, {Bound::Any, ""});
      if (!(a >= std::cbrt(std::numbers::pi / 6.0)))
        throw InputError(e->where, path,
                         format_double(a) + " is out of range (allowed: " + rule + ")");
      c.porosity.cube_factor = a;
    }
    if (const auto e = find(*t, "scheme", p + ".scheme")) {
      const std::int64_t n =
          integer(*e, p + ".scheme", std::numeric_limits<std::int64_t>::min(), "1, 2 or 3");
      static const std::array<coupling::ExchangeScheme, 3> schemes = {
          coupling::ExchangeScheme::scheme1, coupling::ExchangeScheme::scheme2,
          coupling::ExchangeScheme::scheme3};
      if (n < 1 || n > 3)
        throw InputError(e->where, p + ".scheme",
                         std::to_string(n) +
                             " is not a coupling scheme (allowed: 1, 2 or 3 [Zhu07 §3.2])");
      c.scheme = schemes[static_cast<std::size_t>(n - 1)];
    }
    opt_number(t, p, "d_mean", {Bound::NonNegative, "m"}, c.d_mean);
    opt_bool(t, p, "hold_gas_at_rest", c.hold_gas_at_rest);
    read_smoothing_length(*t, p + ".smoothing_length", c.smoothing_length);
    const auto& per = spec_.domain.periodic;
    if (c.hold_gas_at_rest && !per[0] && !per[1] && !per[2])
      throw InputError(spec_.where(p + ".hold_gas_at_rest"), p + ".hold_gas_at_rest",
                       "true needs a periodic axis (allowed: true only with domain.periodic true "
                       "on some axis; closed walls hold the gas already)");
    read_coupling_mode(t, p, c);
  }

  /// coupling.mode, particle_force and the frozen field (docs/coupling.md, "Coupling modes",
  /// "Particle force forms"). The closure's own form is checked at set-up
  /// (coupling::validate), which knows the closures.
  void read_coupling_mode(const toml::table* t, const std::string& p,
                          coupling::CouplingSettings& c) {
    using coupling::CouplingMode;
    using coupling::ParticleForceForm;
    std::vector<std::pair<std::string, CouplingMode>> modes;
    for (const auto m : {CouplingMode::two_way, CouplingMode::one_way, CouplingMode::frozen})
      modes.emplace_back(coupling::to_string(m), m);
    opt_enum<CouplingMode>(t, p, "mode", modes, c.mode);
    std::vector<std::pair<std::string, ParticleForceForm>> forms;
    for (const auto f : {ParticleForceForm::pressure_gradient, ParticleForceForm::buoyancy,
                         ParticleForceForm::total})
      forms.emplace_back(coupling::to_string(f), f);
    const bool model_a = spec_.gas->model == gas::PressureModel::A;
    ParticleForceForm form =
        model_a ? ParticleForceForm::pressure_gradient : ParticleForceForm::buoyancy;
    opt_enum<ParticleForceForm>(t, p, "particle_force", forms, form);
    // Model A's gas equation holds the pressure force's reaction in its -eps grad p; Model B's
    // takes the whole interaction force through its source (docs/coupling.md).
    if (model_a != (form == ParticleForceForm::pressure_gradient))
      throw InputError(spec_.where(p + ".particle_force"), p + ".particle_force",
                       "\"" + std::string(coupling::to_string(form)) +
                           "\" does not go with gas.model = \"" + (model_a ? "A" : "B") +
                           "\" (allowed: \"pressure_gradient\" with gas.model = \"A\"; "
                           "\"buoyancy\" or \"total\" with gas.model = \"B\")");
    if (t->contains("particle_force")) c.particle_force = form; // else: the gas model's
    const bool frozen = c.mode == CouplingMode::frozen;
    for (const char* key : {"frozen_velocity", "frozen_velocity_gradient"}) {
      const std::string path = p + "." + key;
      const auto e = find(*t, key, path);
      if (!e) continue;
      if (!frozen)
        throw InputError(e->where, path,
                         "only with mode = \"frozen\" (the prescribed gas field; the gas of "
                         "mode = \"" +
                             std::string(coupling::to_string(c.mode)) + "\" is solved)");
      if (std::string(key) == "frozen_velocity") {
        c.frozen_velocity = vec3(*e, path, {Bound::Any, "m/s"});
      } else {
        const auto g = vec<9>(*e, path, {Bound::Any, "1/s, row-major du_i/dx_j"});
        for (std::size_t i = 0; i < 3; ++i)
          for (std::size_t j = 0; j < 3; ++j) c.frozen_gradient[i][j] = g[3 * i + j];
      }
    }
    if (const toml::table* ft = table(*t, "forces", p + ".forces", coupling_force_keys()))
      read_fluid_forces(ft, p + ".forces", c.forces);
    if (c.hold_gas_at_rest && c.mode != CouplingMode::two_way)
      throw InputError(spec_.where(p + ".hold_gas_at_rest"), p + ".hold_gas_at_rest",
                       "true needs mode = \"two_way\" (the particles give the gas no momentum "
                       "in mode = \"" +
                           std::string(coupling::to_string(c.mode)) + "\")");
  }

  /// `[coupling.forces]` (docs/coupling.md, "Fluid forces beyond drag").
  void read_fluid_forces(const toml::table* t, const std::string& p,
                         coupling::FluidForceSettings& f) {
    opt_bool(t, p, "virtual_mass", f.virtual_mass);
    if (const auto e = find(*t, "virtual_mass_coefficient", p + ".virtual_mass_coefficient")) {
      const std::string path = p + ".virtual_mass_coefficient";
      if (!f.virtual_mass) throw InputError(e->where, path, "only with virtual_mass = true");
      f.virtual_mass_coefficient = number(*e, path, {Bound::Positive, ""});
    }
    opt_bool(t, p, "basset", f.basset);
    if (const auto e = find(*t, "basset_window", p + ".basset_window")) {
      const std::string path = p + ".basset_window";
      if (!f.basset) throw InputError(e->where, path, "only with basset = true");
      f.basset_window = int_value(*e, path, 1, "a whole number of flow steps >= 1");
    }
    opt_bool(t, p, "saffman", f.saffman);
    opt_enum<std::string>(t, p, "magnus",
                          {{"off", "off"},
                           {"rubinow_keller", "rubinow_keller"},
                           {"oesterle_bui_dinh", "oesterle_bui_dinh"}},
                          f.magnus);
    opt_enum<std::string>(t, p, "torque",
                          {{"off", "off"}, {"stokes", "stokes"}, {"dennis", "dennis"}}, f.torque);
  }

  /// `[output.continuum]`: discrete-to-continuum averages [Zhu07 Tables 5-6] (after [domain]:
  /// the weighted method's cutoff radius must fit half a periodic length).
  void read_continuum(const toml::table* output) {
    if (output == nullptr) return;
    const std::string p = "output.continuum";
    const toml::table* t = table(*output, "continuum", p, continuum_keys());
    if (t == nullptr) return;
    ContinuumOutputSpec c;
    const int dim = spec_.simulation.dimension;
    const std::string cells_rule = dim == 2 ? "an array of 3 integers [nx, 1, nz], each >= 1"
                                            : "an array of 3 integers [nx, ny, nz], each >= 1";
    const auto cells = find(*t, "cells", p + ".cells");
    if (!cells) missing(t, p, "[output.continuum]", "cells", cells_rule);
    c.cells = int3(*cells, p + ".cells", cells_rule);
    if (dim == 2 && c.cells[1] != 1)
      throw InputError(cells->where, p + ".cells",
                       "ny = " + std::to_string(c.cells[1]) +
                           " is not 1 in dimension 2 (allowed: " + cells_rule + ")");
    opt_enum<ContinuumMethod>(
        t, p, "method",
        {{"volume", ContinuumMethod::Volume}, {"weighted", ContinuumMethod::Weighted}}, c.method);
    const bool weighted = c.method == ContinuumMethod::Weighted;
    for (const char* key : {"width", "cutoff"})
      if (!weighted)
        if (const auto e = find(*t, key, p + "." + key))
          throw InputError(e->where, p + "." + key,
                           "only with method = \"weighted\" (allowed: remove it, or set "
                           "output.continuum.method = \"weighted\")");
    if (weighted) {
      c.width = req_number(t, p, "[output.continuum] with method = \"weighted\"", "width",
                           {Bound::Positive, "m"});
      opt_number(t, p, "cutoff", {Bound::Positive, ""}, c.cutoff);
      const double reach = c.width * c.cutoff;
      for (int a = 0; a < 3; ++a) {
        const double len = spec_.domain.hi[a] - spec_.domain.lo[a];
        if (spec_.domain.periodic[a] && !(dim == 2 && a == 1) && reach > 0.5 * len)
          throw InputError(spec_.where(p + ".width"), p + ".width",
                           "width x cutoff = " + format_double(reach) +
                               " m is more than half the periodic length along " +
                               std::string(1, "xyz"[a]) + " (" + format_double(len) +
                               " m) (allowed: width x cutoff <= " + format_double(0.5 * len) +
                               " m)");
      }
    }
    opt_number(t, p, "interval", kTime, c.interval);
    if (const auto e = find(*t, "stride", p + ".stride"))
      c.stride = int_value(*e, p + ".stride", 1, "an integer >= 1 (average every stride-th step)");
    if (spec_.simulation.engine == Engine::HardSphere)
      throw InputError(table_loc(t, p), p,
                       "needs the soft-sphere engine (the contact stresses come from its "
                       "contacts; allowed: simulation.engine = \"soft_sphere\", or remove "
                       "[output.continuum])");
    spec_.output.continuum = c;
  }

  /// `[[output.probe]]` (coupled runs only): named points where the gas pressure is recorded.
  void read_probes(const toml::table* output) {
    if (output == nullptr) return;
    const std::string name_rule =
        "a non-empty name other than \"time\", unique among the [[output.probe]], without "
        "commas, quotes or line breaks (it names a column of probes.csv)";
    const toml::array* a = opt_table_array(*output, "probe", "output.probe", "output.probe",
                                           probe_keys(), "each with a name and a position");
    if (a == nullptr) return;
    if (!spec_.gas)
      throw InputError(spec_.where("output.probe"), "output.probe",
                       "not allowed without [gas] (allowed: probes of the gas pressure in a "
                       "coupled run, one with a [gas] table)");
    static const char* axis_name = "xyz";
    for (std::size_t i = 0; i < a->size(); ++i) {
      const toml::table* t = a->get(i)->as_table();
      const std::string p = "output.probe[" + std::to_string(i) + "]";
      const std::string shown = "[[output.probe]] " + p;
      ProbeSpec probe;
      const auto name = find(*t, "name", p + ".name");
      if (!name) missing(t, p, shown, "name", name_rule);
      probe.name = str_value(*name, p + ".name", name_rule);
      if (probe.name.empty())
        throw InputError(name->where, p + ".name", "is empty (allowed: " + name_rule + ")");
      if (probe.name == "time")
        throw InputError(name->where, p + ".name",
                         "\"time\" is the first column of probes.csv (allowed: " + name_rule + ")");
      if (probe.name.find_first_of(",\"\r\n") != std::string::npos)
        throw InputError(name->where, p + ".name",
                         in_quotes(probe.name) +
                             " has a comma, a quote or a line break (allowed: " + name_rule + ")");
      for (std::size_t j = 0; j < spec_.output.probes.size(); ++j)
        if (spec_.output.probes[j].name == probe.name)
          throw InputError(name->where, p + ".name",
                           "duplicate probe name " + in_quotes(probe.name) +
                               ", also output.probe[" + std::to_string(j) + "] at " +
                               spec_.where("output.probe[" + std::to_string(j) + "].name").str() +
                               " (allowed: " + name_rule + ")");
      const auto pos = find(*t, "position", p + ".position");
      if (!pos)
        missing(t, p, shown, "position", "an array of 3 numbers, in m: a point inside the domain");
      probe.position = vec3(*pos, p + ".position", {Bound::Any, "m"});
      for (std::size_t d = 0; d < 3; ++d) {
        if (spec_.simulation.dimension == 2 && d == 1) continue; // y is not used in 2-D
        const double x = probe.position[d];
        if (x < spec_.domain.lo[d] || x > spec_.domain.hi[d])
          throw InputError(pos->where, p + ".position",
                           "position[" + std::to_string(d) + "] = " + format_double(x) +
                               " is outside the domain (allowed: a point inside the domain, " +
                               format_double(spec_.domain.lo[d]) + " <= " + axis_name[d] +
                               " <= " + format_double(spec_.domain.hi[d]) + ")");
      }
      spec_.output.probes.push_back(probe);
    }
  }

  /// `[[output.collision_region]]` (with output.collisions = true): named spheres over which the
  /// collision frequency and the void fraction are computed [Chang08 Table 1].
  void read_collision_regions(const toml::table* output) {
    if (output == nullptr) return;
    const std::string name_rule =
        "a non-empty name, unique among the [[output.collision_region]], without commas, quotes "
        "or line breaks (it names columns of collisions.csv)";
    const toml::array* a = opt_table_array(*output, "collision_region", "output.collision_region",
                                           "output.collision_region", collision_region_keys(),
                                           "each with a name, a centre and a radius");
    if (a == nullptr) return;
    if (!spec_.output.collisions)
      throw InputError(spec_.where("output.collision_region"), "output.collision_region",
                       "needs output.collisions = true (allowed: collision regions of a run "
                       "that writes collision statistics)");
    static const char* axis_name = "xyz";
    for (std::size_t i = 0; i < a->size(); ++i) {
      const toml::table* t = a->get(i)->as_table();
      const std::string p = "output.collision_region[" + std::to_string(i) + "]";
      const std::string shown = "[[output.collision_region]] " + p;
      CollisionRegionSpec region;
      const auto name = find(*t, "name", p + ".name");
      if (!name) missing(t, p, shown, "name", name_rule);
      region.name = str_value(*name, p + ".name", name_rule);
      if (region.name.empty())
        throw InputError(name->where, p + ".name", "is empty (allowed: " + name_rule + ")");
      if (region.name.find_first_of(",\"\r\n") != std::string::npos)
        throw InputError(name->where, p + ".name",
                         in_quotes(region.name) +
                             " has a comma, a quote or a line break (allowed: " + name_rule + ")");
      for (std::size_t j = 0; j < spec_.output.collision_regions.size(); ++j)
        if (spec_.output.collision_regions[j].name == region.name)
          throw InputError(
              name->where, p + ".name",
              "duplicate collision region name " + in_quotes(region.name) +
                  ", also output.collision_region[" + std::to_string(j) + "] at " +
                  spec_.where("output.collision_region[" + std::to_string(j) + "].name").str() +
                  " (allowed: " + name_rule + ")");
      const auto centre = find(*t, "centre", p + ".centre");
      if (!centre)
        missing(t, p, shown, "centre", "an array of 3 numbers, in m: a point inside the domain");
      region.centre = vec3(*centre, p + ".centre", {Bound::Any, "m"});
      for (std::size_t d = 0; d < 3; ++d) {
        if (spec_.simulation.dimension == 2 && d == 1) continue; // y is not used in 2-D
        const double x = region.centre[d];
        if (x < spec_.domain.lo[d] || x > spec_.domain.hi[d])
          throw InputError(centre->where, p + ".centre",
                           "centre[" + std::to_string(d) + "] = " + format_double(x) +
                               " is outside the domain (allowed: a point inside the domain, " +
                               format_double(spec_.domain.lo[d]) + " <= " + axis_name[d] +
                               " <= " + format_double(spec_.domain.hi[d]) + ")");
      }
      const auto radius = find(*t, "radius", p + ".radius");
      if (!radius) missing(t, p, shown, "radius", "a number > 0, in m");
      region.radius = number(*radius, p + ".radius", {Bound::Positive, "m"});
      spec_.output.collision_regions.push_back(region);
    }
  }
};

/// `s` with control characters escaped, so a message stays one line.
std::string one_line(const std::string& s) {
  std::string out;
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (u < 0x20 || u == 0x7f) {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[u >> 4];
      out += hex[u & 0xf];
    } else {
      out += c;
    }
  }
  return out;
}

CaseSpec read_case(const std::string& text, const std::string& source_name,
                   const std::vector<std::string>& overrides) {
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(source_name));
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw InputError(
        SourceLocation{source_name, static_cast<long>(b.line), static_cast<long>(b.column)}, "",
        "TOML syntax error: " + std::string(e.description()));
  }
  std::set<std::string> overridden;
  for (const auto& o : overrides) overridden.insert(apply_override(root, o));

  fs::path base = fs::path(source_name).parent_path();
  if (base.empty()) base = ".";
  std::error_code ec;
  const fs::path abs_base = fs::absolute(base, ec);
  if (!ec) base = abs_base;

  CaseSpec spec;
  spec.source_file = source_name;
  Reader(spec, source_name, base, std::move(overridden)).read(root);
  return spec;
}

} // namespace

CaseSpec read_case_string(const std::string& text, const std::string& source_name,
                          const std::vector<std::string>& overrides) {
  try {
    return read_case(text, source_name, overrides);
  } catch (const InputError& e) {
    // Keys and values quoted in a message may hold control characters ("a\nb" = 1).
    throw InputError(one_line(e.what()));
  }
}

CaseSpec read_case_file(const std::string& path, const std::vector<std::string>& overrides) {
  const std::string allowed = " (allowed: a readable TOML case file)";
  if (const auto problem = input_file_problem(path, /*allow_pipe=*/true))
    throw InputError(SourceLocation{path, 0, 0}, "", *problem + allowed);
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(SourceLocation{path, 0, 0}, "",
                     "cannot be opened: " + std::string(std::strerror(errno)) + allowed);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(SourceLocation{path, 0, 0}, "", read_failure(errno) + allowed);
  return read_case_string(ss.str(), path, overrides);
}

} // namespace fluidem
