// Case-file reader: defaults, every class of bad input (message names file, line and key),
// unknown-key suggestions, --set overrides, insert file resolution. docs/case-file.md is the spec.
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <unistd.h>
#include <vector>

#include "io/case_reader.hpp"
#include "io/key_suggest.hpp"

#include "../../common/case_error.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;

// A minimal valid case; the helpers below splice extra lines into its sections.
const std::string kSimulation = "[simulation]\nend_time = 0.5\n";
const std::string kDomain = "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.1, 0.004, 0.2]\n";
const std::string kSpecies = "[[species]]\nname = \"glass\"\ndiameter = 0.004\ndensity = 2700.0\n";
const std::string kInsert = "[[insert]]\nspecies = \"glass\"\ncount = 500\n";

std::string minimal() {
  return kSimulation + kDomain + kSpecies + kInsert;
}

/// 1-based line of the first occurrence of `marker` in `text` (0 if absent).
long line_of(const std::string& text, const std::string& marker) {
  const auto pos = text.find(marker);
  if (pos == std::string::npos) return 0;
  return 1 +
         static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

using fluidem::test::error_of;

/// Expects an InputError at the line of `marker` in `text`, naming `key`, containing `what`.
void expect_error_at(const std::string& text, const std::string& marker, const std::string& key,
                     const std::string& what) {
  const long line = line_of(text, marker);
  ASSERT_GT(line, 0) << "marker not in text: " << marker;
  const std::string msg = error_of(text);
  const std::string where = "case.toml:" + std::to_string(line) + ":";
  EXPECT_EQ(msg.rfind(where, 0), 0u) << "expected location " << where << " in: " << msg;
  EXPECT_NE(msg.find(": " + key + ": "), std::string::npos)
      << "expected key " << key << " in: " << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << "expected '" << what << "' in: " << msg;
}

struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name)
      : path(fs::temp_directory_path() /
             ("fluidem_io_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  fs::path write(const std::string& rel, const std::string& text) const {
    const fs::path p = path / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p;
  }
};

// --- key suggestions ------------------------------------------------------------------------

TEST(KeySuggest, EditDistance) {
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("abc", ""), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("stifness", "stiffness"), 1u);
  EXPECT_EQ(edit_distance("flaw", "lawn"), 2u);
}

TEST(KeySuggest, NearestKey) {
  const std::vector<std::string> keys = {"normal", "stiffness", "stiffness_ratio", "rolling"};
  EXPECT_EQ(nearest_key("stifness", keys), "stiffness");
  EXPECT_EQ(nearest_key("stiffnes_ratio", keys), "stiffness_ratio");
  EXPECT_EQ(nearest_key("rolling", keys), "rolling");
  EXPECT_EQ(nearest_key("x", {}), "");
}

// --- valid input ----------------------------------------------------------------------------

