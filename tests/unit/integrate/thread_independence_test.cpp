// Results must not depend on the number of threads (fluidem's standard): the slab-ordered
// contact loop (neighbour/neighbour_list.hpp) gives bitwise identical particle arrays with one,
// two and three OpenMP threads. The case has > 4096 particles (the parallel threshold), periodic x
// and y axes (pairs across the periodic slab boundary), a floor, gravity and random velocities, so
// contacts form, slide and end and the neighbour list is rebuilt with history carried over.
#include <gtest/gtest.h>
#include <omp.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

const char* kCase = R"(
[simulation]
dimension = 3
end_time = 0.006
time_step = 2e-5
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.08, 0.08, 0.06]
periodic = [true, true, false]
[[species]]
name = "glass"
diameter = 0.003
density = 2500.0
youngs_modulus = 1e7
restitution = 0.8
friction = 0.4
rolling_friction = 0.05
[[insert]]
species = "glass"
count = 6000
placement = "random"
velocity_spread = 0.8
seed = 7
[contact]
normal = "hertz"
tangential = "history"
rolling = "spring_dashpot"
)";

// A bed above 32768 particles: the contact loop runs its slabs in groups of about equal
// particle counts (contact_forces.cpp, slab_group_starts) instead of even/odd pairs; periodic
// in x and y, so the last group's last slab writes into the first slab.
const char* kLargeCase = R"(
[simulation]
dimension = 3
end_time = 0.0012
time_step = 2e-5
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.16, 0.16, 0.12]
periodic = [true, true, false]
[[species]]
name = "glass"
diameter = 0.003
density = 2500.0
youngs_modulus = 1e7
restitution = 0.8
friction = 0.4
[[insert]]
species = "glass"
count = 40000
placement = "random"
velocity_spread = 0.8
seed = 11
[contact]
normal = "hertz"
tangential = "history"
)";

// A closed box four diameters deep in y (walls on every face, no periodic axis) with fast
// particles everywhere: wall contacts in every slab, so the wall chunks, which run after the
// pairs that add into their particles (on whichever thread ran those), span the threads' shares.
const char* kClosedCase = R"(
[simulation]
dimension = 3
end_time = 0.0045
time_step = 1.2e-5
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.06, 0.008, 0.2]
[walls]
friction = 0.3
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
youngs_modulus = 1e7
restitution = 0.8
friction = 0.4
[[insert]]
species = "glass"
count = 6000
placement = "random"
velocity_spread = 0.8
seed = 5
[contact]
normal = "hertz"
tangential = "history"
)";

struct State {
  std::vector<double> x, v, w;
  long contacts = 0;
  std::size_t wall_entries = 0;
};

State run_with_threads(int threads, const char* text = kCase, long steps = 300) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  Simulation sim(read_case_string(text, "threads.toml"));
  sim.advance(steps);
  omp_set_num_threads(saved);
  const auto& p = sim.particles();
  State s;
  s.contacts = sim.contact_stats().n_contacts;
  s.wall_entries = sim.neighbour_wall_entries();
  for (std::size_t i = 0; i < p.size(); ++i) {
    s.x.insert(s.x.end(), {p.x[i], p.y[i], p.z[i]});
    s.v.insert(s.v.end(), {p.vx[i], p.vy[i], p.vz[i]});
    s.w.insert(s.w.end(), {p.wx[i], p.wy[i], p.wz[i]});
  }
  return s;
}

/// The runs on two and three threads end with the particles of the run on one thread, bit for
/// bit (operator== on doubles, no tolerance).
void expect_bitwise_equal(const State& one, const State& two, const State& three) {
  EXPECT_TRUE(one.x == two.x);
  EXPECT_TRUE(one.v == two.v);
  EXPECT_TRUE(one.w == two.w);
  EXPECT_TRUE(one.x == three.x);
  EXPECT_TRUE(one.v == three.v);
  EXPECT_TRUE(one.w == three.w);
}

TEST(ThreadIndependence, OneAndTwoThreadsGiveBitwiseIdenticalParticles) {
  const State one = run_with_threads(1);
  const State two = run_with_threads(2);
  // Three threads: the slabs are shared out in contiguous runs by particle count, which two
  // threads split in halves; three split them unevenly (and share two cores here).
  const State three = run_with_threads(3);
  ASSERT_EQ(one.x.size(), 18000u);
  expect_bitwise_equal(one, two, three);
  // The run did something: contacts exist, particles rotate.
  EXPECT_GT(one.contacts, 100);
  double wmax = 0.0;
  for (double c : one.w) wmax = std::max(wmax, std::abs(c));
  EXPECT_GT(wmax, 0.0);
}

