// The contact loop reads the contact parameters once for all of a batch's contacts when they are
// the same for every contact (one species; walls of one material), with the particles' radius
// and mass too when those are all the same, and a lane at a time through each contact's species
// pair otherwise (contact_forces.cpp, Uniformity; tests/unit/contact/uniform_batches_test.cpp
// checks each path at the contact loop). Over whole runs: a bed of one species (all of its
// contacts on the uniform path) and the same bed whose upper half is a second species of
// identical material (its own [[species]] entry, so the pairs take the per-contact path, the
// walls still the uniform one) must stay bitwise identical, with Hertz and linear springs
// and tangential history and with rolling springs (whose torques the additions into the
// particles' sums take on their torque lanes), in a closed box (wall contacts) with > 4096
// particles (the threaded slab loop, one batch per slab) and with fewer (one batch through all
// slabs).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <fmt/format.h>

#include "../../common/random_bed.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

/// The bed: `count` spheres in each half of a box `side` wide (two inserts, their own seeds), the
/// upper half of species `upper` ("glass" or its twin "glass_b", listed either way); `extra`
/// goes at the end of [contact].
std::string bed(int count, double side, const char* upper, const char* normal, const char* extra) {
  return fmt::format(R"(
[simulation]
dimension = 3
end_time = 1.0
time_step = 2e-5
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [{4}, {4}, 0.08]
{5}{6}
[[insert]]
species = "glass"
count = {0}
placement = "random"
velocity_spread = 0.8
seed = 3
region = {{ lo = [0.0, 0.0, 0.0], hi = [{4}, {4}, 0.04] }}
[[insert]]
species = "{1}"
count = {0}
placement = "random"
velocity_spread = 0.8
seed = 4
region = {{ lo = [0.0, 0.0, 0.04], hi = [{4}, {4}, 0.08] }}
[contact]
normal = "{2}"
tangential = "history"
{3}
)",
                     count, upper, normal, extra, side, test::glass_species("glass"),
                     test::glass_species("glass_b"));
}

struct Outcome {
  std::vector<double> state; // x y z vx vy vz wx wy wz of every particle
  long contacts = 0;
  int species_used = 0; // distinct species among the particles
};

Outcome run(const std::string& text, long steps) {
  Simulation sim(read_case_string(text, "uniform.toml"));
  sim.advance(steps);
  const auto& p = sim.particles();
  Outcome o;
  o.contacts = sim.contact_stats().n_contacts;
  bool seen[2] = {false, false};
  for (std::size_t i = 0; i < p.size(); ++i) {
    o.state.insert(o.state.end(),
                   {p.x[i], p.y[i], p.z[i], p.vx[i], p.vy[i], p.vz[i], p.wx[i], p.wy[i], p.wz[i]});
    seen[p.species[i]] = true;
  }
  o.species_used = int{seen[0]} + int{seen[1]};
  return o;
}

/// Both beds, `count` spheres in each half of a box `side` wide (a quarter of its volume solid),
/// after `steps` steps.
void expect_same(int count, double side, const char* normal, const char* extra, long steps) {
  const Outcome one = run(bed(count, side, "glass", normal, extra), steps);
  const Outcome two = run(bed(count, side, "glass_b", normal, extra), steps);
  ASSERT_EQ(one.species_used, 1);
  ASSERT_EQ(two.species_used, 2);
  ASSERT_EQ(one.state.size(), 9u * 2 * count);
  EXPECT_GT(one.contacts, count / 10); // the spheres collide (0.8 m/s spread)
  EXPECT_EQ(one.contacts, two.contacts);
  // Bitwise: operator== on doubles, no tolerance.
  EXPECT_TRUE(one.state == two.state)
      << normal << " " << extra << ", " << 2 * count << " particles";
}

TEST(UniformParameters, TwinSpeciesGiveTheSameHertzBedAsOne) {
  expect_same(2500, 0.06, "hertz", "", 150); // 5000 particles: the threaded slab loop
  expect_same(600, 0.03, "hertz", "", 150);  // 1200: one batch through all slabs
}

TEST(UniformParameters, TwinSpeciesGiveTheSameLinearBedAsOne) {
  expect_same(2500, 0.06, "linear", "stiffness = 800.0", 150);
}

TEST(UniformParameters, TwinSpeciesGiveTheSameBedWithRollingSpringsAsOne) {
  expect_same(2500, 0.06, "hertz", "rolling = \"spring_dashpot\"", 150);
}

} // namespace
} // namespace fluidem
