// The output schedule over a long run: with an interval that is a whole number of steps, every
// row of series.csv falls on its mark, k x interval, from the first row to the last. The marks
// were once made by adding the interval mark after mark: its round-off drifted by tens of ulps
// over thousands of rows until a step time that sat on a mark fell short of it, and from then on
// every row came one step late (chang08/spouted_loop.toml's 1 kHz probes from 5.026 s to 9.79 s,
// which `fluidem analyse` refused for a spectrum). With DT = 1e-5 s and rows every 4e-5 s the
// drifting schedule made its first late row at t = 0.17217 s (step 17,217; found by replaying
// the old schedule in floating point), inside this 0.2 s run.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "../../common/bouncing_spheres.hpp"
#include "../../common/cli_runner.hpp"

namespace {

using fluidem::test::fluidem;
using fluidem::test::Result;
using fluidem::test::series_times;
using fluidem::test::TempDir;

// Ten soft spheres bouncing in a closed box, a fixed time step.
const std::string kCase = fluidem::test::bouncing_spheres_case(
    {.dimension = 3, .end_time = 0.2, .time_step = 1e-5, .series_interval = 4e-5});

TEST(OutputSchedule, EveryRowOfALongRunFallsOnItsMark) {
  TempDir dir("fluidem_schedule");
  const auto c = dir.path / "case.toml";
  {
    std::ofstream f(c);
    f << kCase;
  }
  const Result r = fluidem({"run", c.string(), "--out", "out", "--threads", "1"}, dir.path);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const std::vector<double> t = series_times(dir.path / "out" / "series.csv");
  ASSERT_EQ(t.size(), 5001u) << "0 to 0.2 s every 4e-5 s";
  // Each row on its mark to within round-off (a late row is a whole step, 1e-5 s, off).
  for (std::size_t k = 0; k < t.size(); ++k)
    ASSERT_NEAR(t[k], 4e-5 * static_cast<double>(k), 1e-9) << "row " << k;
}

} // namespace
