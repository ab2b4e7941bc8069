// The command line as a user meets it: the real fluidem binary (FLUIDEM_BINARY) run on small case
// files written to a temporary folder, with its exit code, stdout and stderr captured.
// Exit codes (README.md): 0 success, 2 invalid input (case file or command line), 3 unstable run.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "../../common/bouncing_spheres.hpp"
#include "../../common/cli_runner.hpp"
#include "../../common/linear_impact.hpp"

namespace {

namespace fs = std::filesystem;

using fluidem::test::contains;
using fluidem::test::fluidem;
using fluidem::test::quote;
using fluidem::test::read_file;
using fluidem::test::replace;
using fluidem::test::Result;
using fluidem::test::TempDir;

/// 1-based line of the first line of `text` that starts with `marker` (0 if none).
long line_of(const std::string& text, const std::string& marker) {
  std::istringstream in(text);
  std::string line;
  for (long n = 1; std::getline(in, line); ++n)
    if (line.rfind(marker, 0) == 0) return n;
  return 0;
}

// A valid 2-D case: ten 4 mm glass discs on a lattice in a 40 x 40 mm box, linear k = 800 N/m
// (Tsuji's value), e = 0.9 (the default).
const std::string kValid = fluidem::test::resting_discs_case();

// --- version and help -------------------------------------------------------------------------

TEST(Cli, Version) {
  TempDir dir;
  const Result r = fluidem({"--version"}, dir.path);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(^fluidem [0-9]+\.[0-9]+\.[0-9]+\s*$)")))
      << r.out;
}

TEST(Cli, Help) {
  TempDir dir;
  const Result top = fluidem({"--help"}, dir.path);
  EXPECT_EQ(top.code, 0) << top.err;
  for (const char* word : {"run", "check", "Exit codes"})
    EXPECT_TRUE(contains(top.out, word)) << word;

  const Result run = fluidem({"run", "--help"}, dir.path);
  EXPECT_EQ(run.code, 0) << run.err;
  for (const char* word : {"run", "--set", "--threads", "--out"})
    EXPECT_TRUE(contains(run.out, word)) << word << " not in:\n" << run.out;

  const Result check = fluidem({"check", "--help"}, dir.path);
  EXPECT_EQ(check.code, 0) << check.err;
  EXPECT_TRUE(contains(check.out, "--set")) << check.out;
}

TEST(Cli, BadCommandLineExits2) {
  TempDir dir;
  EXPECT_EQ(fluidem({}, dir.path).code, 2);             // no subcommand
  EXPECT_EQ(fluidem({"frobnicate"}, dir.path).code, 2); // unknown subcommand
  EXPECT_EQ(fluidem({"run"}, dir.path).code, 2);        // no case file
  EXPECT_EQ(fluidem({"run", "x.toml", "--bogus"}, dir.path).code, 2);
  EXPECT_EQ(fluidem({"run", "x.toml", "--threads", "-1"}, dir.path).code, 2);
}

// --- check on a valid case --------------------------------------------------------------------

/// The number printed after `label` (the first one on its line), or NaN.
double number_after(const std::string& text, const std::string& label) {
  std::smatch m;
  const std::regex re(label + R"(\s+([-+0-9.eE]+))");
  if (!std::regex_search(text, m, re)) return std::nan("");
  return std::stod(m[1].str());
}

TEST(Cli, CheckValidCasePrintsDerivedQuantities) {
  TempDir dir;
  const fs::path c = dir.write("case.toml", kValid);
  const Result r = fluidem({"check", c.string()}, dir.path);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;

  // Worked out here: m = 2700 * 4/3 pi (2 mm)^3 per particle (discs carry a sphere's mass);
  // linear contact duration: the force pulse of the impact whose force never pulls
  // (tests/common/linear_impact.hpp) with m* = m/2 for a pair and m for a wall; the stable step is
  // t_c/10, the automatic one 0.02 t_c.
  const double pi = std::numbers::pi;
  const double m = 2700.0 * 4.0 / 3.0 * pi * 0.002 * 0.002 * 0.002;
  const double tc_pair = fluidem::test::linear_impact_for_restitution(0.5 * m, 800.0, 0.9).duration;
  const double tc_wall = fluidem::test::linear_impact_for_restitution(m, 800.0, 0.9).duration;
  // Printed with 4 significant digits.
  auto near = [](double got, double want) { return std::abs(got - want) <= 1e-3 * want; };

  EXPECT_EQ(number_after(r.out, "particles"), 10.0) << r.out;
  EXPECT_PRED2(near, number_after(r.out, "total mass"), 10 * m) << r.out;
  EXPECT_PRED2(near, number_after(r.out, "glass-glass"), tc_pair) << r.out;
  EXPECT_PRED2(near, number_after(r.out, "glass-wall z_lo"), tc_wall) << r.out;
  EXPECT_PRED2(near, number_after(r.out, "largest stable dt"), tc_pair / 10) << r.out;
  EXPECT_PRED2(near, number_after(r.out, "chosen dt"), 0.02 * tc_pair) << r.out;
  // Under its own weight: column height h = 10 pi r^2 / (0.82 * 0.04 m), a bottom disc carries
  // m g h / d, delta = that / k (simulation.cpp's estimate), printed as a fraction of d.
  const double h = 10 * pi * 0.002 * 0.002 / (0.82 * 0.04);
  const double overlap = m * 9.81 * h / 0.004 / 800.0 / 0.004;
  auto near3 = [](double got, double want) { return std::abs(got - want) <= 5e-3 * want; };
  EXPECT_PRED2(near3, number_after(r.out, "expected overlap"), overlap) << r.out; // 3 digits
  EXPECT_TRUE(contains(r.out, "case is valid")) << r.out;
}

// --- every class of bad input: exit 2, one line naming file:line and the key ------------------

struct BadInput {
  const char* label;
  std::string text;   ///< the case file
  std::string marker; ///< start of the line the message must point at
  std::string key;    ///< the key it must name ("" for a TOML syntax error)
  std::string what;   ///< part of the explanation
};

std::vector<BadInput> bad_inputs() {
  const std::string species_end = "density = 2700.0\n";
  return {
      {"syntax", replace(kValid, "end_time = 0.02\n", "end_time = 0.02 = 3\n"), "end_time", "",
       "TOML syntax error"},
      {"unknown_key", replace(kValid, "density = 2700.0", "densty = 2700.0"), "densty",
       "species[0].densty", "unknown key (did you mean \"density\"?)"},
      {"wrong_type", replace(kValid, "density = 2700.0", "density = \"heavy\""), "density",
       "species[0].density", "expected a number"},
      {"restitution_1_5", replace(kValid, species_end, species_end + "restitution = 1.5\n"),
       "restitution", "species[0].restitution", "out of range"},
      {"negative_friction", replace(kValid, species_end, species_end + "friction = -0.1\n"),
       "friction", "species[0].friction", "out of range"},
      {"diameter_0", replace(kValid, "diameter = 0.004", "diameter = 0"), "diameter",
       "species[0].diameter", "out of range"},
      {"missing_required", replace(kValid, "end_time = 0.02\n", ""), "[simulation]",
       "simulation.end_time", "missing"},
      // Linear k = 800 N/m: the pair contact lasts 0.75 ms, so the limit is 75 us.
      {"time_step_unstable",
       replace(kValid, "end_time = 0.02\n", "end_time = 0.02\ntime_step = 1e-2\n"), "time_step",
       "simulation.time_step", "stability limit"},
      {"too_many_lattice", replace(kValid, "count = 10\n", "count = 1000\n"), "count",
       "insert[0].count", "at most 100"},
      {"too_many_random",
       replace(replace(kValid, "count = 10\n", "count = 150\n"), "placement = \"lattice\"\n", ""),
       "count", "insert[0].count", "fit"},
      {"walton_braun_without_stiffness",
       replace(replace(kValid, "normal = \"linear\"", "normal = \"walton_braun\""),
               "stiffness = 800.0\n", ""),
       "[contact]", "contact.stiffness", "missing required key"},
  };
}

void expect_one_line_error(const Result& r, const fs::path& file, long line, const std::string& key,
                           const std::string& what) {
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line:\n" << r.err;
  std::string where = "error: " + file.string();
  if (line > 0) where += ":" + std::to_string(line) + ":";
  EXPECT_EQ(r.err.rfind(where, 0), 0u) << "expected it to start with '" << where << "':\n" << r.err;
  if (!key.empty()) {
    EXPECT_TRUE(contains(r.err, ": " + key + ": ")) << key << " not in:\n" << r.err;
  }
  EXPECT_TRUE(contains(r.err, what)) << "'" << what << "' not in:\n" << r.err;
}

TEST(Cli, BadInputExits2WithOneLineNamingFileLineAndKey) {
  TempDir dir;
  for (const auto& b : bad_inputs()) {
    SCOPED_TRACE(b.label);
    const fs::path c = dir.write(std::string(b.label) + ".toml", b.text);
    const long line = line_of(b.text, b.marker);
    ASSERT_GT(line, 0) << b.marker;
    expect_one_line_error(fluidem({"check", c.string()}, dir.path), c, line, b.key, b.what);
    // `run` rejects it the same way, before writing anything.
    const fs::path out = dir.path / (std::string(b.label) + "_out");
    const Result run =
        fluidem({"run", c.string(), "--out", out.string(), "--threads", "1"}, dir.path);
    expect_one_line_error(run, c, line, b.key, b.what);
    EXPECT_FALSE(fs::exists(out / "series.csv"));
  }
}

TEST(Cli, ForcedTimeStepIsAcceptedByCheck) {
  TempDir dir;
  const fs::path c = dir.write(
      "forced.toml", replace(kValid, "end_time = 0.02\n",
                             "end_time = 0.02\ntime_step = 1e-2\nforce_time_step = true\n"));
  const Result r = fluidem({"check", c.string()}, dir.path);
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_TRUE(contains(r.out, "FORCED")) << r.out;
}

TEST(Cli, OverlapAtInsertionExits2) {
  TempDir dir;
  // Two 4 mm particles 3 mm apart: they overlap by a quarter of a diameter.
  dir.write("two.data", R"(LAMMPS data file: two overlapping particles

2 atoms
1 atom types

0 0.04 xlo xhi
0 0.004 ylo yhi
0 0.04 zlo zhi

Atoms # sphere

1 1 0.004 2700 0.010 0.002 0.010
2 1 0.004 2700 0.013 0.002 0.010
)");
  const std::string text = replace(replace(kValid, "count = 10\n", "file = \"two.data\"\n"),
                                   "placement = \"lattice\"", "placement = \"file\"");
  const fs::path c = dir.write("overlap.toml", text);
  expect_one_line_error(fluidem({"check", c.string()}, dir.path), c, line_of(text, "[[insert]]"),
                        "insert", "particles 1 and 2 overlap by 0.25");
}

// The event-driven engine cannot start from an overlap (hard_sphere_engine.cpp stops when a pair
// is closer than (1 - 5e-7) of its contact distance): with engine = "hard_sphere" an overlap of
// 1e-5 of a diameter, which the soft-sphere engine's default tolerance (0.01) lets through, is
// refused at set-up naming the pair; spheres exactly touching are accepted by both.
TEST(Cli, HardSphereStartRefusesAnyOverlap) {
  TempDir dir;
  const auto data = [](const char* x2) {
    return fmt::format("LAMMPS data file: two particles\n\n2 atoms\n1 atom types\n\n"
                       "Atoms # sphere\n\n1 1 0.004 2700 0.010 0.002 0.010\n"
                       "2 1 0.004 2700 {} 0.002 0.010\n",
                       x2);
  };
  dir.write("overlap.data", data("0.01399996")); // 4e-8 m: 1e-5 of the diameter
  dir.write("touch.data", data("0.014"));
  for (const char* file : {"overlap.data", "touch.data"}) {
    const std::string text =
        replace(replace(kValid, "count = 10\n", fmt::format("file = \"{}\"\n", file)),
                "placement = \"lattice\"", "placement = \"file\"");
    const fs::path c = dir.write("case.toml", text);
    SCOPED_TRACE(file);
    EXPECT_EQ(fluidem({"check", c.string()}, dir.path).code, 0);
    const Result hard =
        fluidem({"check", c.string(), "--set", "simulation.engine=\"hard_sphere\""}, dir.path);
    if (std::string(file) == "touch.data") {
      EXPECT_EQ(hard.code, 0) << hard.out << hard.err;
    } else {
      EXPECT_EQ(hard.code, 2) << hard.out << hard.err;
      EXPECT_TRUE(contains(hard.err, "particles 1 and 2 overlap by 1e-05")) << hard.err;
      EXPECT_TRUE(contains(hard.err, "engine = \"hard_sphere\": none")) << hard.err;
    }
  }
}

TEST(Cli, UnknownSetKeyExits2) {
  TempDir dir;
  const fs::path c = dir.write("case.toml", kValid);
  for (const char* cmd : {"check", "run"}) {
    SCOPED_TRACE(cmd);
    const Result r = fluidem({cmd, c.string(), "--set", "contact.stifness=3"}, dir.path);
    EXPECT_EQ(r.code, 2) << r.out << r.err;
    EXPECT_EQ(
        r.err,
        "error: --set: contact.stifness: unknown key (did you mean \"contact.stiffness\"?)\n");
  }
  // A valid override is applied: the count changes.
  const Result ok = fluidem({"check", c.string(), "--set", "insert[0].count=7"}, dir.path);
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_EQ(number_after(ok.out, "particles"), 7.0) << ok.out;
}

TEST(Cli, MissingCaseFileExits2) {
  TempDir dir;
  const fs::path c = dir.path / "no_such_case.toml";
  for (const char* cmd : {"check", "run"}) {
    SCOPED_TRACE(cmd);
    const Result r = fluidem({cmd, c.string()}, dir.path);
    expect_one_line_error(r, c, 0, "", "does not exist (allowed: a readable TOML case file)");
  }
}

// --- runs -------------------------------------------------------------------------------------

TEST(Cli, UnstableRunExits3AndKeepsItsOutputs) {
  TempDir dir;
  // Ten discs dropped from 20-40 mm onto the floor with a step 27x the stability limit.
  const std::string text =
      replace(replace(kValid, "end_time = 0.02\n",
                      "end_time = 0.5\ntime_step = 2e-3\nforce_time_step = true\n"),
              "placement = \"lattice\"\n",
              "seed = 3\nregion = { lo = [0.0, 0.0, 0.02], hi = [0.04, 0.004, 0.04] }\n");
  const fs::path c = dir.write("unstable.toml", text);
  const fs::path out = dir.path / "out";
  const Result r = fluidem({"run", c.string(), "--out", out.string(), "--threads", "1"}, dir.path);
  EXPECT_EQ(r.code, 3) << r.out << r.err;
  EXPECT_TRUE(std::regex_search(r.err, std::regex(R"(unstable.*particle [0-9]+)"))) << r.err;
  EXPECT_TRUE(contains(r.err, out.string())) << "should say where the outputs are:\n" << r.err;
  ASSERT_TRUE(fs::exists(out / "series.csv"));
  EXPECT_TRUE(fs::exists(out / "particles.h5"));
  const std::string series = read_file(out / "series.csv");
  EXPECT_EQ(series.rfind("time,", 0), 0u) << series;
  EXPECT_GE(std::count(series.begin(), series.end(), '\n'), 2) << "header and at least one row";
}

// A small 3-D Hertz run: particles from a data file at the bottom, random ones above with random
// velocities, so that the run exercises contacts, walls and the random generator.
const std::string kSmallRun = R"([simulation]
dimension = 3
end_time = 0.02

[output]
frame_interval = 0.01
series_interval = 0.001

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.02, 0.04]

