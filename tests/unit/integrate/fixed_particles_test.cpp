// Fixed particles ([[insert]] fixed = true, docs/fixed_particles.md): held in place, bodies of
// infinite mass in every collision.
//
// Soft spheres, head-on impact on a fixed sphere (linear spring-dashpot, no gravity): against a
// partner of infinite mass the contact's effective mass is the moving sphere's, m* = m, so the
// impact is that of [Deen07 eq. 41] with m* = m: contact duration
// t_c = sqrt(m (pi^2 + ln^2 e) / k_n) and rebound speed e v (the damping is calibrated with m*,
// [Deen07 eq. 27]). A free partner of the same mass would give m* = m/2 (t_c 29% shorter); the
// 20000 kg/m3 stand-in of before, m* = 0.88 m (t_c 6% shorter). Tolerance 1% (dt = t_c/400; the
// first and last contact steps cut the contact by up to a step: 0.25% each).
//
// Hard spheres under gravity: a sphere dropped from rest above a fixed one meets it when it has
// fallen sigma_z0 - sqrt(sigma^2 - b^2) (b: the horizontal offset), after
// t_c = sqrt(2 (z0 - z_c) / g) (free fall), and leaves with v' = v - (1 + e)(v.n) n (smooth,
// [Deen07 eq. 20] with 1/m_n = 1/m: infinite partner mass), then flies on a parabola: the state
// at the end of the flow step is checked against these closed forms to 1e-9 (the collision time
// is bisected to adjacent doubles, the rest is double arithmetic).
//
// Both engines, a bed falling onto a fixed layer (a rough floor): the fixed particles keep their
// positions bit for bit and no velocity, the moving ones come to rest on them (no overlap beyond
// contact.max_overlap, no missed hard-sphere collision), the energies stay finite, and the
// result is the same bit for bit with one and two threads.
//
// The automatic time step follows only the contacts that can happen: a species used only by
// fixed particles (tiny, light ones: a rough wall) does not shorten it. A fixed particle may not
// overlap a wall. The energies of a fixed particle are zero (it is part of the walls).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "../../common/cli_runner.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

