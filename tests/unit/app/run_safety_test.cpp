// Runs that never lose data, as a user meets them: the real fluidem binary (FLUIDEM_BINARY).
//  - SIGINT / SIGTERM to a running process: exit 130 / 143, a message saying where the
//    checkpoint and outputs are, a checkpoint that loads (`--restart` continues the run to its
//    end) and outputs that continue without duplicated or missing rows (series.csv times
//    strictly increasing, one row per series interval).
//  - An output directory holding another run's results is refused (exit 2, naming --force);
//    --force overwrites. An output path that cannot be a directory is exit 2 before the run.
//  - --restart with a --set that would change the physics is exit 2.
//  - Guards (exit 3, one message naming what, where and when): a gas flow step that does not
//    converge (gas.solver.max_iterations = 1), a gas Courant number above gas.solver.max_courant,
//    a particle leaving the closed domain (a step 50x above the contact limit, forced, overlap
//    limit lifted). Overlap beyond contact.max_overlap: cli_test (UnstableRunExits3...).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../../common/bouncing_spheres.hpp"
#include "../../common/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;

using fluidem::test::contains;
using fluidem::test::read_file;
using fluidem::test::replace;
using fluidem::test::Result;

/// A fresh folder per test.
struct TempDir : fluidem::test::TempDir {
  TempDir() : fluidem::test::TempDir("fluidem_safety") {}
};

using fluidem::test::finish;
using fluidem::test::series_times;
using fluidem::test::start_fluidem;

Result fluidem(const std::vector<std::string>& args, const fs::path& cwd) {
  return finish(start_fluidem(args, cwd), cwd);
}

// Ten discs bouncing in a 2-D box for a long time (so that a signal finds the run going).
const std::string kLong = fluidem::test::bouncing_spheres_case({.dimension = 2,
                                                                .end_time = 1000.0,
                                                                .time_step = 2e-5,
                                                                .frame_interval = 10.0,
                                                                .series_interval = 0.01,
                                                                .checkpoint_interval = 100.0,
                                                                .engine_key = false});

// A small coupled case: 30 soft spheres in a 40 x 4 x 100 mm column, gas from below.
const std::string kGas = R"([simulation]
dimension = 3
end_time = 0.005
engine = "soft_sphere"

[output]
frame_interval = 0.005
series_interval = 0.001

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.04, 0.004, 0.1]

[[species]]
name = "aluminium"
diameter = 0.004
density = 2700.0

[[insert]]
species = "aluminium"
count = 30
placement = "lattice"

[contact]
normal = "linear"
stiffness = 800.0

[gas]
cells = [4, 1, 10]

[gas.boundary.bottom]
type = "inflow"
velocity = 1.0

[gas.boundary.top]
type = "pressure"
)";

void signal_stops_and_restart_continues(int sig, int expected_code, const char* name) {
  TempDir dir;
  const fs::path c = dir.write("long.toml", kLong);
  const fs::path out = dir.path / "out";
  const pid_t pid =
      start_fluidem({"run", c.string(), "--out", out.string(), "--threads", "1"}, dir.path);
  // Wait until the run has written some rows (at most 60 s), then signal it.
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60)) {
    if (fs::exists(out / "series.csv") && series_times(out / "series.csv").size() > 20) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ::kill(pid, sig);
  const Result r = finish(pid, dir.path);
  EXPECT_EQ(r.code, expected_code) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, std::string("stopped by ") + name)) << r.err;
  EXPECT_TRUE(contains(r.err, (out / "checkpoint.h5").string())) << r.err;
  const std::vector<double> before = series_times(out / "series.csv");
  ASSERT_GT(before.size(), 20u);
  const double t_stop = before.back();
  EXPECT_LT(t_stop, 1000.0);
  // Continue to 0.1 s after the stop.
  const double end = std::ceil((t_stop + 0.1) * 100.0) / 100.0;
  const Result c2 = fluidem({"run", "--restart", (out / "checkpoint.h5").string(), "--set",
                             "simulation.end_time=" + std::to_string(end), "--threads", "1"},
                            dir.path);
  EXPECT_EQ(c2.code, 0) << c2.out << c2.err;
  const std::vector<double> all = series_times(out / "series.csv");
  ASSERT_GT(all.size(), before.size());
  for (std::size_t i = 1; i < all.size(); ++i) {
    EXPECT_GT(all[i], all[i - 1]) << "row " << i << ": duplicated or out of order";
    EXPECT_NEAR(all[i] - all[i - 1], 0.01, 1e-6) << "row " << i << ": a row is missing";
  }
  EXPECT_NEAR(all.back(), end, 1e-9);
  // The continued run still names the case file it was started from (fluidem plot finds the
  // case's published values through it: docs/analysis.md).
  EXPECT_TRUE(contains(read_file(out / "case.resolved.toml"),
                       "\n# case file: " + fs::absolute(c).lexically_normal().string() + "\n"));
}

TEST(RunSafety, SigintCheckpointsAndRestartContinues) {
  signal_stops_and_restart_continues(SIGINT, 130, "SIGINT");
}

TEST(RunSafety, SigtermCheckpointsAndRestartContinues) {
  signal_stops_and_restart_continues(SIGTERM, 143, "SIGTERM");
}

