// `output.analyse = true`: `fluidem run` ends with the analysis of `fluidem analyse OUT`. The
// reference is the separate command itself: the summary.csv it writes afterwards is byte for
// byte the one the run wrote. The key is kept in case.resolved.toml, and a non-boolean value is an
// error naming the key.
#include <gtest/gtest.h>

#include <filesystem>

#include "../../common/cli_runner.hpp"

namespace {

using fluidem::test::contains;
using fluidem::test::fluidem;
using fluidem::test::read_file;
using fluidem::test::Result;
using fluidem::test::TempDir;
namespace fs = std::filesystem;

// Forty 4 mm discs poured in a 40 x 80 mm box for 0.1 s, rows every 1 ms.
const std::string kCase = R"([simulation]
dimension = 2
end_time = 0.1

[output]
frame_interval = 0.01
series_interval = 0.001
analyse = true

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.04, 0.004, 0.08]

[[species]]
name = "glass"
diameter = 0.004
density = 2700.0

[[insert]]
species = "glass"
count = 40
placement = "random"
seed = 3

[contact]
normal = "linear"
stiffness = 800.0
)";

TEST(RunAnalyse, TheRunWritesWhatAnalyseWrites) {
  TempDir dir("fluidem_run_analyse");
  dir.write("pour.toml", kCase);
  const Result run = fluidem({"run", "pour.toml", "--out", "out"}, dir.path);
  ASSERT_EQ(run.code, 0) << run.out << run.err;
  EXPECT_TRUE(contains(run.out, "analysis (output.analyse = true)")) << run.out;
  const fs::path summary = dir.path / "out" / "analysis" / "summary.csv";
  const std::string from_run = read_file(summary);
  ASSERT_FALSE(from_run.empty());
  EXPECT_TRUE(contains(from_run, "energy_balance_error")) << from_run;
  fs::remove(summary);
  const Result again = fluidem({"analyse", "out"}, dir.path);
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(read_file(summary), from_run);
  EXPECT_TRUE(contains(read_file(dir.path / "out" / "case.resolved.toml"), "analyse = true"));
}

TEST(RunAnalyse, ANonBooleanIsAnError) {
  TempDir dir("fluidem_run_analyse_bad");
  dir.write("pour.toml", kCase);
  const Result r = fluidem({"check", "pour.toml", "--set", "output.analyse=3"}, dir.path);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "output.analyse")) << r.err;
}

} // namespace
