// Case-file writer: write_case_toml() then read_case_string() gives back the identical CaseSpec,
// bit for bit in every double; every key is written; insert files are written absolute.
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <string>
#include <unistd.h>

#include "io/case_reader.hpp"
#include "io/case_writer.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;

/// Bitwise equality of doubles (so -0.0 != 0.0 and the last ulp counts).
::testing::AssertionResult same_bits(double a, double b) {
  if (std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b))
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << format_double(a) << " != " << format_double(b);
}

void expect_same(const std::array<double, 3>& a, const std::array<double, 3>& b,
                 const std::string& what) {
  for (std::size_t i = 0; i < 3; ++i) EXPECT_TRUE(same_bits(a[i], b[i])) << what << "[" << i << "]";
}

void expect_same(const std::optional<double>& a, const std::optional<double>& b,
                 const std::string& what) {
  ASSERT_EQ(a.has_value(), b.has_value()) << what;
  if (a) {
    EXPECT_TRUE(same_bits(*a, *b)) << what;
  }
}

void expect_same(const MaterialSpec& a, const MaterialSpec& b, const std::string& what) {
  EXPECT_TRUE(same_bits(a.youngs_modulus, b.youngs_modulus)) << what;
  EXPECT_TRUE(same_bits(a.poisson_ratio, b.poisson_ratio)) << what;
  expect_same(a.shear_modulus, b.shear_modulus, what + " shear_modulus");
  EXPECT_TRUE(same_bits(a.restitution, b.restitution)) << what;
  EXPECT_TRUE(same_bits(a.friction, b.friction)) << what;
  EXPECT_TRUE(same_bits(a.tangential_restitution, b.tangential_restitution)) << what;
  EXPECT_TRUE(same_bits(a.rolling_friction, b.rolling_friction)) << what;
}

