// The automatic neighbour skin (neighbour.skin = "auto", docs/case-file.md): each list build
// chooses skin = clamp(2 k v_max dt, 0.2 d_max, d_max) with k = 10, so a list lasts at least k
// steps at the largest speed of its build (a rebuild is due when a particle moved skin/2).
// Issue 32 item 23: one fast 100 um sphere rebuilt its list every few steps with the fixed
// 0.2 d skin (20 um against v dt = 2.8 um: every 4th step). The count of builds is the check
// (a count, not a time): a particle flying at 20 m/s in a straight line through 2000 steps
// needs at most 2000 / 10 builds plus the first, and its skin is 2 k v dt.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

const std::string kSingle = "[simulation]\nend_time = 1.0\ngravity = [0.0, 0.0, 0.0]\n"
                            "[domain]\nlo = [0, 0, 0]\nhi = [0.04, 0.04, 0.04]\n"
                            "[[species]]\nname = \"glass\"\ndiameter = 1e-4\ndensity = 2500\n"
                            "youngs_modulus = 1e7\n"
                            "[[insert]]\nspecies = \"glass\"\ncount = 1\n"
                            "region = { lo = [0.005, 0.019, 0.019], hi = [0.006, 0.021, 0.021] }\n"
                            "velocity = [20.0, 0.0, 0.0]\n";

TEST(AutomaticSkin, AFastParticleKeepsItsListForTenSteps) {
  Simulation sim(read_case_string(kSingle, "case.toml"));
  const double dt = sim.time_step();
  ASSERT_GT(20.0 * dt, 1e-6); // the fixed skin (20 um) lasted fewer than 4 steps at this speed
  const long steps = 2000;    // 20 m/s * 2000 dt < 2 cm: no wall on the way
  ASSERT_LT(20.0 * dt * steps, 0.02);
  sim.advance(steps);
  EXPECT_LE(sim.neighbour_builds(), 1 + steps / 10);
  EXPECT_GE(sim.neighbour_builds(), steps / 11); // (and not much fewer: the skin is 2 k v dt)
}

TEST(AutomaticSkin, AFixedSkinIsKept) {
  // neighbour.skin set: the list keeps it, rebuilt every skin / (2 v dt) steps.
  Simulation sim(read_case_string(kSingle + "[neighbour]\nskin = 2e-5\n", "case.toml"));
  const double dt = sim.time_step();
  const long steps = 2000;
  sim.advance(steps);
  const double per_list = std::floor(1e-5 / (20.0 * dt)) + 1.0; // steps until moved > skin/2
  EXPECT_NEAR(static_cast<double>(sim.neighbour_builds()), 1.0 + steps / per_list,
              0.02 * steps / per_list + 1.0);
}

} // namespace
} // namespace fluidem
