// Bad input as a user meets it, with the real fluidem binary: cases that used to end in
// std::bad_alloc (exit 1) after seconds of allocation, to take 70 s before a random insertion
// gave up, or to blame a key the user did not write (issue 32, items 9 and 10). Each must now
// exit 2 at once with a message naming the key that is wrong, the estimate or the limit, and
// what is allowed. The case files are the fuzz corpus's (tests/data/fuzz/, read by the fuzzer
// and by io/fuzz_regressions_test.cpp) or written here.
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <vector>

#include "../../common/bouncing_spheres.hpp"
#include "../../common/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;

using fluidem::test::contains;
using fluidem::test::fluidem;
using fluidem::test::replace;
using fluidem::test::Result;
using fluidem::test::TempDir;

const fs::path kCorpus = fs::path(FLUIDEM_SOURCE_DIR) / "tests" / "data" / "fuzz";

/// `fluidem check FILE [MORE...]` in a fresh folder, and its wall time in seconds.
struct Timed {
  Result r;
  double seconds = 0.0;
};
Timed check(const TempDir& dir, const fs::path& file, const std::vector<std::string>& more = {}) {
  const auto t0 = std::chrono::steady_clock::now();
  Timed t;
  std::vector<std::string> args = {"check", file.string()};
  args.insert(args.end(), more.begin(), more.end());
  t.r = fluidem(args, dir.path);
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

/// Expects exit 2 within `seconds` (a generous bound on a busy machine: the refusals need no
/// allocation and no insertion) with `message` on stderr.
void expect_refused(const Timed& t, const std::string& message, double seconds = 20.0) {
  EXPECT_EQ(t.r.code, 2) << t.r.out << t.r.err;
  EXPECT_TRUE(contains(t.r.err, message)) << t.r.err;
  EXPECT_LT(t.seconds, seconds);
}

// A valid 2-D case: ten 4 mm glass discs on a lattice in a 40 x 40 mm box, linear k = 800 N/m.
const std::string kValid = fluidem::test::resting_discs_case();

// --- item 9: memory, estimated before it is allocated ----------------------------------------

// 1e10 cells: 7.5 TB at the 750 bytes per cell a coupled run measured (memory_estimate.cpp).
TEST(BadInput, GasGridBeyondTheMemoryIsRefusedAtItsKey) {
  TempDir dir;
  expect_refused(check(dir, kCorpus / "memory_gas_cells_1e10.toml"),
                 "gas.cells: the gas grid of 1e+10 cells needs about 7.5 TB of memory");
}

TEST(BadInput, ContinuumGridBeyondTheMemoryIsRefusedAtItsKey) {
  TempDir dir;
  expect_refused(check(dir, kCorpus / "memory_continuum_cells_1e10.toml"),
                 "output.continuum.cells: the continuum averaging grid of 1e+10 cells needs "
                 "about 8.7 TB of memory");
}

// 1000 x 1000 m of 1 mm discs: cells of 1.2 mm (the diameter plus the skin of 0.2 d), 2.08e12
// of them over the domain, were allocated until std::bad_alloc. The lists' cell grid now keeps
// only the occupied cells of a sparse box (neighbour/cell_grid.hpp): the case runs, at once.
TEST(BadInput, AHugeDomainWithFewParticlesRuns) {
  TempDir dir;
  const Timed t = check(dir, kCorpus / "memory_domain_1000m_cell_grid.toml");
  EXPECT_EQ(t.r.code, 0) << t.r.out << t.r.err;
  EXPECT_LT(t.seconds, 20.0);
  const auto t0 = std::chrono::steady_clock::now();
  const Result run =
      fluidem({"run", (kCorpus / "memory_domain_1000m_cell_grid.toml").string(), "--out", "huge"},
              dir.path);
  EXPECT_EQ(run.code, 0) << run.out << run.err;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 60.0);
}

TEST(BadInput, ParticlesBeyondTheMemoryAreRefusedAtTheirCount) {
  TempDir dir;
  const fs::path c =
      dir.write("case.toml", replace(replace(kValid, "count = 10", "count = 2000000000"),
                                     "hi = [0.04, 0.004, 0.04]", "hi = [1e4, 0.004, 1e4]"));
  expect_refused(check(dir, c),
                 "case.toml:16:1: insert[0].count: 2e+09 particles needs about 2 TB of memory");
}