TEST(CaseReader, DefaultsFilled) {
  const CaseSpec c = read_case_string(minimal(), "case.toml");
  const CaseSpec d; // the struct defaults
  EXPECT_EQ(c.source_file, "case.toml");
  EXPECT_EQ(c.simulation.engine, Engine::SoftSphere);
  EXPECT_EQ(c.simulation.dimension, d.simulation.dimension);
  EXPECT_EQ(c.simulation.end_time, 0.5);
  EXPECT_FALSE(c.simulation.time_step.has_value());
  EXPECT_EQ(c.simulation.time_step_fraction, d.simulation.time_step_fraction);
  EXPECT_EQ(c.simulation.force_time_step, false);
  EXPECT_EQ(c.simulation.gravity, d.simulation.gravity);
  EXPECT_EQ(c.simulation.insertion_overlap_tolerance, d.simulation.insertion_overlap_tolerance);
  EXPECT_EQ(c.output.frame_interval, d.output.frame_interval);
  EXPECT_EQ(c.output.series_interval, d.output.series_interval);
  EXPECT_EQ(c.domain.lo, (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(c.domain.hi, (std::array<double, 3>{0.1, 0.004, 0.2}));
  EXPECT_EQ(c.domain.periodic, (std::array<bool, 3>{false, false, false}));
  const MaterialSpec m;
  for (const auto& w : c.domain.wall_material) {
    EXPECT_EQ(w.youngs_modulus, m.youngs_modulus);
    EXPECT_EQ(w.restitution, m.restitution);
    EXPECT_EQ(w.friction, m.friction);
  }
  ASSERT_EQ(c.species.size(), 1u);
  EXPECT_EQ(c.species[0].name, "glass");
  EXPECT_EQ(c.species[0].diameter, 0.004);
  EXPECT_EQ(c.species[0].density, 2700.0);
  EXPECT_EQ(c.species[0].material.poisson_ratio, m.poisson_ratio);
  EXPECT_EQ(c.species[0].material.tangential_restitution, m.tangential_restitution);
  EXPECT_EQ(c.species[0].material.rolling_friction, m.rolling_friction);
  ASSERT_EQ(c.inserts.size(), 1u);
  EXPECT_EQ(c.inserts[0].species, "glass");
  EXPECT_EQ(c.inserts[0].count, 500);
  EXPECT_EQ(c.inserts[0].placement, Placement::Random);
  EXPECT_EQ(c.inserts[0].region_lo, c.domain.lo); // region defaults to the domain
  EXPECT_EQ(c.inserts[0].region_hi, c.domain.hi);
  EXPECT_EQ(c.inserts[0].velocity, (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(c.inserts[0].velocity_spread, 0.0);
  EXPECT_EQ(c.inserts[0].seed, 1u);
  EXPECT_EQ(c.contact.normal.name, "hertz");
  EXPECT_EQ(c.contact.tangential.name, "history");
  EXPECT_EQ(c.contact.rolling.name, "none");
  EXPECT_FALSE(c.contact.normal.coefficients.contains("stiffness_ratio"));
  EXPECT_FALSE(c.contact.characteristic_velocity.has_value());
  EXPECT_EQ(c.contact.max_overlap, d.contact.max_overlap);
  EXPECT_FALSE(c.neighbour.skin.has_value());
  EXPECT_EQ(c.hardsphere.tc_time, 1e-6);
  EXPECT_EQ(c.hardsphere.max_events_per_particle, 1000.0);
  EXPECT_EQ(c.hardsphere.tc_time, d.hardsphere.tc_time);
  EXPECT_EQ(c.hardsphere.max_events_per_particle, d.hardsphere.max_events_per_particle);
}

TEST(CaseReader, AllKeysRead) {
  const std::string text = R"(
[simulation]
engine = "hard_sphere"
dimension = 2
end_time = 2
time_step = 1e-5
time_step_fraction = 0.05
force_time_step = true
gravity = [0.0, 0, -9.8]
insertion_overlap_tolerance = 0.02

[output]
frame_interval = 0.02
series_interval = 0.002

[domain]
lo = [-0.05, 0.0, 0.0]
hi = [0.05, 0.004, 0.3]
periodic = [true, false, false]

[walls]
friction = 0.5
youngs_modulus = 2e7

[walls.z_lo]
restitution = 0.1

[[species]]
name = "glass"
diameter = 0.004
density = 2700
youngs_modulus = 1e8
poisson_ratio = 0.3
restitution = 0.95
friction = 0.2
tangential_restitution = 0.4
rolling_friction = 0.01

[[insert]]
species = "glass"
count = 10
placement = "lattice"
region = { lo = [-0.04, 0.0, 0.1], hi = [0.04, 0.004, 0.2] }
velocity = [0.1, 0.0, -0.2]
velocity_spread = 0.05
seed = 42

[contact]
normal = "linear"
stiffness = 800
tangential = "none"
stiffness_ratio = 0.5
rolling = "constant_torque"
characteristic_velocity = 1.5
max_overlap = 0.2

[neighbour]
skin = 0.0008

[hardsphere]
tc_time = 2.5e-5
max_events_per_particle = 50
)";
  const CaseSpec c = read_case_string(text, "case.toml");
  EXPECT_EQ(c.simulation.engine, Engine::HardSphere);
  EXPECT_EQ(c.simulation.dimension, 2);
  EXPECT_EQ(c.simulation.end_time, 2.0); // integer accepted where a float is wanted
  ASSERT_TRUE(c.simulation.time_step.has_value());
  EXPECT_EQ(*c.simulation.time_step, 1e-5);
  EXPECT_EQ(c.simulation.time_step_fraction, 0.05);
  EXPECT_TRUE(c.simulation.force_time_step);
  EXPECT_EQ(c.simulation.gravity, (std::array<double, 3>{0.0, 0.0, -9.8}));
  EXPECT_EQ(c.simulation.insertion_overlap_tolerance, 0.02);
  EXPECT_EQ(c.output.frame_interval, 0.02);
  EXPECT_EQ(c.output.series_interval, 0.002);
  EXPECT_EQ(c.domain.lo, (std::array<double, 3>{-0.05, 0.0, 0.0}));
  EXPECT_EQ(c.domain.periodic, (std::array<bool, 3>{true, false, false}));
  // [walls] sets all faces; [walls.z_lo] overrides one key and inherits the rest.
  const auto& zlo = c.domain.wall_material[static_cast<int>(Face::ZLo)];
  const auto& xhi = c.domain.wall_material[static_cast<int>(Face::XHi)];
  EXPECT_EQ(zlo.restitution, 0.1);
  EXPECT_EQ(zlo.friction, 0.5);
  EXPECT_EQ(zlo.youngs_modulus, 2e7);
  EXPECT_EQ(xhi.restitution, 0.9);
  EXPECT_EQ(xhi.friction, 0.5);
  const auto& sm = c.species[0].material;
  EXPECT_EQ(sm.youngs_modulus, 1e8);
  EXPECT_EQ(sm.poisson_ratio, 0.3);
  EXPECT_EQ(sm.restitution, 0.95);
  EXPECT_EQ(sm.friction, 0.2);
  EXPECT_EQ(sm.tangential_restitution, 0.4);
  EXPECT_EQ(sm.rolling_friction, 0.01);
  const auto& in = c.inserts[0];
  EXPECT_EQ(in.placement, Placement::Lattice);
  EXPECT_EQ(in.count, 10);
  EXPECT_EQ(in.region_lo, (std::array<double, 3>{-0.04, 0.0, 0.1}));
  EXPECT_EQ(in.region_hi, (std::array<double, 3>{0.04, 0.004, 0.2}));
  EXPECT_EQ(in.velocity, (std::array<double, 3>{0.1, 0.0, -0.2}));
  EXPECT_EQ(in.velocity_spread, 0.05);
  EXPECT_EQ(in.seed, 42u);
  EXPECT_EQ(c.contact.normal.name, "linear");
  EXPECT_EQ(c.contact.normal.coefficients.at("stiffness"), 800.0);
  EXPECT_EQ(c.contact.tangential.name, "none");
  EXPECT_EQ(c.contact.normal.coefficients.at("stiffness_ratio"), 0.5);
  EXPECT_EQ(c.contact.rolling.name, "constant_torque");
  EXPECT_EQ(c.contact.characteristic_velocity, 1.5);
  EXPECT_EQ(c.contact.max_overlap, 0.2);
  EXPECT_EQ(c.neighbour.skin, 0.0008);
  EXPECT_EQ(c.hardsphere.tc_time, 2.5e-5);
  EXPECT_EQ(c.hardsphere.max_events_per_particle, 50.0); // integer accepted

  // Locations of keys, in the documented path forms.
  EXPECT_EQ(c.where("simulation.engine").str(), "case.toml:3:1");
  EXPECT_EQ(c.where("simulation.end_time").str(), "case.toml:5:1");
  EXPECT_EQ(c.where("hardsphere.tc_time").line, line_of(text, "tc_time"));
  EXPECT_EQ(c.where("hardsphere.max_events_per_particle").line,
            line_of(text, "max_events_per_particle"));
  EXPECT_EQ(c.where("hardsphere").line, line_of(text, "[hardsphere]"));
  EXPECT_EQ(c.where("walls.z_lo.restitution").line, line_of(text, "restitution = 0.1"));
  EXPECT_EQ(c.where("species[0].rolling_friction").line, line_of(text, "rolling_friction"));
  EXPECT_EQ(c.where("insert[0].seed").line, line_of(text, "seed = 42"));
  EXPECT_EQ(c.where("insert[0].region.hi").line, line_of(text, "region ="));
  EXPECT_EQ(c.where("contact.stiffness").line, line_of(text, "stiffness = 800"));
  EXPECT_EQ(c.where("species[0]").line, line_of(text, "[[species]]"));
  EXPECT_EQ(c.locations.count("walls.x_lo.restitution"), 0u); // not in the file
}

TEST(CaseReader, WaltonBraunAndAutoParse) {
  const CaseSpec c = read_case_string(minimal() + "[contact]\nnormal = \"walton_braun\"\n"
                                                  "stiffness = 1000.0\n"
                                                  "stiffness_ratio = \"auto\"\n"
                                                  "[neighbour]\nskin = \"auto\"\n",
                                      "case.toml");
  EXPECT_EQ(c.contact.normal.name, "walton_braun");
  EXPECT_EQ(c.contact.normal.coefficients.size(), 1u); // stiffness ("auto": absent)
  EXPECT_EQ(c.contact.normal.coefficients.at("stiffness"), 1000.0);
  EXPECT_FALSE(c.neighbour.skin.has_value());
}

TEST(CaseReader, HardSphereEngineAndTcOff) {
  const CaseSpec c =
      read_case_string(kSimulation + "engine = \"hard_sphere\"\n" + kDomain + kSpecies + kInsert +
                           "[hardsphere]\ntc_time = 0\nmax_events_per_particle = 1\n",
                       "case.toml");
  EXPECT_EQ(c.simulation.engine, Engine::HardSphere);
  EXPECT_EQ(c.hardsphere.tc_time, 0.0); // 0 switches the TC model off
  EXPECT_EQ(c.hardsphere.max_events_per_particle, 1.0);
  EXPECT_EQ(
      read_case_string(kSimulation + "engine = \"soft_sphere\"\n" + kDomain + kSpecies + kInsert,
                       "case.toml")
          .simulation.engine,
      Engine::SoftSphere);
}

// --- bad input: syntax, unknown keys ----------------------------------------------------------

TEST(CaseReaderErrors, SyntaxError) {
  const std::string text = "[simulation]\nend_time = = 1\n" + kDomain;
  const std::string msg = error_of(text);
  EXPECT_EQ(msg.rfind("case.toml:2:", 0), 0u) << msg;
  EXPECT_NE(msg.find("TOML syntax error"), std::string::npos) << msg;
}

TEST(CaseReaderErrors, UnknownKeyExactMessage) {
  const std::string text = minimal() + "[contact]\nnormal = \"linear\"\nstifness = 800\n";
  const long line = line_of(text, "stifness");
  EXPECT_EQ(error_of(text), "case.toml:" + std::to_string(line) +
                                ":1: contact.stifness: unknown key (did you mean \"stiffness\"?)");
}

TEST(CaseReaderErrors, UnknownKeysEverywhere) {
  std::string t = minimal() + "[contat]\nnormal = \"hertz\"\n";
  expect_error_at(t, "[contat]", "contat", "did you mean \"contact\"?");

  t = kSimulation + "dimensoin = 3\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "dimensoin", "simulation.dimensoin", "did you mean \"dimension\"?");

  t = kSimulation + kDomain + kSpecies + "restitutin = 0.5\n" + kInsert;
  expect_error_at(t, "restitutin", "species[0].restitutin", "did you mean \"restitution\"?");

  t = minimal() + "[[insert]]\nspecies = \"glass\"\ncont = 5\n";
  expect_error_at(t, "cont = 5", "insert[1].cont", "did you mean \"count\"?");

  t = minimal() + "region = { lo = [0.0, 0.0, 0.0], hj = [0.1, 0.004, 0.1] }\n";
  expect_error_at(t, "region", "insert[0].region.hj", "did you mean \"hi\"?");

  t = minimal() + "[walls.z_lo]\nfrction = 0.1\n";
  expect_error_at(t, "frction", "walls.z_lo.frction", "did you mean \"friction\"?");

  t = minimal() + "[walls.z_low]\nfriction = 0.1\n";
  expect_error_at(t, "[walls.z_low]", "walls.z_low", "did you mean \"z_lo\"?");

  t = minimal() + "[hardsphere]\ntc_tme = 1e-6\n";
  expect_error_at(t, "tc_tme", "hardsphere.tc_tme", "did you mean \"tc_time\"?");

  t = minimal() + "[hardsphere]\nmax_event_per_particle = 10\n";
  expect_error_at(t, "max_event_per", "hardsphere.max_event_per_particle",
                  "did you mean \"max_events_per_particle\"?");

  t = minimal() + "[hardspheres]\ntc_time = 1e-6\n";
  expect_error_at(t, "[hardspheres]", "hardspheres", "did you mean \"hardsphere\"?");

  t = kSimulation + "engin = \"hard_sphere\"\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "engin", "simulation.engin", "did you mean \"engine\"?");

  t = minimal() + "[output]\nframe_intervall = 0.1\n";
  expect_error_at(t, "frame_intervall", "output.frame_intervall",
                  "did you mean \"frame_interval\"?");
}

TEST(CaseReaderErrors, ControlCharactersEscapedInMessages) {
  // error_of() fails the test if the message spans more than one line.
  const std::string t = minimal() + "[contact]\n\"a\\nb\" = 1\n";
  expect_error_at(t, "\"a\\nb\"", "contact.a\\nb", "unknown key");
  const std::string msg = error_of(minimal(), {"contact.a\nb=1"});
  EXPECT_EQ(msg.rfind("--set: contact.a\\nb: unknown key", 0), 0u) << msg;
}

TEST(CaseReaderErrors, FirstUnknownKeyInFileOrder) {
  // toml++ tables are ordered by name; the error must still name the first one in the file.
  const std::string t = minimal() + "[contact]\nzzz = 1\naaa = 2\n";
  expect_error_at(t, "zzz", "contact.zzz", "unknown key");
}

// --- bad input: wrong types -------------------------------------------------------------------

TEST(CaseReaderErrors, WrongTypes) {
  std::string t = "[simulation]\nend_time = \"long\"\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "end_time", "simulation.end_time", "expected a number, got the string");

  t = kSimulation + "gravity = [0.0, -9.81]\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "gravity", "simulation.gravity", "an array of 3 numbers");

  t = kSimulation + "gravity = [0.0, \"y\", -9.81]\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "gravity", "simulation.gravity[1]", "expected a number");

  t = kSimulation + kDomain + kSpecies + "[[insert]]\nspecies = \"glass\"\ncount = 10.5\n";
  expect_error_at(t, "count = 10.5", "insert[0].count", "expected an integer");

  t = kSimulation + "dimension = 2.0\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "dimension", "simulation.dimension", "expected an integer");

  t = kSimulation + "force_time_step = 1\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "force_time_step", "simulation.force_time_step", "expected a boolean");

  t = kSimulation + kDomain + "periodic = [true, false]\n" + kSpecies + kInsert;
  expect_error_at(t, "periodic", "domain.periodic", "an array of 3 booleans");

  t = kSimulation + kDomain + "[[species]]\nname = 7\ndiameter = 0.004\ndensity = 2700.0\n" +
      kInsert;
  expect_error_at(t, "name = 7", "species[0].name", "expected a string");

  t = minimal() + "[contact]\nnormal = 1\n";
  expect_error_at(t, "normal = 1", "contact.normal", "expected a string");

  t = kSimulation + "engine = 1\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "engine", "simulation.engine", "expected a string");

  t = minimal() + "[hardsphere]\ntc_time = \"off\"\n";
  expect_error_at(t, "tc_time", "hardsphere.tc_time", "expected a number, got the string");

  t = "hardsphere = 1\n" + minimal();
  expect_error_at(t, "hardsphere = 1", "hardsphere", "expected a table");

  t = minimal() + "[neighbour]\nskin = \"big\"\n";
  expect_error_at(t, "skin", "neighbour.skin", "expected a number or \"auto\"");

  t = kSimulation + "time_step = true\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "time_step", "simulation.time_step", "expected a number or \"auto\"");

  t = "simulation = 3\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "simulation = 3", "simulation", "expected a table");

  t = kSimulation + kDomain + "[species]\nname = \"glass\"\n" + kInsert;
  expect_error_at(t, "[species]", "species", "expected an array of tables [[species]]");
}

