// Initial angular velocity ([[insert]] angular_velocity, docs/case-file.md) in both engines.
//
// Free flight: a sphere given a spin w and no contact keeps it exactly (gravity acts at the
// centre: no torque), and its rotational energy is 1/2 I |w|^2 with the solid sphere's
// I = 2/5 m R^2, m = rho pi d^3 / 6 (computed here from the case's diameter and density), to
// round-off (1e-12). Also a 2-D disc turning about y.
//
// A spinning sphere hitting the floor (no gravity), against the closed forms of the
// three-parameter impact model [Foerster, Louge, Chang & Allia 1994, Phys. Fluids 6:1108;
// Walton 1993]: the wall's impulse J acts at the contact point, so the angular momentum about
// that point, m R v_x + I w_y, is conserved, i.e. dw_y = -(5/2) dv_x / R; the contact point
// slips at u = v_x - R w_y (its velocity is v + w x (-R z)). Sticking (mu (1+e) v_n >=
// 2/7 (1+beta0) |u|): the contact point's slip becomes -beta0 u, so
//   v_x' = v_x - 2/7 (1 + beta0) u     (beta0 = 0: v_x' = 5/7 v_x + 2/7 R w_y, rolling);
// sliding: Coulomb, |J_t| = mu J_n = mu (1 + e) m v_n, against the slip:
//   v_x' = v_x - mu (1 + e) v_n sign(u).
// The cases are chosen so that the spin sets the regime or the direction of friction (a spin
// R w_y > v_x makes the contact point slip backwards: friction then speeds the sphere up).
//  - Hard spheres (the collision operator applies the model exactly): 1e-12.
//  - Soft spheres (linear spring-dashpot, tangential spring with history, as
//    oblique_impact_test.cpp): gross sliding J_t/J_n = mu with the sign set by the spin, and
//    sticking with an undamped tangential spring (beta0 = 1, k_t/k_n = 2/7: the contact
//    point's slip reverses, u' = -u [Deen07 §2.3]); dw_y from dv_x as above. 1% (the
//    discretisation of the first contact step, oblique_impact_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kD = 0.004, kR = 0.5 * kD, kRho = 2700.0, kBox = 0.04;
const double kMass = kRho * kPi * kD * kD * kD / 6.0;
const double kInertia = 0.4 * kMass * kR * kR;

struct Launch {
  bool hard = false;
  int dimension = 3;
  double gz = 0.0;
  double z0 = 0.5 * kBox; ///< centre height, m
  double vx = 0.0, vz = 0.0;
  std::array<double, 3> w{};
  double e = 0.9, mu = 0.3, beta0 = 0.0; ///< the walls' material
  double dt = 1e-5;
};

std::string case_text(const Launch& s) {
  const double c = 0.5 * kBox;
  const double y_hi = s.dimension == 2 ? kD : kBox;
  const double yc = 0.5 * y_hi;
  return fmt::format(
      "[simulation]\ndimension = {dim}\nengine = \"{engine}\"\nend_time = 1.0\n"
      "time_step = {dt:.17g}\ngravity = [0.0, 0.0, {gz}]\n\n"
      "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [{L}, {yh}, {L}]\n\n"
      "[walls]\nrestitution = {e:.17g}\nfriction = {mu:.17g}\ntangential_restitution = {b:.17g}\n\n"
      "[[species]]\nname = \"s\"\ndiameter = {d}\ndensity = {rho}\n\n"
      "[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\n"
      "region = {{ lo = [{xl:.17g}, {yl:.17g}, {zl:.17g}], hi = [{xh:.17g}, {yhh:.17g}, "
      "{zh:.17g}] }}\nvelocity = [{vx:.17g}, 0.0, {vz:.17g}]\n"
      "angular_velocity = [{wx:.17g}, {wy:.17g}, {wz:.17g}]\n\n"
      "[contact]\nnormal = \"linear\"\nstiffness = 1.0e4\ntangential = \"history\"\n",
      fmt::arg("dim", s.dimension), fmt::arg("engine", s.hard ? "hard_sphere" : "soft_sphere"),
      fmt::arg("dt", s.dt), fmt::arg("gz", s.gz), fmt::arg("L", kBox), fmt::arg("yh", y_hi),
      fmt::arg("e", s.e), fmt::arg("mu", s.mu), fmt::arg("b", s.beta0), fmt::arg("d", kD),
      fmt::arg("rho", kRho), fmt::arg("xl", c - kR), fmt::arg("xh", c + kR),
      fmt::arg("yl", yc - kR), fmt::arg("yhh", yc + kR), fmt::arg("zl", s.z0 - kR),
      fmt::arg("zh", s.z0 + kR), fmt::arg("vx", s.vx), fmt::arg("vz", s.vz), fmt::arg("wx", s.w[0]),
      fmt::arg("wy", s.w[1]), fmt::arg("wz", s.w[2]));
}