TEST(ThreadIndependence, LargeBedInSlabGroupsGivesBitwiseIdenticalParticles) {
  const State one = run_with_threads(1, kLargeCase, 60);
  const State two = run_with_threads(2, kLargeCase, 60);
  const State three = run_with_threads(3, kLargeCase, 60);
  ASSERT_EQ(one.x.size(), 120000u);
  expect_bitwise_equal(one, two, three);
  EXPECT_GT(one.contacts, 1000); // the particles collide (0.8 m/s spread, 1.2 ms)
}

TEST(ThreadIndependence, ClosedBoxWithWallsInEverySlabGivesBitwiseIdenticalParticles) {
  const State one = run_with_threads(1, kClosedCase);
  const State two = run_with_threads(2, kClosedCase);
  const State three = run_with_threads(3, kClosedCase);
  ASSERT_EQ(one.x.size(), 18000u);
  expect_bitwise_equal(one, two, three);
  // Walls near a third of the particles (the y walls are four diameters apart).
  EXPECT_GT(one.wall_entries, 1500u); // 1955
  EXPECT_GT(one.contacts, 100);
}

// The contact models with history of their own (issue 34): Walton & Braun's normal spring
// (delta_max per contact, k1 = 5000 N/m with a step of 6e-6 s: a pair contact lasts ~15 steps,
// an overlap stays below 10% of a diameter up to ~3 m/s) and the
// Mindlin-Deresiewicz tangential force, in the closed box (pairs and walls in every slab).
TEST(ThreadIndependence, WaltonBraunAndMindlinDeresiewiczGiveBitwiseIdenticalParticles) {
  std::string text = kClosedCase;
  const std::string hertz = "normal = \"hertz\"\ntangential = \"history\"\n";
  const std::string step = "time_step = 1.2e-5\n";
  ASSERT_NE(text.find(hertz), std::string::npos);
  ASSERT_NE(text.find(step), std::string::npos);
  text.replace(text.find(step), step.size(), "time_step = 6e-6\n");
  text.replace(text.find(hertz), hertz.size(),
               "normal = \"walton_braun\"\nstiffness = 5000.0\n"
               "tangential = \"mindlin_deresiewicz\"\n");
  const State one = run_with_threads(1, text.c_str());
  const State two = run_with_threads(2, text.c_str());
  const State three = run_with_threads(3, text.c_str());
  ASSERT_EQ(one.x.size(), 18000u);
  expect_bitwise_equal(one, two, three);
  EXPECT_GT(one.contacts, 100);
  double wmax = 0.0;
  for (double c : one.w) wmax = std::max(wmax, std::abs(c));
  EXPECT_GT(wmax, 0.0); // the tangential force acts
}

// The JKR adhesive normal model (issue 34): history "attached" per contact, entries that touch
// in tension down to -delta_c (the walk's attached test), the list's reach, in the closed box
// (pairs and walls in every slab).
TEST(ThreadIndependence, JkrGivesBitwiseIdenticalParticles) {
  std::string text = kClosedCase;
  const std::string hertz = "normal = \"hertz\"\n";
  ASSERT_NE(text.find(hertz), std::string::npos);
  text.replace(text.find(hertz), hertz.size(), "normal = \"jkr\"\nadhesion_energy = 0.2\n");
  const State one = run_with_threads(1, text.c_str());
  const State two = run_with_threads(2, text.c_str());
  const State three = run_with_threads(3, text.c_str());
  ASSERT_EQ(one.x.size(), 18000u);
  expect_bitwise_equal(one, two, three);
  EXPECT_GT(one.contacts, 100);
}

// kCase on a floor of fixed particles (a lattice layer, inserted first so that the random bed
// avoids it): pairs with a fixed partner (1/m = 0) in the soft-sphere contact loop, no pairs of
// two fixed ones, no wall entries of them; and the same with the hard-sphere engine, whose
// collisions with fixed particles are found on the moving one's parabola.
std::string fixed_layer_case(const char* engine) {
  std::string text = kCase;
  const std::string layer = "[[insert]]\nspecies = \"glass\"\ncount = 676\n"
                            "placement = \"lattice\"\n"
                            "region = { hi = [0.08, 0.08, 0.003] }\nfixed = true\n";
  text.insert(text.find("[[insert]]"), layer);
  text.insert(text.find("[simulation]\n") + 13, std::string("engine = \"") + engine + "\"\n");
  return text;
}

