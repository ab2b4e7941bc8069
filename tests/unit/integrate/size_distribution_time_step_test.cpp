// The automatic time step of a batch with a size distribution resolves the contacts of its
// smallest particles (integrate/time_step_rule.hpp, with_smallest_diameters): linear springs,
// whose duration is c(e) sqrt(m*/k) [Deen07 eq. 24-26] with m* ~ d^3, so halving the smallest
// diameter shortens the shortest contact, and the step, by 2^(-3/2) = 0.353553 (1e-3: the step is
// rounded down to divide end_time, one step in ~10^4).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

std::string bed(const std::string& distribution) {
  return R"(
[simulation]
end_time = 0.01
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.02, 0.02]
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
[contact]
normal = "linear"
stiffness = 1000.0
[[insert]]
species = "glass"
count = 50
)" + distribution;
}

TEST(SizeDistributionTimeStep, TheSmallestDrawSetsTheStep) {
  const Simulation plain(read_case_string(bed(""), "plain.toml"));
  const Simulation mixed(read_case_string(
      bed("size_distribution = { kind = \"discrete\", diameters = [0.001, 0.002], fractions = "
          "[0.5, 0.5] }\n"),
      "mixed.toml"));
  const double ratio = mixed.time_step() / plain.time_step();
  std::printf("time step: species diameter %.6e s, with 1 mm draws %.6e s (ratio %.6f)\n",
              plain.time_step(), mixed.time_step(), ratio);
  // end_time / ceil(end_time / dt) rounds the step down to divide end_time: within 1 step in
  // the ~10^4 steps of the run.
  EXPECT_NEAR(ratio, std::pow(0.5, 1.5), 1e-3);
  EXPECT_LT(ratio, 0.36);
}

} // namespace
} // namespace fluidem