TEST(InitialSpin, FreeFlightKeepsItsSpinAndEnergy) {
  const struct {
    bool hard;
    int dimension;
    std::array<double, 3> w;
    long steps;
  } cases[] = {{false, 3, {30.0, -70.0, 110.0}, 2000},
               {true, 3, {30.0, -70.0, 110.0}, 200},
               {false, 2, {0.0, 250.0, 0.0}, 2000}};
  for (const auto& c : cases) {
    Launch s;
    s.hard = c.hard;
    s.dimension = c.dimension;
    s.gz = -9.81;
    s.w = c.w;
    s.dt = c.hard ? 1e-4 : 1e-5;
    Simulation sim(read_case_string(case_text(s), "spin.toml"));
    const ParticleStore& p = sim.particles();
    ASSERT_EQ(p.size(), 1u);
    sim.advance(c.steps); // 0.02 s of flight: 2 mm of fall, far from the walls
    EXPECT_LT(p.vz[0], -0.19);
    EXPECT_EQ(p.wx[0], c.w[0]);
    EXPECT_EQ(p.wy[0], c.w[1]);
    EXPECT_EQ(p.wz[0], c.w[2]);
    const double w2 = c.w[0] * c.w[0] + c.w[1] * c.w[1] + c.w[2] * c.w[2];
    const double ref = 0.5 * kInertia * w2;
    std::printf("%s, %d-D: E_rot = %.12g J, 1/2 I w^2 = %.12g J\n", c.hard ? "hard" : "soft",
                c.dimension, sim.energies().rotational, ref);
    EXPECT_NEAR(sim.energies().rotational / ref, 1.0, 1e-12);
  }
}

struct Impact {
  double vx, vz, wy; ///< after the impact
};

/// One impact on the floor from 1 mm above it; the state once the contact (or collision) is
/// over.
Impact impact(const Launch& s) {
  Simulation sim(read_case_string(case_text(s), "impact.toml"));
  const ParticleStore& p = sim.particles();
  if (s.hard) {
    sim.advance(100); // the collision at 1 ms, then 9 ms of flight
    EXPECT_EQ(sim.hard_sphere()->stats().wall_collisions, 1);
  } else {
    bool touched = false;
    for (long step = 0; step < 200000; ++step) {
      sim.advance(1);
      if (sim.contact_stats().n_contacts > 0)
        touched = true;
      else if (touched)
        break;
    }
    EXPECT_TRUE(touched);
    EXPECT_EQ(sim.contact_stats().n_contacts, 0) << "the contact never ended";
  }
  return {p.vx[0], p.vz[0], p.wy[0]};
}

Launch floor_impact(bool hard, double vx, double r_wy, double e, double mu, double beta0) {
  Launch s;
  s.hard = hard;
  s.z0 = kR + 0.001;
  s.vx = vx;
  s.vz = -1.0;
  s.w = {0.0, r_wy / kR, 0.0};
  s.e = e, s.mu = mu, s.beta0 = beta0;
  // Soft: the linear contact lasts t_c = sqrt(m (pi^2 + ln^2 e) / k) [Deen07 eq. 41]; ~400 steps.
  const double l = std::log(e);
  s.dt = hard ? 1e-4 : std::sqrt(kMass * (kPi * kPi + l * l) / 1.0e4) / 397.3;
  return s;
}