TEST(ThreadIndependence, FixedLayerGivesBitwiseIdenticalParticles) {
  for (const char* engine : {"soft_sphere", "hard_sphere"}) {
    const std::string text = fixed_layer_case(engine);
    const State one = run_with_threads(1, text.c_str());
    const State two = run_with_threads(2, text.c_str());
    const State three = run_with_threads(3, text.c_str());
    ASSERT_EQ(one.x.size(), 3u * 6676u) << engine;
    expect_bitwise_equal(one, two, three);
  }
}

// kCase with the non-contact forces (noncontact/): van der Waals between the particles and with
// the walls, charged particles (half the bed each sign) with Coulomb forces across the periodic
// sides and image charges in the conducting floor, and wet particles with liquid bridges
// (forming, rupturing, shared liquid). Their per-particle sums run over each particle's partners
// in index order, in parallel over the particles.
TEST(ThreadIndependence, NonContactForcesGiveBitwiseIdenticalParticles) {
  std::string text = kCase;
  text.insert(text.find("[simulation]\n") + 13, "force_time_step = true\n");
  const std::string second = "[[insert]]\nspecies = \"glass\"\ncount = 3000\n"
                             "placement = \"random\"\nvelocity_spread = 0.8\nseed = 9\n"
                             "charge = -1e-10\n";
  text.insert(text.find("[contact]"), second);
  text.replace(text.find("count = 6000"), 12, "count = 3000\ncharge = 1e-10");
  text += "[van_der_waals]\nhamaker = 1e-19\nmin_separation = 4e-10\nrange = 3e-4\n"
          "wall_hamaker = 1e-19\n"
          "[electrostatics]\ncutoff = 0.009\nconducting_walls = [\"z_lo\"]\n"
          "[liquid_bridge]\nsurface_tension = 0.0728\ncontact_angle = 20\nviscosity = 1e-3\n"
          "min_gap = 1e-6\n";
  text.insert(text.find("rolling_friction = 0.05"), "liquid_fraction = 1e-3\n");
  const State one = run_with_threads(1, text.c_str(), 80);
  const State two = run_with_threads(2, text.c_str(), 80);
  const State three = run_with_threads(3, text.c_str(), 80);
  ASSERT_EQ(one.x.size(), 18000u);
  expect_bitwise_equal(one, two, three);
  EXPECT_GT(one.contacts, 100);
}

// A liquid-fluidised column of 5000 spheres (above kThreadedParticles: the fluid forces' particle
// loop runs on the threads) with every fluid force of [coupling.forces] on.
const char* const kFluidForcesCase = R"(
[simulation]
end_time = 1.0
time_step = 1e-5
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.06, 0.06, 0.12]
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
[[insert]]
species = "glass"
count = 5000
placement = "random"
velocity_spread = 0.1
seed = 3
[gas]
cells = [6, 6, 12]
time_step = 1e-4
eos = "incompressible"
density = 1000.0
viscosity = 1e-3
[gas.boundary.bottom]
type = "inflow"
velocity = 0.02
[gas.boundary.top]
type = "pressure"
[coupling]
drag = "wen_yu"
[coupling.forces]
virtual_mass = true
basset = true
basset_window = 5
saffman = true
magnus = "oesterle_bui_dinh"
torque = "dennis"
)";

TEST(ThreadIndependence, FluidForcesGiveBitwiseIdenticalParticles) {
  // 100 steps: 10 flow steps.
  const State one = run_with_threads(1, kFluidForcesCase, 100);
  const State two = run_with_threads(2, kFluidForcesCase, 100);
  const State three = run_with_threads(3, kFluidForcesCase, 100);
  expect_bitwise_equal(one, two, three);
}

} // namespace
} // namespace fluidem

namespace fluidem {
namespace {

// A coarse-grained coupled bed: Case D of the Chang08 bubbling bed (1850 parcels of W = 64 real
// particles, chang08 Hertz scaling, drag at the real diameter shared by scheme 2), 300 steps.
TEST(ThreadIndependence, CoarseGrainedBubblingBedGivesBitwiseIdenticalParticles) {
  std::ifstream f(std::string(FLUIDEM_SOURCE_DIR) + "/cases/chang08/bubbling_D.toml");
  std::stringstream text;
  text << f.rdbuf();
  const std::string s = text.str();
  ASSERT_NE(s.find("[coarse_graining]"), std::string::npos);
  const State one = run_with_threads(1, s.c_str(), 300);
  const State two = run_with_threads(2, s.c_str(), 300);
  const State three = run_with_threads(3, s.c_str(), 300);
  expect_bitwise_equal(one, two, three);
}

} // namespace
} // namespace fluidem