/// Every field of the case except source_file and locations (which say where a key was read).
void expect_same(const CaseSpec& a, const CaseSpec& b) {
  EXPECT_EQ(a.simulation.engine, b.simulation.engine);
  EXPECT_EQ(a.simulation.dimension, b.simulation.dimension);
  EXPECT_TRUE(same_bits(a.simulation.end_time, b.simulation.end_time));
  expect_same(a.simulation.time_step, b.simulation.time_step, "time_step");
  EXPECT_TRUE(same_bits(a.simulation.time_step_fraction, b.simulation.time_step_fraction));
  EXPECT_EQ(a.simulation.force_time_step, b.simulation.force_time_step);
  expect_same(a.simulation.gravity, b.simulation.gravity, "gravity");
  EXPECT_TRUE(same_bits(a.simulation.insertion_overlap_tolerance,
                        b.simulation.insertion_overlap_tolerance));
  EXPECT_TRUE(same_bits(a.output.frame_interval, b.output.frame_interval));
  EXPECT_TRUE(same_bits(a.output.series_interval, b.output.series_interval));
  EXPECT_EQ(a.output.layers, b.output.layers);
  expect_same(a.domain.lo, b.domain.lo, "domain.lo");
  expect_same(a.domain.hi, b.domain.hi, "domain.hi");
  EXPECT_EQ(a.domain.periodic, b.domain.periodic);
  for (std::size_t f = 0; f < 6; ++f)
    expect_same(a.domain.wall_material[f], b.domain.wall_material[f],
                std::string("walls.") + kFaceNames[f]);
  ASSERT_EQ(a.species.size(), b.species.size());
  for (std::size_t i = 0; i < a.species.size(); ++i) {
    EXPECT_EQ(a.species[i].name, b.species[i].name);
    EXPECT_TRUE(same_bits(a.species[i].diameter, b.species[i].diameter));
    EXPECT_TRUE(same_bits(a.species[i].density, b.species[i].density));
    expect_same(a.species[i].material, b.species[i].material, "species " + std::to_string(i));
  }
  ASSERT_EQ(a.inserts.size(), b.inserts.size());
  for (std::size_t i = 0; i < a.inserts.size(); ++i) {
    const InsertSpec& x = a.inserts[i];
    const InsertSpec& y = b.inserts[i];
    EXPECT_EQ(x.species, y.species);
    EXPECT_EQ(x.count, y.count);
    expect_same(x.region_lo, y.region_lo, "region_lo");
    expect_same(x.region_hi, y.region_hi, "region_hi");
    EXPECT_EQ(x.placement, y.placement);
    EXPECT_EQ(x.file, y.file);
    expect_same(x.velocity, y.velocity, "velocity");
    EXPECT_TRUE(same_bits(x.velocity_spread, y.velocity_spread));
    EXPECT_EQ(x.seed, y.seed);
  }
  for (const auto& [x, y] : {std::pair{&a.contact.normal, &b.contact.normal},
                             std::pair{&a.contact.tangential, &b.contact.tangential},
                             std::pair{&a.contact.rolling, &b.contact.rolling}}) {
    EXPECT_EQ(x->name, y->name);
    ASSERT_EQ(x->coefficients.size(), y->coefficients.size()) << x->name;
    for (const auto& [key, value] : x->coefficients) {
      ASSERT_TRUE(y->coefficients.contains(key)) << key;
      EXPECT_TRUE(same_bits(value, y->coefficients.at(key))) << key;
    }
  }
  expect_same(a.contact.characteristic_velocity, b.contact.characteristic_velocity,
              "characteristic_velocity");
  EXPECT_TRUE(same_bits(a.contact.max_overlap, b.contact.max_overlap));
  expect_same(a.neighbour.skin, b.neighbour.skin, "skin");
  EXPECT_TRUE(same_bits(a.hardsphere.tc_time, b.hardsphere.tc_time));
  EXPECT_TRUE(
      same_bits(a.hardsphere.max_events_per_particle, b.hardsphere.max_events_per_particle));
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

// A case using every key with non-default values, three placements and per-face walls.
const char* kFullCase = R"(
[simulation]
engine = "hard_sphere"
dimension = 2
end_time = 0.30000000000000004
time_step = 1.2345678901234567e-6
time_step_fraction = 0.05
force_time_step = true
gravity = [0.1, 0.0, -9.80665]
insertion_overlap_tolerance = 0.02

[output]
frame_interval = 0.01
series_interval = 0.001

[domain]
lo = [-0.05, 0.0, 0.0]
hi = [0.05, 0.004, 0.3]
periodic = [true, false, false]

[walls]
friction = 0.5
youngs_modulus = 2e7

[walls.z_lo]
restitution = 0.1

[walls.x_hi]
rolling_friction = 0.003

[[species]]
name = "glass \"A\" \\ é"
diameter = 0.004
density = 2700
youngs_modulus = 1e8
poisson_ratio = 0.3
restitution = 0.95
friction = 0.2
tangential_restitution = 0.4
rolling_friction = 0.01

[[species]]
name = "steel"
diameter = 0.0015
density = 7800.5

[[insert]]
species = "glass \"A\" \\ é"
count = 10
placement = "lattice"
region = { lo = [-0.04, 0.0, 0.1], hi = [0.04, 0.004, 0.2] }
velocity = [0.1, 0.0, -0.2]
velocity_spread = 0.05
seed = 42

[[insert]]
species = "steel"
count = 3

[[insert]]
species = "steel"
placement = "file"
file = "beds/bed.data"

[contact]
normal = "linear"
stiffness = 812.5
tangential = "none"
stiffness_ratio = 0.2857142857142857
rolling = "spring_dashpot"
characteristic_velocity = 1.5
max_overlap = 0.2

[neighbour]
skin = 0.0008

[hardsphere]
tc_time = 3.3333333333333333e-7
max_events_per_particle = 250.5
)";

TEST(CaseWriter, RoundTripFullCase) {
  const TempDir dir("writer_full");
  dir.write("beds/bed.data", "# LAMMPS data\n");
  const fs::path case_path = dir.write("case.toml", kFullCase);
  const CaseSpec a = read_case_file(case_path.string());
  // Sanity: the case really is non-default where it matters.
  ASSERT_EQ(a.inserts.size(), 3u);
  ASSERT_EQ(a.contact.normal.name, "linear");
  ASSERT_EQ(a.simulation.engine, Engine::HardSphere);
  ASSERT_EQ(a.hardsphere.tc_time, 3.3333333333333333e-7);
  ASSERT_EQ(a.hardsphere.max_events_per_particle, 250.5);
  ASSERT_EQ(a.domain.wall_material[static_cast<int>(Face::ZLo)].restitution, 0.1);

  const std::string text = write_case_toml(a);
  // Read back from a different folder: absolute insert paths must not depend on it.
  const CaseSpec b = read_case_string(text, (dir.path / "elsewhere" / "resolved.toml").string());
  expect_same(a, b);
  // Writing the read-back case gives the same text (the format is a fixed point).
  EXPECT_EQ(write_case_toml(b), text);
}