/// Bit for bit (Vec3 has no operator==).
bool same(const Vec3& a, const Vec3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

constexpr double kPi = std::numbers::pi;
constexpr double kD = 0.004, kR = 0.5 * kD, kRho = 2700.0, kBox = 0.04, kK = 1.0e4;
const double kMass = kRho * kPi * kD * kD * kD / 6.0;

/// One fixed sphere at the box centre and one moving sphere at `above` (centre offsets x, z from
/// the fixed one's centre) with velocity (0, 0, vz).
std::string two_spheres(bool hard, double e, double dt, double gz, double bx, double bz,
                        double vz) {
  const double c = 0.5 * kBox;
  auto box = [&](double x, double z) {
    return fmt::format("{{ lo = [{:.17g}, {:.17g}, {:.17g}], hi = [{:.17g}, {:.17g}, {:.17g}] }}",
                       x - kR, c - kR, z - kR, x + kR, c + kR, z + kR);
  };
  return fmt::format(
      "[simulation]\nengine = \"{engine}\"\nend_time = 1.0\ntime_step = {dt:.17g}\n"
      "gravity = [0.0, 0.0, {gz}]\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [{L}, {L}, {L}]\n"
      "[hardsphere]\ntc_time = 0.0\n"
      "[[species]]\nname = \"s\"\ndiameter = {d}\ndensity = {rho}\nrestitution = {e:.17g}\n"
      "friction = 0.0\n"
      "[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\nregion = {fixed}\n"
      "fixed = true\n"
      "[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\nregion = {moving}\n"
      "velocity = [0.0, 0.0, {vz:.17g}]\n"
      "[contact]\nnormal = \"linear\"\nstiffness = {k}\ntangential = \"history\"\n",
      fmt::arg("engine", hard ? "hard_sphere" : "soft_sphere"), fmt::arg("dt", dt),
      fmt::arg("gz", gz), fmt::arg("L", kBox), fmt::arg("d", kD), fmt::arg("rho", kRho),
      fmt::arg("e", e), fmt::arg("fixed", box(c, c)), fmt::arg("moving", box(c + bx, c + bz)),
      fmt::arg("vz", vz), fmt::arg("k", kK));
}

TEST(FixedParticles, SoftImpactOnAFixedSphereHasTheMovingSpheresMass) {
  for (const double e : {0.5, 0.9}) {
    const double l = std::log(e);
    const double tc = std::sqrt(kMass * (kPi * kPi + l * l) / kK); // [Deen07 eq. 41], m* = m
    const double dt = tc / 400.0;
    Simulation sim(
        read_case_string(two_spheres(false, e, dt, 0.0, 0.0, kD + 0.1 * kD, -1.0), "fixed.toml"));
    const ParticleStore& p = sim.particles();
    ASSERT_EQ(p.size(), 2u);
    ASSERT_TRUE(p.fixed(0));
    ASSERT_FALSE(p.fixed(1));
    const Vec3 x0 = p.position(0);
    long contact_steps = 0;
    bool touched = false;
    for (long step = 0; step < 100000; ++step) {
      sim.advance(1);
      if (sim.contact_stats().n_contacts > 0)
        touched = true, ++contact_steps;
      else if (touched)
        break;
    }
    ASSERT_TRUE(touched);
    const double duration = static_cast<double>(contact_steps) * dt;
    std::printf("e = %.1f: rebound %.6f m/s (e v = %.6f), contact %.6g s (t_c(m* = m) = %.6g s)\n",
                e, p.vz[1], e, duration, tc);
    EXPECT_NEAR(p.vz[1], e * 1.0, 0.01 * e);
    EXPECT_NEAR(duration / tc, 1.0, 0.01);
    // The fixed sphere has not moved, bit for bit, and has no velocity.
    EXPECT_TRUE(same(p.position(0), x0));
    EXPECT_TRUE(same(p.velocity(0), Vec3{0.0, 0.0, 0.0}));
    EXPECT_TRUE(same(p.angular_velocity(0), Vec3{0.0, 0.0, 0.0}));
    // Its energy counts nowhere: the kinetic energy is the moving sphere's.
    const double v2 = p.vx[1] * p.vx[1] + p.vy[1] * p.vy[1] + p.vz[1] * p.vz[1];
    EXPECT_EQ(sim.energies().kinetic, 0.5 * p.mass[1] * v2);
  }
}

TEST(FixedParticles, HardSphereDropsOntoAFixedSphere) {
  const double g = 9.81, e = 0.8, dt = 1e-4, sigma = kD;
  for (const double b : {0.0, 0.3 * kD}) {
    const double h = 0.01; // z0 above the fixed centre
    Simulation sim(
        read_case_string(two_spheres(true, e, dt, -g, b, sigma + h, 0.0), "fixed_hard.toml"));
    const ParticleStore& p = sim.particles();
    const Vec3 fixed0 = p.position(0);
    const double z0 = p.z[1] - p.z[0];
    const double zc = std::sqrt(sigma * sigma - b * b); // centre height above the fixed one's
    const double tc = std::sqrt(2.0 * (z0 - zc) / g);
    const Vec3 n{b / sigma, 0.0, zc / sigma}; // from the fixed centre to the moving one
    const Vec3 v_in{0.0, 0.0, -g * tc};
    const Vec3 v_out = v_in - n * ((1.0 + e) * dot(v_in, n));
    const long steps = static_cast<long>(std::ceil(tc / dt)) + 3; // a few steps after it
    sim.advance(steps);
    const double t = static_cast<double>(steps) * dt, s = t - tc;
    const Vec3 x_ref = fixed0 + n * sigma + v_out * s + Vec3{0.0, 0.0, -0.5 * g * s * s};
    const Vec3 v_ref = v_out + Vec3{0.0, 0.0, -g * s};
    std::printf("offset %.4g m: collision at %.9g s; after: x = (%.12g, %.12g) m, reference "
                "(%.12g, %.12g); v = (%.12g, %.12g) m/s, reference (%.12g, %.12g)\n",
                b, tc, p.x[1], p.z[1], x_ref.x, x_ref.z, p.vx[1], p.vz[1], v_ref.x, v_ref.z);
    EXPECT_EQ(sim.hard_sphere()->stats().collisions, 1);
    EXPECT_NEAR(p.x[1], x_ref.x, 1e-9);
    EXPECT_NEAR(p.z[1], x_ref.z, 1e-9);
    EXPECT_NEAR(p.vx[1], v_ref.x, 1e-9);
    EXPECT_NEAR(p.vz[1], v_ref.z, 1e-9);
    EXPECT_TRUE(same(p.position(0), fixed0));
    EXPECT_TRUE(same(p.velocity(0), Vec3{0.0, 0.0, 0.0}));
  }
}

/// A closed box with a fixed lattice layer on the floor (a rough floor) and `count` spheres
/// falling onto it.
std::string bed_on_a_fixed_layer(bool hard, int count) {
  return fmt::format(R"(
[simulation]
engine = "{}"
end_time = 1.0
time_step = {}
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.03, 0.03, 0.06]
[walls]
friction = 0.3
[[species]]
name = "glass"
diameter = 0.003
density = 2500.0
youngs_modulus = 1e7
restitution = 0.8
friction = 0.4
[[insert]]
species = "glass"
count = 100
placement = "lattice"
region = {{ lo = [0.0, 0.0, 0.0], hi = [0.03, 0.03, 0.003] }}
fixed = true
[[insert]]
species = "glass"
count = {}
placement = "random"
region = {{ lo = [0.0, 0.0, 0.004], hi = [0.03, 0.03, 0.06] }}
velocity_spread = 0.3
seed = 3
[contact]
normal = "hertz"
tangential = "history"
rolling = "spring_dashpot"
)",
                     hard ? "hard_sphere" : "soft_sphere", hard ? 1e-4 : 2e-5, count);
}

