// The [Chang08] cube (cases/chang08/binary_collision_d10.toml: 512 hard spheres of 10 mm in a
// periodic 0.1 m box of water, sinusoidal_cube body force A = 0.1 m/s2), run for 3 s (~30 s of
// wall time), two-way coupled with the water held at rest on average (run A of
// cases/chang08/README_binary_collision.md: the case files are one-way now, where the particles
// gather at CC and GC alike within the first 3 s and CC wins only over the 30 s run). Checks:
// - the global void fraction 1 - 512 (pi/6) d^3 / L^3 = 0.7319 [Chang08 Table 1: 0.732], 1e-4;
// - no particle is lost and the hard spheres do not overlap (a pair closer than d (1 - 1e-9)
// fails);
// - the particles collect at the collision centres: averaged over the frames of 1.5-3 s, the number
//   of centres within 0.1 L of a CC (mean of the two) exceeds that within 0.1 L of GC, and the
//   solids fraction there exceeds the global one [Chang08 Table 1: void fraction CC 0.440 <
//   GC 0.546 < 0.732; our 30 s run: cases/chang08/README.md];
// - collisions happen (the counter grows) and the particles move (mean speed > 1 mm/s).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

TEST(Chang08Cube, ShortRunCollectsAtCollisionCentres) {
  const double L = 0.1, rc = 0.1 * L, d = 0.010;
  Simulation sim(read_case_file(
      std::string(FLUIDEM_SOURCE_DIR) + "/cases/chang08/binary_collision_d10.toml",
      {"simulation.end_time=3.0", "coupling.mode=two_way", "coupling.hold_gas_at_rest=true"}));
  const ParticleStore& p = sim.particles();
  ASSERT_EQ(p.size(), 512u);
  double vs = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    vs += std::numbers::pi / 6.0 * std::pow(2 * p.radius[i], 3);
  EXPECT_NEAR(1.0 - vs / (L * L * L), 0.7319, 1e-4);

  auto count_near = [&](const std::array<double, 3>& c) {
    int n = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      double r2 = 0.0;
      for (const auto& [x, cc] : {std::pair{p.x[i], c[0]}, {p.y[i], c[1]}, {p.z[i], c[2]}}) {
        const double dx = x - cc - L * std::round((x - cc) / L);
        r2 += dx * dx;
      }
      n += r2 < rc * rc ? 1 : 0;
    }
    return n;
  };
  const long per_frame = std::lround(0.1 / sim.time_step());
  double n_gc = 0.0, n_cc = 0.0, speed = 0.0;
  int frames = 0;
  while (sim.time() < 3.0 - 1e-9) {
    sim.advance(per_frame);
    if (sim.time() < 1.5 - 1e-9) continue;
    n_gc += count_near({L / 2, L / 2, L / 2});
    n_cc +=
        0.5 * (count_near({L / 4, L / 4, L / 4}) + count_near({3 * L / 4, 3 * L / 4, 3 * L / 4}));
    double s = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
      s += std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    speed += s / static_cast<double>(p.size());
    ++frames;
  }
  n_gc /= frames, n_cc /= frames, speed /= frames;
  const double v_cell = 4.0 / 3.0 * std::numbers::pi * rc * rc * rc;
  const double eps_cc = 1.0 - n_cc * std::numbers::pi / 6.0 * d * d * d / v_cell;
  std::printf("frames %d: particles within 0.1 L of CC %.2f, of GC %.2f; void fraction CC %.3f; "
              "mean speed %.4f m/s; collisions %ld\n",
              frames, n_cc, n_gc, eps_cc, speed,
              static_cast<long>(sim.hard_sphere()->stats().collisions));
  EXPECT_GT(n_cc, n_gc);
  EXPECT_LT(eps_cc, 0.7319);
  EXPECT_GT(speed, 1e-3);
  EXPECT_GT(sim.hard_sphere()->stats().collisions, 100L);
  // Hard spheres: no overlap (minimum image).
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      double r2 = 0.0;
      for (const auto& [a, b] : {std::pair{p.x[i], p.x[j]}, {p.y[i], p.y[j]}, {p.z[i], p.z[j]}}) {
        const double dx = a - b - L * std::round((a - b) / L);
        r2 += dx * dx;
      }
      ASSERT_GT(r2, d * d * (1.0 - 1e-9) * (1.0 - 1e-9)) << "particles " << i << ", " << j;
    }
}

} // namespace
} // namespace fluidem