// --- bad input: out of range ------------------------------------------------------------------

TEST(CaseReaderErrors, OutOfRange) {
  struct Case {
    std::string extra_species, extra_sim, extra_tail, marker, key, what;
  };
  const std::vector<Case> cases = {
      {"restitution = 1.5\n", "", "", "restitution", "species[0].restitution", "[0, 1]"},
      {"friction = -0.1\n", "", "", "friction", "species[0].friction", ">= 0"},
      {"poisson_ratio = 0.5\n", "", "", "poisson_ratio", "species[0].poisson_ratio", "[0, 0.5)"},
      {"youngs_modulus = 0\n", "", "", "youngs_modulus", "species[0].youngs_modulus", "> 0"},
      {"tangential_restitution = 2\n", "", "", "tangential_restitution",
       "species[0].tangential_restitution", "[0, 1]"},
      {"rolling_friction = -1\n", "", "", "rolling_friction", "species[0].rolling_friction",
       ">= 0"},
      {"", "dimension = 4\n", "", "dimension", "simulation.dimension", "2 or 3"},
      {"", "time_step = -1e-5\n", "", "time_step", "simulation.time_step", "> 0"},
      {"", "time_step_fraction = 0\n", "", "time_step_fraction", "simulation.time_step_fraction",
       "(0, 1]"},
      {"", "insertion_overlap_tolerance = -0.1\n", "", "insertion_overlap",
       "simulation.insertion_overlap_tolerance", ">= 0"},
      {"", "dimension = 2\ngravity = [0.0, -1.0, -9.81]\n", "", "gravity", "simulation.gravity",
       "x-z plane"},
      {"", "", "[output]\nframe_interval = 0\n", "frame_interval", "output.frame_interval", "> 0"},
      {"", "", "[output]\nseries_interval = -1\n", "series_interval", "output.series_interval",
       "> 0"},
      {"", "", "[walls]\nrestitution = -0.5\n", "restitution", "walls.restitution", "[0, 1]"},
      {"", "", "[walls.x_hi]\nfriction = -1\n", "friction", "walls.x_hi.friction", ">= 0"},
      {"", "", "velocity_spread = -1\n", "velocity_spread", "insert[0].velocity_spread", ">= 0"},
      {"", "", "seed = -1\n", "seed", "insert[0].seed", "an integer >= 0"},
      {"", "", "[contact]\nmax_overlap = 1.0\n", "max_overlap", "contact.max_overlap", "(0, 1)"},
      {"", "", "[contact]\nstiffness_ratio = 0\n", "stiffness_ratio", "contact.stiffness_ratio",
       "> 0"},
      {"", "", "[contact]\ncharacteristic_velocity = -1\n", "characteristic_velocity",
       "contact.characteristic_velocity", "> 0"},
      {"", "", "[neighbour]\nskin = 0\n", "skin", "neighbour.skin", "> 0"},
      {"", "", "[contact]\nmax_overlap = nan\n", "max_overlap", "contact.max_overlap", "(0, 1)"},
      {"", "", "[neighbour]\nskin = inf\n", "skin", "neighbour.skin", "> 0"},
      {"", "", "[hardsphere]\ntc_time = -1e-6\n", "tc_time", "hardsphere.tc_time",
       "-1e-06 is out of range (allowed: a number >= 0, in s)"},
      {"", "", "[hardsphere]\ntc_time = nan\n", "tc_time", "hardsphere.tc_time", ">= 0, in s"},
      {"", "", "[hardsphere]\nmax_events_per_particle = 0.5\n", "max_events",
       "hardsphere.max_events_per_particle", "0.5 is out of range (allowed: a number >= 1)"},
      {"", "", "[hardsphere]\nmax_events_per_particle = 0\n", "max_events",
       "hardsphere.max_events_per_particle", "(allowed: a number >= 1)"},
      {"", "", "[hardsphere]\nmax_events_per_particle = -inf\n", "max_events",
       "hardsphere.max_events_per_particle", ">= 1"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.key);
    const std::string t =
        kSimulation + c.extra_sim + kDomain + kSpecies + c.extra_species + kInsert + c.extra_tail;
    const long line = line_of(t, c.marker); // markers are not in the base text
    ASSERT_GT(line, 0);
    const std::string msg = error_of(t);
    EXPECT_EQ(msg.rfind("case.toml:" + std::to_string(line) + ":", 0), 0u) << msg;
    EXPECT_NE(msg.find(": " + c.key + ": "), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.what), std::string::npos) << msg;
  }
}