struct State {
  std::vector<double> x, v, w;
};

State settle(bool hard, int threads, long steps) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  Simulation sim(read_case_string(bed_on_a_fixed_layer(hard, 600), "b.toml"));
  // The store as inserted, by id (the soft-sphere engine sorts it in space).
  ParticleStore fixed_before = sim.particles();
  {
    std::vector<std::uint32_t> order(fixed_before.size());
    for (std::size_t i = 0; i < order.size(); ++i)
      order[static_cast<std::size_t>(fixed_before.id[i] - 1)] = static_cast<std::uint32_t>(i);
    fixed_before.permute(order);
  }
  sim.advance(steps);
  omp_set_num_threads(saved);
  const ParticleStore& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.fixed(i)) {
      // Above the fixed layer: at least in a hollow of four touching fixed spheres, the
      // centre d / sqrt(2) above theirs (less 10% for the overlap of soft contacts).
      EXPECT_GT(p.z[i], 0.0015 + 0.9 * 0.003 / std::sqrt(2.0))
          << "particle " << p.id[i] << " went through";
      continue;
    }
    // Fixed: where it was inserted.
    const auto k = static_cast<std::size_t>(p.id[i] - 1);
    EXPECT_TRUE(same(p.position(i), fixed_before.position(k)));
    EXPECT_TRUE(same(p.velocity(i), Vec3{0.0, 0.0, 0.0}));
    EXPECT_TRUE(same(p.angular_velocity(i), Vec3{0.0, 0.0, 0.0}));
  }
  const Energies en = sim.energies();
  EXPECT_TRUE(std::isfinite(en.kinetic) && std::isfinite(en.rotational) &&
              std::isfinite(en.potential));
  State s;
  std::vector<std::size_t> by_id(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) by_id[static_cast<std::size_t>(p.id[i] - 1)] = i;
  for (const std::size_t i : by_id) {
    s.x.insert(s.x.end(), {p.x[i], p.y[i], p.z[i]});
    s.v.insert(s.v.end(), {p.vx[i], p.vy[i], p.vz[i]});
    s.w.insert(s.w.end(), {p.wx[i], p.wy[i], p.wz[i]});
  }
  return s;
}

TEST(FixedParticles, SoftBedSettlesOnAFixedLayer) {
  const State one = settle(false, 1, 6000); // 0.12 s
  const State two = settle(false, 2, 6000);
  EXPECT_TRUE(one.x == two.x && one.v == two.v && one.w == two.w);
}

TEST(FixedParticles, HardSphereBedSettlesOnAFixedLayer) {
  const State one = settle(true, 1, 1500); // 0.15 s
  const State two = settle(true, 2, 1500);
  EXPECT_TRUE(one.x == two.x && one.v == two.v && one.w == two.w);
}