TEST(CaseWriter, RoundTripAwkwardDoubles) {
  const TempDir dir("writer_doubles");
  CaseSpec a = read_case_string("[simulation]\nend_time = 1.0\n"
                                "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [1.0, 1.0, 1.0]\n"
                                "[[species]]\nname = \"s\"\ndiameter = 0.1\ndensity = 1.0\n"
                                "[[insert]]\nspecies = \"s\"\ncount = 1\n",
                                (dir.path / "case.toml").string());
  const double awkward[] = {0.1 + 0.2,
                            1.0 / 3.0,
                            std::nextafter(1.0, 2.0),
                            1e-300,
                            std::numeric_limits<double>::denorm_min(),
                            std::numeric_limits<double>::max(),
                            123456789012345678901234.0,
                            1.0,
                            2.5e-7};
  for (const double x : awkward) {
    SCOPED_TRACE(format_double(x));
    a.simulation.end_time = x;
    a.simulation.time_step = x;
    a.species[0].diameter = x;
    a.contact.characteristic_velocity = x;
    a.simulation.gravity = {-x, 0.0, x};
    a.inserts[0].velocity = {-0.0, x, -x};
    a.domain.hi[0] = std::max(x, 1e-3);
    a.inserts[0].region_hi[0] = a.domain.hi[0];
    a.hardsphere.tc_time = x;
    a.hardsphere.max_events_per_particle = std::max(x, 1.0);
    const CaseSpec b = read_case_string(write_case_toml(a), "resolved.toml");
    expect_same(a, b);
  }
}

TEST(CaseWriter, DefaultsAndEveryKeyWritten) {
  const std::string minimal = "[simulation]\nend_time = 1\n"
                              "[domain]\nlo = [0, 0, 0]\nhi = [1, 1, 1]\n"
                              "[[species]]\nname = \"s\"\ndiameter = 0.1\ndensity = 1\n"
                              "[[insert]]\nspecies = \"s\"\ncount = 1\n";
  const CaseSpec a = read_case_string(minimal, "case.toml");
  const std::string text = write_case_toml(a);
  for (const char* key : {"[simulation]",
                          "engine = \"soft_sphere\"",
                          "dimension = 3",
                          "end_time = 1.0",
                          "time_step = \"auto\"",
                          "time_step_fraction = 0.02",
                          "force_time_step = false",
                          "gravity = [0.0, 0.0, -9.81]",
                          "insertion_overlap_tolerance = 0.01",
                          "[output]",
                          "frame_interval = 0.01",
                          "series_interval = 0.001",
                          "[domain]",
                          "lo = [0.0, 0.0, 0.0]",
                          "hi = [1.0, 1.0, 1.0]",
                          "periodic = [false, false, false]",
                          "[walls]",
                          "youngs_modulus = 1e+07",
                          "poisson_ratio = 0.25",
                          "restitution = 0.9",
                          "friction = 0.3",
                          "tangential_restitution = 0.0",
                          "rolling_friction = 0.0",
                          "[[species]]",
                          "name = \"s\"",
                          "diameter = 0.1",
                          "density = 1.0",
                          "[[insert]]",
                          "species = \"s\"",
                          "count = 1",
                          "placement = \"random\"",
                          "region = { lo = [0.0, 0.0, 0.0], hi = [1.0, 1.0, 1.0] }",
                          "velocity = [0.0, 0.0, 0.0]",
                          "velocity_spread = 0.0",
                          "seed = 1",
                          "[contact]",
                          "normal = \"hertz\"",
                          "tangential = \"history\"",
                          "stiffness_ratio = \"auto\"",
                          "rolling = \"none\"",
                          "characteristic_velocity = \"auto\"",
                          "max_overlap = 0.1",
                          "[neighbour]",
                          "skin = \"auto\"",
                          "[hardsphere]",
                          "tc_time = 1e-06",
                          "max_events_per_particle = 1000.0"})
    EXPECT_NE(text.find(key), std::string::npos) << "missing '" << key << "' in:\n" << text;
  // Keys that do not apply are left out (the reader would reject them).
  EXPECT_EQ(text.find("stiffness ="), std::string::npos) << text; // hertz: no stiffness
  EXPECT_EQ(text.find("file ="), std::string::npos) << text;      // random: no file
  EXPECT_EQ(text.find("[walls."), std::string::npos) << text;     // all faces alike
  expect_same(a, read_case_string(text, "case.toml"));
}