TEST(CaseReaderErrors, RequiredPositive) {
  std::string t = "[simulation]\nend_time = 0\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "end_time", "simulation.end_time", "0 is out of range (allowed: a number > 0");

  t = kSimulation + kDomain + "[[species]]\nname = \"glass\"\ndiameter = 0.0\ndensity = 1.0\n" +
      kInsert;
  expect_error_at(t, "diameter", "species[0].diameter", "> 0, in m");

  t = kSimulation + kDomain + "[[species]]\nname = \"glass\"\ndiameter = 0.1\ndensity = -5\n" +
      kInsert;
  expect_error_at(t, "density", "species[0].density", "> 0, in kg/m^3");

  t = kSimulation + kDomain + kSpecies + "[[insert]]\nspecies = \"glass\"\ncount = 0\n";
  expect_error_at(t, "count", "insert[0].count", "an integer >= 1");
}

TEST(CaseReaderErrors, Boxes) {
  std::string t =
      kSimulation + "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.1, 0.0, 0.2]\n" + kSpecies + kInsert;
  expect_error_at(t, "hi =", "domain.hi", "hi > lo on every axis");

  t = minimal() + "region = { lo = [0.0, 0.0, 0.1], hi = [0.1, 0.004, 0.05] }\n";
  expect_error_at(t, "region", "insert[0].region.hi", "hi > lo");

  t = minimal() + "region = { lo = [0.0, 0.0, 0.1], hi = [0.1, 0.004, 0.5] }\n";
  expect_error_at(t, "region", "insert[0].region.hi", "outside the domain");

  t = minimal() + "region = { lo = [-0.1, 0.0, 0.1] }\n";
  expect_error_at(t, "region", "insert[0].region.lo", "outside the domain");
}

// --- bad input: missing required keys ---------------------------------------------------------

TEST(CaseReaderErrors, MissingRequired) {
  // A missing key is reported at its table, naming the key and the table.
  std::string t = "[simulation]\ndimension = 3\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "[simulation]", "simulation.end_time", "missing required key in [simulation]");

  t = kSimulation + kDomain + "[[species]]\nname = \"glass\"\ndensity = 2700.0\n" + kInsert;
  expect_error_at(t, "[[species]]", "species[0].diameter", "missing required key in [[species]]");

  t = kSimulation + kDomain + kSpecies + "[[species]]\ndiameter = 0.1\ndensity = 1.0\n" + kInsert;
  const long line = line_of(t, "[[species]]\ndiameter");
  const std::string msg = error_of(t);
  EXPECT_EQ(msg.rfind("case.toml:" + std::to_string(line) + ":", 0), 0u) << msg;
  EXPECT_NE(msg.find("species[1].name: missing required key"), std::string::npos) << msg;

  t = kSimulation + "[domain]\nlo = [0.0, 0.0, 0.0]\n" + kSpecies + kInsert;
  expect_error_at(t, "[domain]", "domain.hi", "missing required key in [domain]");

  t = kSimulation + kDomain + kSpecies + "[[insert]]\nspecies = \"glass\"\n";
  expect_error_at(t, "[[insert]]", "insert[0].count", "missing required key in [[insert]]");

  t = kSimulation + kDomain + kSpecies + "[[insert]]\ncount = 3\n";
  expect_error_at(t, "[[insert]]", "insert[0].species", "missing required key");

  t = minimal() + "[contact]\nnormal = \"linear\"\n";
  expect_error_at(t, "[contact]", "contact.stiffness", "required with normal = \"linear\"");

  // Whole tables missing: no line, but the file and the key are named.
  EXPECT_EQ(
      error_of(kDomain + kSpecies + kInsert).rfind("case.toml: simulation.end_time: missing", 0),
      0u);
  EXPECT_EQ(error_of(kSimulation + kSpecies + kInsert).rfind("case.toml: domain: missing", 0), 0u);
  EXPECT_EQ(error_of(kSimulation + kDomain + kInsert).rfind("case.toml: species: missing", 0), 0u);
  EXPECT_EQ(error_of(kSimulation + kDomain + kSpecies).rfind("case.toml: insert: missing", 0), 0u);
  EXPECT_NE(error_of("").find("missing"), std::string::npos);
}

// --- bad input: cross-references, enumerations, combinations ------------------------------------

TEST(CaseReaderErrors, DuplicateSpecies) {
  const std::string t = kSimulation + kDomain + kSpecies +
                        "[[species]]\nname = \"glass\" # again\ndiameter = 0.002\ndensity = 1.0\n" +
                        kInsert;
  expect_error_at(t, "# again", "species[1].name", "duplicate species name \"glass\"");
  // The message also says where the first one is.
  EXPECT_NE(error_of(t).find("case.toml:" + std::to_string(line_of(t, "name = \"glass\"")) + ":1"),
            std::string::npos);
}

TEST(CaseReaderErrors, EmptySpeciesName) {
  const std::string t =
      kSimulation + kDomain + "[[species]]\nname = \"\"\ndiameter = 0.1\ndensity = 1.0\n" + kInsert;
  expect_error_at(t, "name", "species[0].name", "is empty");
}

TEST(CaseReaderErrors, InsertUnknownSpeciesListsValid) {
  const std::string t = kSimulation + kDomain + kSpecies +
                        "[[species]]\nname = \"steel\"\ndiameter = 0.002\ndensity = 7800.0\n" +
                        "[[insert]]\nspecies = \"glas\"\ncount = 3\n";
  expect_error_at(t, "\"glas\"", "insert[0].species",
                  "unknown species \"glas\" (allowed: one of \"glass\", \"steel\")");
}

TEST(CaseReaderErrors, UnknownEnumerationListsValid) {
  std::string t = minimal() + "[contact]\nnormal = \"hertzz\"\n";
  expect_error_at(t, "hertzz", "contact.normal",
                  "unknown value \"hertzz\" (allowed: \"linear\", \"hertz\", \"walton_braun\", "
                  "\"jkr\")");
  t = minimal() + "[contact]\nrolling = \"constant\"\n";
  expect_error_at(t, "constant", "contact.rolling", "\"constant_torque\", \"spring_dashpot\"");
  t = minimal() + "[contact]\ntangential = \"yes\"\n";
  expect_error_at(t, "yes", "contact.tangential", "\"history\", \"none\"");
  t = kSimulation + "engine = \"event_driven\"\n" + kDomain + kSpecies + kInsert;
  expect_error_at(t, "event_driven", "simulation.engine",
                  "unknown value \"event_driven\" (allowed: \"soft_sphere\", \"hard_sphere\")");
  t = minimal() + "placement = \"grid\"\n";
  expect_error_at(t, "grid", "insert[0].placement", "\"random\", \"lattice\", \"file\"");
}

TEST(CaseReaderErrors, NotAllowedCombinations) {
  std::string t = minimal() + "[contact]\nnormal = \"hertz\"\nstiffness = 800.0\n";
  expect_error_at(t, "stiffness", "contact.stiffness", "not allowed with normal = \"hertz\"");

  t = kSimulation + kDomain + kSpecies + "[[insert]]\nspecies = \"glass\"\ncount = 3\n" +
      "placement = \"file\"\nfile = \"case.toml\"\n";
  expect_error_at(t, "count", "insert[0].count", "not allowed with placement = \"file\"");

  t = minimal() + "file = \"bed.data\"\n";
  expect_error_at(t, "file", "insert[0].file", "only with placement = \"file\"");

  t = kSimulation + kDomain + kSpecies + "[[insert]]\nspecies = \"glass\"\nplacement = \"file\"\n";
  expect_error_at(t, "[[insert]]", "insert[0].file", "missing required key");
}

TEST(CaseReaderErrors, ElasticConstantsForTheNormalModel) {
  // Which material keys each normal model takes (docs/case-file.md "[contact]"): Hertz-Mindlin
  // takes its k_t from the materials, so contact.stiffness_ratio is refused there; the linear
  // model's stiffnesses are contact keys, so a shear modulus or a rigid wall (which it would
  // ignore) is refused there.
  std::string t = minimal() + "[contact]\nnormal = \"hertz\"\nstiffness_ratio = 0.4\n";
  expect_error_at(t, "stiffness_ratio", "contact.stiffness_ratio",
                  "not allowed with normal = \"hertz\" (allowed: \"auto\")");
  const std::string linear = "[contact]\nnormal = \"linear\"\nstiffness = 1e4\n";
  t = kSimulation + kDomain + kSpecies + "shear_modulus = 4e6\n" + kInsert + linear;
  expect_error_at(t, "shear_modulus", "species[0].shear_modulus",
                  "not allowed with contact.normal = \"linear\"");
  t = kSimulation + kDomain + "[walls]\nyoungs_modulus = \"rigid\"\n" + kSpecies + kInsert + linear;
  expect_error_at(t, "rigid", "walls.youngs_modulus",
                  "not allowed with contact.normal = \"linear\"");
  t = kSimulation + kDomain + "[walls.z_lo]\nshear_modulus = 4e6\n" + kSpecies + kInsert + linear;
  expect_error_at(t, "shear_modulus", "walls.z_lo.shear_modulus", "contact.stiffness_ratio");
  // The same keys with Hertz are read.
  t = kSimulation + kDomain + "[walls]\nyoungs_modulus = \"rigid\"\n" + kSpecies +
      "shear_modulus = 4e6\n" + kInsert;
  const CaseSpec c = read_case_string(t, "case.toml");
  EXPECT_TRUE(std::isinf(c.domain.wall_material[4].youngs_modulus));
  EXPECT_EQ(c.species[0].material.shear_modulus, 4e6);
  EXPECT_EQ(c.species[0].material.poisson_ratio, 1e7 / 8e6 - 1.0);
}

TEST(CaseReaderErrors, ShearModulusRigidWallsAndInfiniteFriction) {
  auto species_with = [](const std::string& keys) {
    return kSimulation + kDomain + kSpecies + keys + kInsert;
  };
  // One of poisson_ratio and shear_modulus; G in (E/3, E/2].
  expect_error_at(species_with("poisson_ratio = 0.3\nshear_modulus = 4e6\n"), "shear_modulus",
                  "species[0].shear_modulus", "not allowed together with poisson_ratio");
  expect_error_at(species_with("shear_modulus = 6e6\n"), "shear_modulus",
                  "species[0].shear_modulus", "gives poisson_ratio E/(2G) - 1 = -0.1666");
  expect_error_at(species_with("shear_modulus = 3e6\n"), "shear_modulus",
                  "species[0].shear_modulus", "G in (E/3, E/2]");
  expect_error_at(species_with("shear_modulus = 0\n"), "shear_modulus", "species[0].shear_modulus",
                  "> 0");
  // Only walls can be rigid; a rigid wall takes no shear modulus (inherited or its own).
  expect_error_at(species_with("youngs_modulus = \"rigid\"\n"), "rigid",
                  "species[0].youngs_modulus", "only walls can be \"rigid\"");
  std::string t =
      kSimulation + kDomain + "[walls]\nyoungs_modulus = \"soft\"\n" + kSpecies + kInsert;
  expect_error_at(t, "soft", "walls.youngs_modulus", "or \"rigid\"");
  t = kSimulation + kDomain + "[walls]\nshear_modulus = 4e6\n[walls.z_lo]\n" +
      "youngs_modulus = \"rigid\"\n" + kSpecies + kInsert;
  expect_error_at(t, "rigid", "walls.z_lo.youngs_modulus", "takes no shear_modulus");
  // friction = inf is the sticking limit; -inf and nan are refused, and inf elsewhere too.
  const CaseSpec c = read_case_string(species_with("friction = inf\n"), "case.toml");
  EXPECT_TRUE(std::isinf(c.species[0].material.friction));
  expect_error_at(species_with("friction = -inf\n"), "friction", "species[0].friction",
                  "a number >= 0, or inf");
  expect_error_at(species_with("friction = nan\n"), "friction", "species[0].friction",
                  "a number >= 0, or inf");
  expect_error_at(species_with("rolling_friction = inf\n"), "rolling_friction",
                  "species[0].rolling_friction", "a number >= 0");
}

TEST(CaseReaderErrors, MissingInsertFile) {
  const TempDir dir("missing_file");
  const std::string t = kSimulation + kDomain + kSpecies +
                        "[[insert]]\nspecies = \"glass\"\nplacement = \"file\"\n" +
                        "file = \"nowhere.data\"\n";
  const fs::path path = dir.write("case.toml", t);
  try {
    (void)read_case_file(path.string());
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path.string() + ":" + std::to_string(line_of(t, "nowhere")) + ":", 0), 0u)
        << msg;
    EXPECT_NE(msg.find("insert[0].file: file not found: " + (dir.path / "nowhere.data").string()),
              std::string::npos)
        << msg;
  }
}