TEST(FixedParticles, TimeStepIgnoresContactsOnlyFixedParticlesCouldForm) {
  // A rough wall of 0.5 mm fixed particles under 4 mm moving ones (linear model: the contact
  // duration scales with sqrt(m*), so the tiny species' own pairs would cut the step ~20x).
  const std::string big =
      "[simulation]\nend_time = 0.1\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.04, 0.04, 0.04]\n"
      "[[species]]\nname = \"big\"\ndiameter = 0.004\ndensity = 2700.0\n";
  const std::string rest = "[[insert]]\nspecies = \"big\"\ncount = 20\n"
                           "region = { lo = [0.0, 0.0, 0.01], hi = [0.04, 0.04, 0.04] }\n"
                           "[contact]\nnormal = \"linear\"\nstiffness = 1000.0\n";
  const std::string head =
      big + "[[species]]\nname = \"small\"\ndiameter = 0.0005\ndensity = 2700.0\n" + rest;
  const std::string rough = "[[insert]]\nspecies = \"small\"\ncount = 200\nplacement = "
                            "\"lattice\"\nregion = { hi = [0.04, 0.04, 0.0005] }\n";
  const Simulation alone(read_case_string(big + rest, "a.toml")); // no small species at all
  const Simulation fixed(read_case_string(head + rough + "fixed = true\n", "f.toml"));
  const Simulation moving(read_case_string(head + rough, "m.toml"));
  std::printf("automatic step: big alone %.4g s, with a fixed rough wall %.4g s, with the small "
              "ones moving %.4g s\n",
              alone.time_step(), fixed.time_step(), moving.time_step());
  EXPECT_EQ(fixed.time_step(), alone.time_step());
  EXPECT_LT(moving.time_step(), 0.1 * alone.time_step());
  // Every particle fixed: no contact can happen; the step is 1e-4 s.
  const std::string all_fixed =
      "[simulation]\nend_time = 0.1\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.04, 0.04, 0.04]\n"
      "[[species]]\nname = \"big\"\ndiameter = 0.004\ndensity = 2700.0\n"
      "[[insert]]\nspecies = \"big\"\ncount = 20\nfixed = true\n";
  Simulation still(read_case_string(all_fixed, "s.toml"));
  EXPECT_NEAR(still.time_step(), 1e-4, 1e-12);
  const ParticleStore before = still.particles();
  still.advance(10);
  EXPECT_TRUE(still.particles().x == before.x && still.particles().z == before.z);
  const Energies en = still.energies();
  EXPECT_EQ(en.kinetic, 0.0);
  EXPECT_EQ(en.rotational, 0.0);
  EXPECT_EQ(en.potential, 0.0);
}

TEST(FixedParticles, AFixedParticleMayNotOverlapAWall) {
  test::TempDir dir("fluidem_fixed");
  // A particle 0.5% of its diameter into the floor: within the insertion tolerance (1%) when
  // it moves, refused when it is fixed (nothing could push it off).
  const auto file = dir.write("floor.data", "title\n\n1 atoms\n\nAtoms # sphere\n\n"
                                            "1 1 0.004 2700 0.02 0.02 0.00198\n");
  const std::string text =
      "[simulation]\nend_time = 0.1\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.04, 0.04, 0.04]\n"
      "[[species]]\nname = \"s\"\ndiameter = 0.004\ndensity = 2700.0\n"
      "[[insert]]\nspecies = \"s\"\nplacement = \"file\"\nfile = \"" +
      file.string() + "\"\n";
  EXPECT_NO_THROW(Simulation(read_case_string(text, "w.toml")));
  try {
    Simulation sim(read_case_string(text + "fixed = true\n", "w.toml"));
    ADD_FAILURE() << "a fixed particle overlapping the floor was accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("fixed particle 1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("z_lo wall"), std::string::npos) << msg;
  }
  // Touching is allowed (lattice rows against the walls).
  EXPECT_NO_THROW(Simulation(read_case_string(
      "[simulation]\nend_time = 0.1\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.04, 0.04, 0.04]\n"
      "[[species]]\nname = \"s\"\ndiameter = 0.004\ndensity = 2700.0\n"
      "[[insert]]\nspecies = \"s\"\ncount = 1000\nplacement = \"lattice\"\nfixed = true\n",
      "t.toml")));
}

} // namespace
} // namespace fluidem
