// The hard-sphere engine's neighbour list in a box much larger than its particles (issue 32 item
// 23: the list's cell grid spanned the whole box, 1.2e11 cells of 2 mm in a 10 m box, which could
// not even be allocated; CellGrid keeps only the occupied cells then). Two elastic spheres
// head-on in a 10 m periodic box without gravity: with e = 1 and equal masses they exchange
// their velocities [Hoomans96 eq. 23 with v_t = 0], which they do only if the list found the
// pair; the engine's memory stays that of two particles.
#include <gtest/gtest.h>

#include <string>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

TEST(HardSphereSparseBox, TwoSpheresInATenMetreBoxCollide) {
  const std::string text =
      "[simulation]\nengine = \"hard_sphere\"\nend_time = 1.0\ntime_step = 1e-4\n"
      "gravity = [0.0, 0.0, 0.0]\n"
      "[domain]\nlo = [0, 0, 0]\nhi = [10.0, 10.0, 10.0]\nperiodic = [true, true, true]\n"
      "[[species]]\nname = \"s\"\ndiameter = 0.002\ndensity = 2500\nrestitution = 1.0\n"
      "friction = 0.0\n"
      "[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\n"
      "region = { lo = [4.999, 4.999, 4.999], hi = [5.001, 5.001, 5.001] }\n"
      "velocity = [1.0, 0.0, 0.0]\n"
      "[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\n"
      "region = { lo = [5.009, 4.999, 4.999], hi = [5.011, 5.001, 5.001] }\n"
      "velocity = [-1.0, 0.0, 0.0]\n";
  Simulation sim(read_case_string(text, "case.toml"));
  sim.advance(100); // 10 ms: they touch after (10 mm - 2 mm) / 2 m/s = 4 ms
  const ParticleStore& p = sim.particles();
  ASSERT_EQ(p.size(), 2u);
  const std::size_t a = p.id[0] < p.id[1] ? 0 : 1, b = 1 - a;
  EXPECT_NEAR(p.vx[a], -1.0, 1e-12);
  EXPECT_NEAR(p.vx[b], 1.0, 1e-12);
  EXPECT_EQ(sim.hard_sphere()->stats().collisions, 1);
  EXPECT_LT(sim.hard_sphere()->bytes(), 4096u);
}

} // namespace
} // namespace fluidem