TEST(CaseReaderErrors, MissingCaseFile) {
  EXPECT_THROW((void)read_case_file("/nonexistent/fluidem/case.toml"), InputError);
  EXPECT_THROW((void)read_case_file(fs::temp_directory_path().string()), InputError);
}

// --- insert files ---------------------------------------------------------------------------

TEST(CaseReader, RelativeInsertFileResolvedAgainstCaseFolder) {
  const TempDir dir("relative");
  const fs::path data = dir.write("beds/bed.data", "# LAMMPS data\n");
  const std::string t = kSimulation + kDomain + kSpecies +
                        "[[insert]]\nspecies = \"glass\"\nplacement = \"file\"\n" +
                        "file = \"../beds/bed.data\"\n";
  const fs::path case_path = dir.write("cases/case.toml", t);
  // The current folder is not the case folder, so a cwd-relative lookup would fail.
  ASSERT_NE(fs::current_path(), case_path.parent_path());
  const CaseSpec c = read_case_file(case_path.string());
  ASSERT_EQ(c.inserts.size(), 1u);
  EXPECT_EQ(c.inserts[0].placement, Placement::File);
  EXPECT_EQ(c.inserts[0].count, 0);
  EXPECT_TRUE(fs::path(c.inserts[0].file).is_absolute());
  EXPECT_EQ(c.inserts[0].file, data.lexically_normal().string());
  EXPECT_EQ(c.source_file, case_path.string());
}