[walls]
restitution = 0.8

[[species]]
name = "glass"
diameter = 0.004
density = 2700.0
rolling_friction = 0.05

[[insert]]
species = "glass"
placement = "file"
file = "bottom.data"

[[insert]]
species = "glass"
count = 8
seed = 7
region = { lo = [0.0, 0.0, 0.01], hi = [0.02, 0.02, 0.04] }
velocity_spread = 0.3

[contact]
rolling = "constant_torque"
)";

const std::string kBottomData = R"(LAMMPS data file: two particles on the floor

2 atoms
1 atom types

0 0.02 xlo xhi
0 0.02 ylo yhi
0 0.04 zlo zhi

Atoms # sphere

1 1 0.004 2700 0.005 0.01 0.002 0 0 0
2 1 0.004 2700 0.0091 0.01 0.002 0 0 0
)";

TEST(Cli, ResolvedCaseReproducesTheRunBitwise) {
  TempDir dir;
  fs::create_directories(dir.path / "case");
  dir.write("case/bottom.data", kBottomData);
  const fs::path c = dir.write("case/small.toml", kSmallRun);
  const fs::path out1 = dir.path / "run1", out2 = dir.path / "run2";

  const Result r1 =
      fluidem({"run", c.string(), "--out", out1.string(), "--threads", "1"}, dir.path);
  ASSERT_EQ(r1.code, 0) << r1.out << r1.err;
  EXPECT_TRUE(contains(r1.out, "threads            1")) << r1.out;
  EXPECT_TRUE(std::regex_search(r1.out, std::regex(R"([0-9.e+]+ particle-steps/s)"))) << r1.out;
  EXPECT_TRUE(std::regex_search(r1.out, std::regex(R"(memory [0-9]+ bytes per particle)")))
      << r1.out;
  for (const char* f : {"case.resolved.toml", "series.csv", "particles.h5", "particles.xmf"})
    EXPECT_TRUE(fs::exists(out1 / f)) << f;

  // The resolved case names the insert file by an absolute path, so it runs from anywhere.
  const std::string resolved = read_file(out1 / "case.resolved.toml");
  EXPECT_TRUE(contains(resolved, (dir.path / "case" / "bottom.data").string())) << resolved;
  const fs::path moved = dir.write("elsewhere.toml", resolved);
  const Result r2 =
      fluidem({"run", moved.string(), "--out", out2.string(), "--threads", "1"}, dir.path);
  ASSERT_EQ(r2.code, 0) << r2.out << r2.err;

  const std::string s1 = read_file(out1 / "series.csv"), s2 = read_file(out2 / "series.csv");
  EXPECT_GE(std::count(s1.begin(), s1.end(), '\n'), 20) << s1;
  EXPECT_TRUE(s1 == s2) << "series.csv differs:\n" << s1 << "\n---\n" << s2;
  // Something happened: the particles moved and touched (n_contacts column > 0 somewhere).
  EXPECT_TRUE(std::regex_search(s1, std::regex(R"(,[1-9][0-9]*,[0-9.e+-]+,[0-9]+\n)"))) << s1;
  // Resolving is idempotent: the resolved case of the rerun is the same file, but for the run ID
  // of its first line (each run has its own: output/run_outputs.hpp) and the case file its
  // second line names (the one each run was started from).
  const auto body = [](const std::string& text) {
    std::size_t k = text.find('\n');
    if (text.compare(k + 1, 13, "# case file: ") == 0) k = text.find('\n', k + 1);
    return text.substr(k);
  };
  const std::string resolved2 = read_file(out2 / "case.resolved.toml");
  EXPECT_TRUE(
      contains(resolved, "\n# case file: " + fs::absolute(c).lexically_normal().string() + "\n"))
      << resolved;
  EXPECT_TRUE(contains(resolved2,
                       "\n# case file: " + fs::absolute(moved).lexically_normal().string() + "\n"))
      << resolved2;
  EXPECT_EQ(body(resolved2), body(resolved));
  EXPECT_NE(resolved2.substr(0, resolved2.find('\n')), resolved.substr(0, resolved.find('\n')));
}