// output.layers: read as given, written only when > 0, read back identical.
TEST(CaseWriter, RoundTripOutputLayers) {
  const std::string minimal = "[simulation]\nend_time = 1\n"
                              "[domain]\nlo = [0, 0, 0]\nhi = [1, 1, 1]\n"
                              "[[species]]\nname = \"s\"\ndiameter = 0.1\ndensity = 1\n"
                              "[[insert]]\nspecies = \"s\"\ncount = 1\n";
  const CaseSpec off = read_case_string(minimal, "case.toml");
  EXPECT_EQ(off.output.layers, 0); // default: off
  EXPECT_EQ(write_case_toml(off).find("layers"), std::string::npos) << write_case_toml(off);
  for (const int n : {1, 7, 2147483647}) {
    SCOPED_TRACE(n);
    const CaseSpec a =
        read_case_string(minimal + "[output]\nlayers = " + std::to_string(n) + "\n", "case.toml");
    EXPECT_EQ(a.output.layers, n);
    const std::string text = write_case_toml(a);
    EXPECT_NE(text.find("layers = " + std::to_string(n) + "\n"), std::string::npos) << text;
    const CaseSpec b = read_case_string(text, "resolved.toml");
    EXPECT_EQ(b.output.layers, n);
    expect_same(a, b);
    EXPECT_EQ(write_case_toml(b), text);
  }
}

TEST(CaseWriter, RoundTripEachEngine) {
  const std::string minimal = "[simulation]\nend_time = 1\n"
                              "[domain]\nlo = [0, 0, 0]\nhi = [1, 1, 1]\n"
                              "[[species]]\nname = \"s\"\ndiameter = 0.1\ndensity = 1\n"
                              "[[insert]]\nspecies = \"s\"\ncount = 1\n";
  CaseSpec a = read_case_string(minimal, "case.toml");
  for (const Engine e : {Engine::SoftSphere, Engine::HardSphere}) {
    SCOPED_TRACE(to_string(e));
    a.simulation.engine = e;
    a.hardsphere.tc_time = e == Engine::HardSphere ? 0.0 : 0.1 + 0.2;
    a.hardsphere.max_events_per_particle = e == Engine::HardSphere ? 1.0 : 1e9 + 0.5;
    const std::string text = write_case_toml(a);
    EXPECT_NE(text.find(std::string("engine = \"") + to_string(e) + "\""), std::string::npos)
        << text;
    const CaseSpec b = read_case_string(text, "resolved.toml");
    expect_same(a, b);
    EXPECT_EQ(write_case_toml(b), text);
  }
}