// --- command-line overrides -----------------------------------------------------------------

TEST(CaseReaderOverrides, AppliedByIndexAndByName) {
  const std::string t =
      minimal() + "[[species]]\nname = \"steel\"\ndiameter = 0.002\n" + "density = 7800.0\n";
  const CaseSpec c = read_case_string(
      t, "case.toml",
      {"simulation.end_time=0.25", "contact.normal=linear", "contact.stiffness = 1000",
       "species[0].restitution=0.8", "species.steel.friction=0.45", "insert[0].count=100",
       "walls.z_lo.friction=0.1", "simulation.time_step=1e-6",
       "insert[0].region.hi=[0.1, 0.004, 0.1]", "contact.rolling=\"spring_dashpot\"",
       "neighbour.skin=auto", "simulation.engine=hard_sphere", "hardsphere.tc_time=0",
       "hardsphere.max_events_per_particle=20"});
  EXPECT_EQ(c.simulation.end_time, 0.25);
  EXPECT_EQ(c.contact.normal.name, "linear");
  EXPECT_EQ(c.contact.normal.coefficients.at("stiffness"), 1000.0);
  EXPECT_EQ(c.species[0].material.restitution, 0.8);
  EXPECT_EQ(c.species[1].material.friction, 0.45);
  EXPECT_EQ(c.species[0].material.friction, 0.3);
  EXPECT_EQ(c.inserts[0].count, 100);
  EXPECT_EQ(c.domain.wall_material[static_cast<int>(Face::ZLo)].friction, 0.1);
  EXPECT_EQ(c.domain.wall_material[static_cast<int>(Face::ZHi)].friction, 0.3);
  EXPECT_EQ(c.simulation.time_step, 1e-6);
  EXPECT_EQ(c.inserts[0].region_hi[2], 0.1);
  EXPECT_EQ(c.inserts[0].region_lo, c.domain.lo);
  EXPECT_EQ(c.contact.rolling.name, "spring_dashpot");
  EXPECT_FALSE(c.neighbour.skin.has_value());
  EXPECT_EQ(c.simulation.engine, Engine::HardSphere);
  EXPECT_EQ(c.hardsphere.tc_time, 0.0);
  EXPECT_EQ(c.hardsphere.max_events_per_particle, 20.0);
  // Overridden keys are located at "--set"; the others keep their file position.
  EXPECT_EQ(c.where("simulation.end_time").file, "--set");
  EXPECT_EQ(c.where("species[1].friction").file, "--set");
  EXPECT_EQ(c.where("walls.z_lo.friction").file, "--set");
  EXPECT_EQ(c.where("simulation.engine").file, "--set");
  EXPECT_EQ(c.where("hardsphere.tc_time").file, "--set");
  EXPECT_EQ(c.where("species[0].diameter").str(),
            "case.toml:" + std::to_string(line_of(t, "diameter")) + ":1");
}