// Species no [[insert]] uses have no contact durations: `check` lists the pairs that can meet,
// not 1000 x 1000 / 2 rows (and the run does not mix their coefficients).
TEST(BadInput, UnusedSpeciesHaveNoContactDurations) {
  TempDir dir;
  const Timed t = check(dir, kCorpus / "species_1000_unused.toml");
  EXPECT_EQ(t.r.code, 0) << t.r.err;
  EXPECT_TRUE(contains(t.r.out, "  glass-glass "));
  EXPECT_TRUE(contains(t.r.out, "  glass-wall z_hi "));
  EXPECT_FALSE(contains(t.r.out, "  unused")) << t.r.out.substr(0, 2000); // (no unused0-...)
  EXPECT_LT(t.r.out.size(), 4000u);
  EXPECT_LT(t.seconds, 20.0);
}

// --- item 9: a random insertion that cannot fit, refused before it is tried -------------------

// The pouring box of [Hoomans96 §5.1] (24 x 48 diameters) holds 946 discs by the bound: the
// jamming area fraction 0.547 [Hinrichsen et al. 1986] of 1152 d^2 (802) plus one per diameter
// of its edge (144). 100 000 discs took 70 s of attempts before.
TEST(BadInput, RandomInsertionBeyondTheJammingLimitIsRefusedAtOnce) {
  TempDir dir;
  expect_refused(check(dir, kCorpus / "insert_random_100000_discs.toml"),
                 "insert[0].count: 100000 discs of diameter 0.004 m would cover 68.2 times the "
                 "region's area of 0.0184 m^2; random insertion jams at an area fraction of 0.547 "
                 "[Hinrichsen et al. 1986]: no more than 946 fit in this region",
                 10.0);
}

// Spheres: a 10 x 10 x 10 d box holds 0.384 [Zhang & Torquato 2013] x 1000 d^3 / (pi/6 d^3) =
// 733 plus 600 for its 600 d^2 of surface: 1333.
TEST(BadInput, RandomInsertionOfSpheresBeyondTheJammingLimitIsRefusedAtOnce) {
  TempDir dir;
  std::string text = replace(kValid, "dimension = 2", "dimension = 3");
  text = replace(text, "hi = [0.04, 0.004, 0.04]", "hi = [0.04, 0.04, 0.04]");
  text =
      replace(text, "count = 10\nplacement = \"lattice\"", "count = 5000\nplacement = \"random\"");
  expect_refused(check(dir, dir.write("case.toml", text)),
                 "insert[0].count: 5000 spheres of diameter 0.004 m would cover 2.62 times the "
                 "region's volume of 6.4e-05 m^3; random insertion jams at a volume fraction of "
                 "0.384 [Zhang & Torquato 2013]: no more than 1333 fit in this region",
                 10.0);
}

// --- item 10: the message names the input that is wrong -------------------------------------

// Both used to say "simulation.time_step: ... gives inf steps", a key the case does not set.
TEST(BadInput, TinyDiameterIsNamedNotTheTimeStep) {
  TempDir dir;
  const Timed t = check(dir, kCorpus / "species_diameter_1e-300.toml");
  expect_refused(t, "species[0].diameter: 1e-300 m makes the glass-glass contact last 0 s");
  // The allowed value: m* = m/2 with a force pulse of 3.0749 sqrt(m*/800) = 1e-12 s at e = 0.9
  // (0.02 s in at most 1e12 steps of 0.02 tc; the factor from the explicit solution,
  // tests/common/linear_impact.hpp, computed by hand) gives d = 4.93e-9 m.
  EXPECT_TRUE(contains(t.r.err, "species[0].diameter >= 4.93e-09 m")) << t.r.err;
  EXPECT_FALSE(contains(t.r.err, "simulation.time_step:")) << t.r.err;
}