TEST(Cli, DefaultOutputFolderIsOutSlashCaseName) {
  TempDir dir;
  dir.write("tiny.toml", replace(kValid, "end_time = 0.02\n", "end_time = 0.001\n"));
  const Result r = fluidem({"run", "tiny.toml", "--threads", "1"}, dir.path);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_TRUE(fs::exists(dir.path / "out" / "tiny" / "series.csv"));
  EXPECT_TRUE(fs::exists(dir.path / "out" / "tiny" / "case.resolved.toml"));
}

} // namespace

namespace {

// docs/case-file.md lists only what runs (issue 32, item 13): every value its [contact] table
// gives as allowed for `normal`, `tangential` and `rolling` is accepted by `fluidem check`
// (walton_braun used to be listed, then refused at run time).
TEST(Cli, EveryDocumentedContactModelIsAccepted) {
  TempDir dir;
  const std::string doc = read_file(fs::path(FLUIDEM_SOURCE_DIR) / "docs" / "case-file.md");
  const std::string section = doc.substr(doc.find("## `[contact]`"));
  int checked = 0;
  for (const std::string key : {"normal", "tangential", "rolling"}) {
    const std::size_t row = section.find("| `" + key + "` |");
    ASSERT_NE(row, std::string::npos) << key;
    const std::string line = section.substr(row, section.find('\n', row) - row);
    const std::string allowed = line.substr(line.rfind('|', line.size() - 2));
    const std::regex quoted("\"([a-z_]+)\"");
    for (auto it = std::sregex_iterator(allowed.begin(), allowed.end(), quoted);
         it != std::sregex_iterator(); ++it) {
      const std::string value = (*it)[1].str();
      std::string text = kValid;
      if (key == "normal" && value == "walton_braun") // takes the stiffness (its k1)
        text = replace(text, "normal = \"linear\"", "normal = \"" + value + "\"");
      else if (key == "normal" && value == "jkr") // takes the adhesion energy
        text = replace(replace(text, "normal = \"linear\"", "normal = \"jkr\""),
                       "stiffness = 800.0\n", "adhesion_energy = 0.05\n");
      else if (key == "normal" && value != "linear")
        text = replace(replace(text, "normal = \"linear\"", "normal = \"" + value + "\""),
                       "stiffness = 800.0\n", "");
      else if (key != "normal")
        text += key + " = \"" + value + "\"\n";
      const fs::path c = dir.write("case_" + key + "_" + value + ".toml", text);
      const Result r = fluidem({"check", c.string()}, dir.path);
      EXPECT_EQ(r.code, 0) << key << " = \"" << value << "\" is documented but refused: " << r.err;
      ++checked;
    }
  }
  EXPECT_GE(checked, 7);
}

} // namespace