TEST(CaseReaderOverrides, ValidatedLikeTheFile) {
  std::string msg = error_of(minimal(), {"species[0].restitution=2"});
  EXPECT_EQ(msg.rfind("--set: species[0].restitution: ", 0), 0u) << msg;
  EXPECT_NE(msg.find("[0, 1]"), std::string::npos) << msg;

  msg = error_of(minimal(), {"species.glass.diameter=-1"});
  EXPECT_EQ(msg.rfind("--set: species[0].diameter: ", 0), 0u) << msg;

  msg = error_of(minimal(), {"simulation.end_time=soon"}); // bare string, wrong type
  EXPECT_EQ(msg.rfind("--set: simulation.end_time: expected a number, got the string \"soon\"", 0),
            0u)
      << msg;

  msg = error_of(minimal(), {"contact.normal=linear"}); // now stiffness is required
  EXPECT_NE(msg.find("contact.stiffness: missing required key"), std::string::npos) << msg;

  msg = error_of(minimal(), {"hardsphere.tc_time=-1"});
  EXPECT_EQ(msg.rfind("--set: hardsphere.tc_time: -1.0 is out of range (allowed: a number >= 0", 0),
            0u)
      << msg;

  msg = error_of(minimal(), {"hardsphere.max_events_per_particle=0"});
  EXPECT_EQ(msg.rfind("--set: hardsphere.max_events_per_particle: 0.0 is out of range", 0), 0u)
      << msg;

  msg = error_of(minimal(), {"simulation.engine=dsmc"});
  EXPECT_EQ(msg, "--set: simulation.engine: unknown value \"dsmc\" (allowed: \"soft_sphere\", "
                 "\"hard_sphere\")");

  msg = error_of(minimal(), {"insert[0].species=steel"});
  EXPECT_EQ(msg.rfind("--set: insert[0].species: unknown species \"steel\"", 0), 0u) << msg;
}

TEST(CaseReaderOverrides, UnknownKeysSuggested) {
  EXPECT_EQ(error_of(minimal(), {"contact.stifness=1"}),
            "--set: contact.stifness: unknown key (did you mean \"contact.stiffness\"?)");
  EXPECT_EQ(error_of(minimal(), {"simulaton.end_time=1"}),
            "--set: simulaton.end_time: unknown key (did you mean \"simulation\"?)");
  EXPECT_EQ(error_of(minimal(), {"species.glass.restitutoin=1"}),
            "--set: species.glass.restitutoin: unknown key (did you mean "
            "\"species.glass.restitution\"?)");
  EXPECT_EQ(error_of(minimal(), {"walls.z_lo.frictoin=1"}),
            "--set: walls.z_lo.frictoin: unknown key (did you mean \"walls.z_lo.friction\"?)");
  EXPECT_EQ(error_of(minimal(), {"insert[0].region.hj=[1,1,1]"}),
            "--set: insert[0].region.hj: unknown key (did you mean \"insert[0].region.hi\"?)");
  EXPECT_EQ(error_of(minimal(), {"hardsphere.tc_tim=1"}),
            "--set: hardsphere.tc_tim: unknown key (did you mean \"hardsphere.tc_time\"?)");
  EXPECT_EQ(error_of(minimal(), {"hardspere.tc_time=1"}),
            "--set: hardspere.tc_time: unknown key (did you mean \"hardsphere\"?)");
  EXPECT_EQ(error_of(minimal(), {"simulation.engin=hard_sphere"}),
            "--set: simulation.engin: unknown key (did you mean \"simulation.engine\"?)");
  std::string msg = error_of(minimal(), {"walls.z_top.friction=1"});
  EXPECT_NE(msg.find("did you mean \"walls.z_lo\"?"), std::string::npos) << msg;
}