// Coarse-grained (W = 8, chang08 scaling: parcels of 2 d, linear stiffness x 2), the message
// speaks of the values the user wrote, not the parcels': the parcel's contact needs
// sqrt(m2 / k2) as above, m2 ~ d2^3 and k2 = 2 k, so d2 >= 4.93e-9 m x 2^(1/3) = 6.21e-9 m and
// the user's d1 = d2 / 2 >= 3.1e-9 m; the culprit is the written 1e-300 m (not 2e-300).
TEST(BadInput, CoarseGrainedSuggestionsAreTheUsersValues) {
  TempDir dir;
  const Timed t =
      check(dir, kCorpus / "species_diameter_1e-300.toml", {"--set", "coarse_graining.ratio=8"});
  expect_refused(t, "species[0].diameter: 1e-300 m makes the glass-glass contact last 0 s");
  EXPECT_TRUE(contains(t.r.err, "species[0].diameter >= 3.1e-09 m")) << t.r.err;
}

TEST(BadInput, HugeStiffnessIsNamedNotTheTimeStep) {
  TempDir dir;
  const Timed t = check(dir, kCorpus / "contact_stiffness_1e300.toml");
  expect_refused(t, "contact.stiffness: 1e+300 N/m makes the glass-glass contact last 2.07e-152 s");
  // k = m* (3.0749 / 1e-12 s)^2 with m* = 4.52e-5 kg (the force pulse at e = 0.9, above).
  EXPECT_TRUE(contains(t.r.err, "contact.stiffness <= 4.28e+20 N/m")) << t.r.err;
}

TEST(BadInput, HugeYoungsModulusIsNamedNotTheTimeStep) {
  TempDir dir;
  std::string text =
      replace(kValid, "density = 2700.0", "density = 2700.0\nyoungs_modulus = 1e300");
  text = replace(text, "normal = \"linear\"\nstiffness = 800.0", "normal = \"hertz\"");
  const Timed t = check(dir, dir.write("case.toml", text));
  expect_refused(t, "case.toml:13:1: species[0].youngs_modulus: 1e+300 Pa makes the glass-glass "
                    "contact last");
  EXPECT_TRUE(contains(t.r.err, "species[0].youngs_modulus <= ")) << t.r.err;
}

// Usual values, a run too long: then it is end_time that is named.
TEST(BadInput, TooLongARunNamesTheEndTime) {
  TempDir dir;
  const Timed t =
      check(dir, dir.write("case.toml", replace(kValid, "end_time = 0.02", "end_time = 1e9")));
  expect_refused(t, "case.toml:3:1: simulation.end_time: 1e+09 s is too long for this case: the "
                    "glass-glass contact lasts 0.000731 s");
}

TEST(BadInput, InsertFileThatIsADirectoryOrADeviceSaysSo) {
  TempDir dir;
  expect_refused(check(dir, kCorpus / "insert_file_directory.toml"),
                 "insert[0].file: " + kCorpus.string() + "/ is a directory, not a file");
  expect_refused(check(dir, kCorpus / "insert_file_dev_zero.toml"),
                 "insert[0].file: /dev/zero is a character device, not a regular file");
}

TEST(BadInput, UnreadableCaseFileGivesTheReason) {
  TempDir dir;
  const fs::path c = dir.write("case.toml", kValid);
  expect_refused(check(dir, dir.path / "nowhere.toml"), "nowhere.toml: does not exist");
  expect_refused(check(dir, c / "x.toml"), "case.toml/x.toml: cannot be opened: Not a directory");
  expect_refused(check(dir, dir.path), ": is a directory, not a file");
  fs::create_symlink("b.toml", dir.path / "a.toml");
  fs::create_symlink("a.toml", dir.path / "b.toml");
  expect_refused(check(dir, dir.path / "a.toml"),
                 "a.toml: cannot be opened: Too many levels of symbolic links");
  fs::create_symlink("gone.toml", dir.path / "dangling.toml");
  expect_refused(check(dir, dir.path / "dangling.toml"),
                 "dangling.toml: is a symbolic link to a file that does not exist");
  if (::geteuid() != 0) { // root reads any file
    fs::permissions(c, fs::perms::none);
    expect_refused(check(dir, c), "case.toml: cannot be opened: Permission denied");
  }
}

} // namespace