TEST(CaseWriter, RoundTripRigidWallsShearModulusAndInfiniteFriction) {
  // Hertz: a rigid floor (its own Poisson ratio replaces the inherited shear modulus), walls
  // given by their shear modulus (x_hi overrides E: its nu follows from both), a species given by
  // E and G, friction = inf (never sliding) on the particles.
  const std::string minimal = "[simulation]\nend_time = 1\n"
                              "[domain]\nlo = [0, 0, 0]\nhi = [1, 1, 1]\n"
                              "[walls]\nshear_modulus = 3.9e6\n"
                              "[walls.z_lo]\nyoungs_modulus = \"rigid\"\npoisson_ratio = 0.3\n"
                              "[walls.x_hi]\nyoungs_modulus = 9e6\n"
                              "[[species]]\nname = \"s\"\ndiameter = 0.1\ndensity = 1\n"
                              "shear_modulus = 4.1e10\nyoungs_modulus = 1e11\nfriction = inf\n"
                              "[[insert]]\nspecies = \"s\"\ncount = 1\n";
  const CaseSpec a = read_case_string(minimal, "case.toml");
  const auto& zlo = a.domain.wall_material[static_cast<int>(Face::ZLo)];
  const auto& xhi = a.domain.wall_material[static_cast<int>(Face::XHi)];
  const auto& ylo = a.domain.wall_material[static_cast<int>(Face::YLo)];
  ASSERT_TRUE(std::isinf(zlo.youngs_modulus));
  ASSERT_FALSE(zlo.shear_modulus.has_value());
  ASSERT_EQ(xhi.shear_modulus, 3.9e6);
  ASSERT_EQ(xhi.poisson_ratio, 9e6 / 7.8e6 - 1.0);
  ASSERT_EQ(ylo.poisson_ratio, 1e7 / 7.8e6 - 1.0);
  ASSERT_TRUE(std::isinf(a.species[0].material.friction));
  const std::string out = write_case_toml(a);
  EXPECT_NE(out.find("youngs_modulus = \"rigid\""), std::string::npos) << out;
  EXPECT_NE(out.find("friction = inf"), std::string::npos) << out;
  const CaseSpec b = read_case_string(out, "resolved.toml");
  expect_same(a, b);
  EXPECT_EQ(write_case_toml(b), out);
}

TEST(CaseWriter, InsertFileWrittenAbsolute) {
  const TempDir dir("writer_abs");
  const fs::path data = dir.write("bed.data", "# LAMMPS data\n");
  const fs::path case_path =
      dir.write("case.toml", "[simulation]\nend_time = 1\n"
                             "[domain]\nlo = [0, 0, 0]\nhi = [1, 1, 1]\n"
                             "[[species]]\nname = \"s\"\ndiameter = 0.1\ndensity = 1\n"
                             "[[insert]]\nspecies = \"s\"\nplacement = \"file\"\n"
                             "file = \"bed.data\"\n");
  const std::string text = write_case_toml(read_case_file(case_path.string()));
  EXPECT_NE(text.find("file = \"" + data.string() + "\""), std::string::npos) << text;
  EXPECT_EQ(text.find("count ="), std::string::npos) << text; // file placement: no count
}

TEST(CaseWriter, FormatDouble) {
  EXPECT_EQ(format_double(1.0), "1.0");
  EXPECT_EQ(format_double(-0.0), "-0.0");
  EXPECT_EQ(format_double(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(format_double(1e-7), "1e-07");
  EXPECT_EQ(format_double(2700.0), "2700.0");
  EXPECT_EQ(format_double(std::numeric_limits<double>::infinity()), "inf");
}

// [output.continuum]: written with every key that applies, read back identical.
TEST(CaseWriter, RoundTripOutputContinuum) {
  const std::string minimal = "[simulation]\nend_time = 1\n"
                              "[domain]\nlo = [0, 0, 0]\nhi = [1, 1, 1]\n"
                              "[[species]]\nname = \"s\"\ndiameter = 0.1\ndensity = 1\n"
                              "[[insert]]\nspecies = \"s\"\ncount = 1\n";
  EXPECT_EQ(write_case_toml(read_case_string(minimal, "case.toml")).find("continuum"),
            std::string::npos);
  for (const std::string& extra :
       {std::string("cells = [2, 3, 4]\n"),
        std::string("cells = [5, 1, 7]\nmethod = \"weighted\"\nwidth = 0.125\ncutoff = 2.5\n"
                    "interval = 0.03\nstride = 4\n")}) {
    const CaseSpec a = read_case_string(minimal + "[output.continuum]\n" + extra, "case.toml");
    const std::string text = write_case_toml(a);
    const CaseSpec b = read_case_string(text, "resolved.toml");
    ASSERT_TRUE(b.output.continuum.has_value()) << text;
    EXPECT_EQ(b.output.continuum->cells, a.output.continuum->cells);
    EXPECT_EQ(b.output.continuum->method, a.output.continuum->method);
    EXPECT_EQ(b.output.continuum->width, a.output.continuum->width);
    EXPECT_EQ(b.output.continuum->cutoff, a.output.continuum->cutoff);
    EXPECT_EQ(b.output.continuum->interval, a.output.continuum->interval);
    EXPECT_EQ(b.output.continuum->stride, a.output.continuum->stride);
    EXPECT_EQ(write_case_toml(b), text);
  }
}

} // namespace
} // namespace fluidem