TEST(CaseReaderOverrides, BadPaths) {
  std::string msg = error_of(minimal(), {"species.steel.friction=0.1"});
  EXPECT_EQ(msg.rfind("--set: species.steel.friction: no species named \"steel\"", 0), 0u) << msg;
  EXPECT_NE(msg.find("\"glass\""), std::string::npos) << msg;

  msg = error_of(minimal(), {"insert[3].count=1"});
  EXPECT_EQ(msg.rfind("--set: insert[3].count: index out of range", 0), 0u) << msg;

  msg = error_of(minimal(), {"insert.count=1"});
  EXPECT_EQ(msg.rfind("--set: insert.count: needs an index", 0), 0u) << msg;

  msg = error_of(minimal(), {"simulation.end_time"});
  EXPECT_EQ(msg.rfind("--set: simulation.end_time: expected key=value", 0), 0u) << msg;

  msg = error_of(minimal(), {"simulation=1"});
  EXPECT_EQ(msg.rfind("--set: simulation: names a table", 0), 0u) << msg;

  msg = error_of(minimal(), {"simulation.end_time.x=1"});
  EXPECT_EQ(msg.rfind("--set: simulation.end_time.x: unknown key", 0), 0u) << msg;

  msg = error_of(minimal(), {"species[x].friction=1"});
  EXPECT_EQ(msg.rfind("--set: species[x].friction: malformed key", 0), 0u) << msg;
}

// output.layers: an integer >= 0; negative, fractional or text values are errors at the key.
TEST(CaseReader, OutputLayersMustBeANonNegativeInteger) {
  const std::string base = "[simulation]\nend_time = 1\n"
                           "[domain]\nlo = [0, 0, 0]\nhi = [1, 1, 1]\n"
                           "[[species]]\nname = \"s\"\ndiameter = 0.1\ndensity = 1\n"
                           "[[insert]]\nspecies = \"s\"\ncount = 1\n[output]\n";
  EXPECT_EQ(read_case_string(base + "layers = 0\n", "case.toml").output.layers, 0);
  EXPECT_EQ(read_case_string(base + "layers = 12\n", "case.toml").output.layers, 12);
  for (const char* bad : {"layers = -1", "layers = 2.5", "layers = \"4\"", "layers = 3000000000"})
    expect_error_at(base + bad + "\n", bad, "output.layers", "integer >= 0");
}

// [output.continuum]: cells >= 1 (ny = 1 in 2-D), method "volume" | "weighted", width > 0 and
// required for "weighted" (rejected for "volume"), cutoff > 0, interval > 0, stride >= 1,
// width x cutoff at most half a periodic length, soft-sphere engine only; errors name the key
// and its line.
TEST(CaseReader, OutputContinuumKeysAreValidated) {
  const std::string base = "[simulation]\nend_time = 1\n"
                           "[domain]\nlo = [0, 0, 0]\nhi = [1, 1, 1]\nperiodic = [true, false, "
                           "false]\n"
                           "[[species]]\nname = \"s\"\ndiameter = 0.1\ndensity = 1\n"
                           "[[insert]]\nspecies = \"s\"\ncount = 1\n[output.continuum]\n";
  const CaseSpec a = read_case_string(base + "cells = [4, 3, 2]\n", "case.toml");
  ASSERT_TRUE(a.output.continuum.has_value());
  EXPECT_EQ(a.output.continuum->cells, (std::array<int, 3>{4, 3, 2}));
  EXPECT_EQ(a.output.continuum->method, ContinuumMethod::Volume);
  EXPECT_EQ(a.output.continuum->interval, 0.0);
  EXPECT_EQ(a.output.continuum->stride, 1);
  EXPECT_FALSE(read_case_string(minimal(), "case.toml").output.continuum.has_value());
  const CaseSpec b = read_case_string(base + "cells = [4, 3, 2]\nmethod = \"weighted\"\n"
                                             "width = 0.05\ncutoff = 4\ninterval = 0.02\n"
                                             "stride = 5\n",
                                      "case.toml");
  EXPECT_EQ(b.output.continuum->method, ContinuumMethod::Weighted);
  EXPECT_EQ(b.output.continuum->width, 0.05);
  EXPECT_EQ(b.output.continuum->cutoff, 4.0);
  EXPECT_EQ(b.output.continuum->interval, 0.02);
  EXPECT_EQ(b.output.continuum->stride, 5);

  const std::string w = base + "cells = [4, 3, 2]\nmethod = \"weighted\"\n";
  expect_error_at(base + "cells = [0, 3, 2]\n", "cells = [0", "output.continuum.cells[0]",
                  "each >= 1");
  expect_error_at(base + "cells = [4, 3]\n", "cells = [4, 3]", "output.continuum.cells",
                  "array of 3 integers");
  expect_error_at(w + "width = -0.1\n", "width = -0.1", "output.continuum.width", "> 0");
  expect_error_at(w + "width = 0\n", "width = 0", "output.continuum.width", "> 0");
  expect_error_at(w + "width = 0.1\ncutoff = 0\n", "cutoff = 0", "output.continuum.cutoff", "> 0");
  expect_error_at(w + "width = 0.2\n", "width = 0.2", "output.continuum.width",
                  "half the periodic length along x");
  expect_error_at(w, "[output.continuum]", "output.continuum.width", "missing required key");
  expect_error_at(base + "cells = [1, 1, 1]\nmethod = \"gauss\"\n",
                  "method =", "output.continuum.method", "\"volume\", \"weighted\"");
  expect_error_at(base + "cells = [1, 1, 1]\nwidth = 0.1\n", "width =", "output.continuum.width",
                  "only with method = \"weighted\"");
  expect_error_at(base + "cells = [1, 1, 1]\ninterval = -1\n",
                  "interval =", "output.continuum.interval", "> 0");
  expect_error_at(base + "cells = [1, 1, 1]\nstride = 0\n", "stride =", "output.continuum.stride",
                  "integer >= 1");
  expect_error_at(base + "cells = [1, 1, 1]\nsize = 3\n", "size =", "output.continuum.size",
                  "unknown key");
  expect_error_at(base, "[output.continuum]", "output.continuum.cells", "missing required key");
}

} // namespace
} // namespace fluidem