TEST(RunSafety, OutputOfAnotherRunNeedsForce) {
  TempDir dir;
  const fs::path c = dir.write("gas.toml", kGas);
  const fs::path out = dir.path / "out";
  ASSERT_EQ(fluidem({"run", c.string(), "--out", out.string()}, dir.path).code, 0);
  const Result again = fluidem({"run", c.string(), "--out", out.string()}, dir.path);
  EXPECT_EQ(again.code, 2) << again.out << again.err;
  EXPECT_TRUE(contains(again.err, "--force")) << again.err;
  EXPECT_TRUE(contains(again.err, out.string())) << again.err;
  const Result forced = fluidem({"run", c.string(), "--out", out.string(), "--force"}, dir.path);
  EXPECT_EQ(forced.code, 0) << forced.out << forced.err;
}

TEST(RunSafety, OutputPathThatCannotBeADirectoryIsAnErrorBeforeTheRun) {
  TempDir dir;
  const fs::path c = dir.write("gas.toml", kGas);
  dir.write("plain_file", "not a directory\n");
  const fs::path out = dir.path / "plain_file" / "out";
  const Result r = fluidem({"run", c.string(), "--out", out.string()}, dir.path);
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "output directory")) << r.err;
  EXPECT_FALSE(contains(r.out, "t = ")) << "no progress: the run must not start\n" << r.out;
}

TEST(RunSafety, RestartCannotChangeThePhysics) {
  TempDir dir;
  const fs::path c = dir.write("gas.toml", kGas);
  const fs::path out = dir.path / "out";
  ASSERT_EQ(fluidem({"run", c.string(), "--out", out.string()}, dir.path).code, 0);
  const Result r =
      fluidem({"run", "--restart", (out / "checkpoint.h5").string(), "--set", "gas.viscosity=1e-3"},
              dir.path);
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "simulation.end_time")) << r.err;
}

void expect_guard(const std::string& text, const std::string& what_regex) {
  TempDir dir;
  const fs::path c = dir.write("case.toml", text);
  const fs::path out = dir.path / "out";
  const Result r = fluidem({"run", c.string(), "--out", out.string(), "--threads", "1"}, dir.path);
  EXPECT_EQ(r.code, 3) << r.out << r.err;
  EXPECT_TRUE(std::regex_search(r.err, std::regex(what_regex))) << r.err;
  EXPECT_TRUE(contains(r.err, out.string())) << "should say where the outputs are\n" << r.err;
}

TEST(RunSafety, GasNotConvergingExits3) {
  expect_guard(kGas + "\n[gas.solver]\nmax_iterations = 1\ntolerance = 1e-14\n",
               R"(did not converge.*t = [0-9.e-]+ s)");
}

TEST(RunSafety, GasCourantAboveLimitExits3) {
  expect_guard(
      kGas + "\n[gas.solver]\nmax_courant = 1e-6\n",
      R"(Courant number .* above gas.solver.max_courant.*cell \([0-9]+, [0-9]+, [0-9]+\))");
}

TEST(RunSafety, ParticleLeavingTheDomainExits3) {
  // Discs thrown at 20 m/s with a step of 1e-3 s (about 50x the contact limit, forced) and the
  // overlap limit lifted: they pass through the wall before a contact can stop them.
  std::string text = replace(kLong, "end_time = 1000.0\ntime_step = 2e-5\n",
                             "end_time = 0.1\ntime_step = 1e-3\nforce_time_step = true\n");
  text = replace(text, "velocity_spread = 0.5", "velocity_spread = 20.0");
  text = replace(text, "stiffness = 800.0\n", "stiffness = 800.0\nmax_overlap = 0.99\n");
  expect_guard(text, R"(particle [0-9]+ left the closed domain)");
}

} // namespace

namespace {

// Found with the sanitizer build (issue "Runs that never lose data", fuzzing): a time step so
// small the run would never end, and a lattice of tiny particles in a large region, were
// accepted (the second overflowed a long). The first is exit 2 naming the key, the second is
// computed without overflow; more particles than the memory holds is exit 2.
TEST(RunSafety, EndlessRunIsRefused) {
  TempDir dir;
  const fs::path c =
      dir.write("endless.toml", replace(kLong, "time_step = 2e-5\n", "time_step = 4.9e-324\n"));
  const Result r = fluidem({"check", c.string()}, dir.path);
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "simulation.time_step")) << r.err;
}

TEST(RunSafety, LatticeOfTinyParticlesInAHugeRegionDoesNotOverflow) {
  TempDir dir;
  std::string text = replace(kLong, "hi = [0.04, 0.004, 0.04]", "hi = [1.0e6, 0.004, 1.0e6]");
  text = replace(text, "diameter = 0.004", "diameter = 1e-7");
  text = replace(text, "time_step = 2e-5\n", "time_step = 2e-5\nforce_time_step = true\n");
  // 10 particles: the lattice capacity (about 1e26 sites) is computed without overflow.
  const Result ok = fluidem({"check", dir.write("tiny.toml", text).string()}, dir.path);
  EXPECT_EQ(ok.code, 0) << ok.out << ok.err;
  // 2e9 particles: more than the machine's memory holds, an input error naming the key.
  text = replace(text, "count = 10", "count = 2000000000");
  const Result r = fluidem({"check", dir.write("huge.toml", text).string()}, dir.path);
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "memory")) << r.err;
}

} // namespace