TEST(InitialSpin, HardSphereSpinningImpactsFollowTheThreeParameterModel) {
  const struct {
    const char* name;
    double vx, r_wy, e, mu, beta0;
    bool sticking;
  } cases[] = {
      // u = 0.5 - (-1.0) = 1.5: mu (1+e) v_n = 1.8 >= 2/7 * 1.5: sticking, rolls off at
      // v_x' = 5/7 0.5 + 2/7 (-1.0) = 0.0714 m/s (0.357 m/s without the spin).
      {"sticking, backspin", 0.5, -1.0, 0.8, 1.0, 0.0, true},
      // u = 1 - 3 = -2: mu (1+e) v_n = 0.19 < 2/7 1.35 * 2: sliding, friction forwards:
      // v_x' = 1 + 0.19 (0.81 without the spin).
      {"sliding, topspin", 1.0, 3.0, 0.9, 0.1, 0.35, false},
      {"sticking, topspin, beta0 = 0.4", 0.2, 0.5, 0.7, 2.0, 0.4, true},
  };
  for (const auto& c : cases) {
    const Impact a = impact(floor_impact(true, c.vx, c.r_wy, c.e, c.mu, c.beta0));
    const double u = c.vx - c.r_wy, vn = 1.0;
    const bool sticks = c.mu * (1.0 + c.e) * vn >= 2.0 / 7.0 * (1.0 + c.beta0) * std::abs(u);
    ASSERT_EQ(sticks, c.sticking) << c.name;
    const double dvx = sticks ? -2.0 / 7.0 * (1.0 + c.beta0) * u
                              : -c.mu * (1.0 + c.e) * vn * (u > 0.0 ? 1.0 : -1.0);
    const double vx_ref = c.vx + dvx, wy_ref = c.r_wy / kR - 2.5 * dvx / kR;
    std::printf("hard, %s: v_x' = %.15g (model %.15g), w_y' = %.15g (model %.15g), v_z' = %.15g\n",
                c.name, a.vx, vx_ref, a.wy, wy_ref, a.vz);
    EXPECT_NEAR(a.vx, vx_ref, 1e-12 * std::abs(vx_ref)) << c.name;
    EXPECT_NEAR(a.wy, wy_ref, 1e-12 * std::abs(wy_ref)) << c.name;
    EXPECT_NEAR(a.vz, c.e * vn, 1e-12) << c.name;
  }
}

TEST(InitialSpin, SoftSphereGrossSlidingTakesItsDirectionFromTheSpin) {
  // u = 1 - 3 = -2 m/s: the contact point slips backwards through the whole contact (it starts
  // slipping, 2/7 |u| / v_n = 0.57 > mu, and loses at most 7/2 mu (1 + e) v_n = 0.67 m/s of its
  // 2 m/s), so friction pushes the sphere forwards: J_t = +mu J_n.
  const double mu = 0.1, e = 0.9;
  const Impact a = impact(floor_impact(false, 1.0, 3.0, e, mu, 1.0));
  const double jn = kMass * (a.vz + 1.0), jt = kMass * (a.vx - 1.0);
  const double dwy = a.wy - 3.0 / kR, dwy_ref = -2.5 * (a.vx - 1.0) / kR;
  std::printf("soft, gross sliding with topspin: J_t/J_n = %.6f (mu = %g), dw_y = %.6g rad/s "
              "(from dv_x: %.6g), J_n/(m v_n) = %.5f\n",
              jt / jn, mu, dwy, dwy_ref, jn / kMass);
  EXPECT_NEAR(jt / jn, mu, 0.01 * mu);
  EXPECT_NEAR(dwy, dwy_ref, 0.01 * std::abs(dwy_ref));
  EXPECT_NEAR(jn, (1.0 + e) * kMass, 0.01 * (1.0 + e) * kMass);
}

TEST(InitialSpin, SoftSphereStickingReversesTheSpinningContactPoint) {
  // v_x = 0.2, R w_y = 0.5: u = -0.3 m/s (0.2 without the spin); tan = |u| / v_n = 0.3 <
  // 7 mu / 2 / 1.5 = 0.93: sticking; undamped spring: u' = -u = +0.3 m/s, and
  // v_x' = v_x - 2/7 (1 + 1) u = 0.371 m/s.
  const double vx = 0.2, r_wy = 0.5, u = vx - r_wy;
  const Impact a = impact(floor_impact(false, vx, r_wy, 0.9, 0.4, 1.0));
  const double u_out = a.vx - kR * a.wy;
  const double vx_ref = vx - 4.0 / 7.0 * u;
  std::printf("soft, sticking with topspin: u' = %.6f m/s (-u = %.6f), v_x' = %.6f (%.6f)\n", u_out,
              -u, a.vx, vx_ref);
  EXPECT_NEAR(u_out, -u, 0.01 * std::abs(u));
  EXPECT_NEAR(a.vx, vx_ref, 0.01 * std::abs(vx_ref));
  EXPECT_NEAR(a.wy - r_wy / kR, -2.5 * (a.vx - vx) / kR, 0.01 * std::abs(2.5 * (a.vx - vx) / kR));
}

} // namespace
} // namespace fluidem
