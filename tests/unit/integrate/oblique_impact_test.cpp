// Oblique impact of a sphere on the floor (z_lo wall), no gravity, linear spring-dashpot (and, for
// gross sliding, Hertz-Mindlin) with the tangential spring of [Deen07 eq. 28-31], checked against
// the two analytic regimes of an oblique impact [Maw, Barber & Fawcett 1976; Walton 1993; Deen07
// §2.3, eq. 43]:
//
// (a) Gross sliding, tan(theta) = v_t/v_n >> 7 mu/2: the contact point slides through the whole
//     contact, so the tangential force is mu F_n at every instant and the tangential impulse is
//     J_t = mu J_n (Coulomb), at every restitution: the normal force never pulls, so friction
//     (bounded by the compressive force) and the normal impulse see the same force (with a
//     tensile tail in J_n, J_t/J_n was 1.034 mu at e = 0.5). The friction torque r n x F_t spins
//     the sphere up to w = J_t r / I, I = 2/5 m r^2 (solid sphere). Sliding from the first step
//     needs the tangential trial force to exceed mu F_n there: with beta0 = 0 (the default) its
//     dashpot, eta_t v_t > mu eta_n v_n, holds for tan(theta) above ~0.2 here; with beta0 = 1 (no
//     tangential dashpot) the spring must first load up to the damped normal force's mu F_n, a
//     sticking onset that takes 5% of mu J_n at e = 0.3 (linear) and is not gross sliding.
// (b) Sticking, tan(theta) < 7 mu/2: with beta0 = 1 (undamped tangential spring) and
//     k_t/k_n = 2/7 [Deen07 eq. 43], the tangential spring acting on the reduced tangential mass
//     m_t = m / (1 + m r^2/I) = 2m/7 oscillates with sqrt(k_t/m_t) = sqrt(k_n/m), the normal
//     frequency. Both start together, F_t/F_n = (2/7) v_t/v_n stays constant (below mu: no slip)
//     and both end after half a period: the contact-point tangential velocity is reversed,
//     v_t,c(out) = -v_t,c(in). The spin again follows w = J_t r / I. friction = inf sticks at any
//     angle: the same reversal at tan(theta) = 5, where mu = 0.5 would slide.
//
// Tolerances: 1% on every ratio (dt = t_c/397; the first contact step integrates the tangential
// displacement over a whole step, an O(dt/t_c) error of ~0.3%), except J_t/J_n in gross sliding:
// 1e-9. Every step slides with F_t = mu F_n exactly, and J_n is the impulse of the same F_n, so
// the ratio is mu to round-off (measured: below 1e-13).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <ostream>
#include <string>

#include <fmt/format.h>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kD = 0.004; // m
constexpr double kR = 0.5 * kD;
constexpr double kRho = 2700.0;
constexpr double kBox = 0.04; // m: the side walls are far from the impact
constexpr double kK = 1.0e4;  // N/m, k_n
constexpr double kVn = 1.0;   // m/s, normal impact speed
constexpr double kInf = std::numeric_limits<double>::infinity(); // friction = inf
const double kMass = 4.0 / 3.0 * kPi * kR * kR * kR * kRho;
const double kInertia = 0.4 * kMass * kR * kR; // solid sphere

struct Oblique {
  double mu;          // wall friction
  double ratio;       // tan(theta) = v_t / v_n
  double e;           // wall restitution
  bool hertz = false; // Hertz-Mindlin instead of the linear spring
};
void PrintTo(const Oblique& o, std::ostream* os) {
  // also the ctest name suffix
  *os << (o.hertz ? "hertz_" : "") << "mu" << o.mu << "_tan" << o.ratio << "_e" << o.e;
}

// Hertz: E = 1e7 Pa, nu = 0.25 for the sphere and the floor; the elastic contact duration at
// v_n = 1 m/s [Johnson 1985 §11.4] sets the step: t_c = 2.94328 delta_max / v with
// delta_max = (15 m v^2 / (16 E* sqrt(R)))^{2/5}, E* = E / (2 (1 - nu^2)).
constexpr double kE = 1.0e7, kNu = 0.25;
double hertz_duration() {
  const double e_star = kE / (2.0 * (1.0 - kNu * kNu));
  const double dmax = std::pow(15.0 * kMass * kVn * kVn / (16.0 * e_star * std::sqrt(kR)), 0.4);
  return 2.94328 * dmax / kVn;
}

struct Result {
  double jn, jt;          // normal (+z) and tangential (x) impulse on the sphere, N s
  double wy;              // spin after the impact, rad/s
  double vtc_in, vtc_out; // contact-point tangential velocity before and after, m/s
};

/// The impact; beta0: the floor's tangential restitution.
Result run(const Oblique& o, double beta0) {
  const double l = std::log(o.e);
  const double tc = o.hertz ? hertz_duration()
                            : std::sqrt(kMass * (kPi * kPi + l * l) / kK); // [Deen07 eq. 41], wall
  const double dt = tc / 397.3;
  const std::string elastic = fmt::format("youngs_modulus = {}\npoisson_ratio = {}\n", kE, kNu);
  const std::string contact =
      o.hertz ? "normal = \"hertz\"\n" : fmt::format("normal = \"linear\"\nstiffness = {}\n", kK);
  const double c = 0.5 * kBox, z0 = kR + 0.01 * kD;
  const std::string text = fmt::format(
      "[simulation]\ndimension = 3\nend_time = 1.0\ntime_step = {dt:.17g}\n"
      "gravity = [0.0, 0.0, 0.0]\n\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [{L}, {L}, {L}]\n\n"
      "[walls]\nrestitution = {e:.17g}\nfriction = {mu:.17g}\ntangential_restitution = {b0}\n"
      "{elastic}\n"
      "[[species]]\nname = \"s\"\ndiameter = {d}\ndensity = {rho}\nrestitution = 0.5\n"
      "friction = 0.9\n{elastic}\n"
      "[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\n"
      "region = {{ lo = [{xl:.17g}, {xl:.17g}, {zl:.17g}], hi = [{xh:.17g}, {xh:.17g}, "
      "{zh:.17g}] }}\nvelocity = [{vt:.17g}, 0.0, {vn:.17g}]\n\n"
      "[contact]\n{contact}tangential = \"history\"\n",
      fmt::arg("dt", dt), fmt::arg("L", kBox), fmt::arg("e", o.e), fmt::arg("mu", o.mu),
      fmt::arg("d", kD), fmt::arg("rho", kRho), fmt::arg("xl", c - kR), fmt::arg("xh", c + kR),
      fmt::arg("zl", z0 - kR), fmt::arg("zh", z0 + kR), fmt::arg("vt", o.ratio * kVn),
      fmt::arg("vn", -kVn), fmt::arg("elastic", elastic), fmt::arg("contact", contact),
      fmt::arg("b0", beta0));
  Simulation sim(read_case_string(text, "oblique.toml"));
  const auto& p = sim.particles();
  EXPECT_EQ(p.size(), 1u);
  EXPECT_NEAR(p.z[0], z0, 1e-12);
  // Contact point at -r z: its velocity is v + w x (-r z), x component v_x - r w_y.
  auto vtc = [&] { return p.vx[0] - kR * p.wy[0]; };
  const double vx0 = p.vx[0], vz0 = p.vz[0];
  Result r;
  r.vtc_in = vtc();
  bool touched = false;
  for (long step = 0; step < 100000; ++step) {
    sim.advance(1);
    if (sim.contact_stats().n_contacts > 0)
      touched = true;
    else if (touched)
      break;
  }
  EXPECT_TRUE(touched);
  EXPECT_EQ(sim.contact_stats().n_contacts, 0) << "contact never ended";
  r.jn = kMass * (p.vz[0] - vz0);
  r.jt = kMass * (p.vx[0] - vx0);
  r.wy = p.wy[0];
  r.vtc_out = vtc();
  return r;
}

/// Spin from the tangential impulse: torque r n x F_t with n = -z gives I dw_y = -r dJ_x.
double spin_from_impulse(double jt) {
  return -jt * kR / kInertia;
}

class GrossSliding : public ::testing::TestWithParam<Oblique> {};

TEST_P(GrossSliding, TangentialImpulseIsMuTimesNormalImpulse) {
  const Oblique o = GetParam();
  // Preconditions of the regime: slipping from the first instant (2/7 v_t/v_n > mu) to the last
  // (the contact point still moves forward: v_t - 7/2 mu (1+e) v_n > 0).
  ASSERT_GT(2.0 / 7.0 * o.ratio, 2.0 * o.mu);
  ASSERT_GT(o.ratio - 3.5 * o.mu * (1.0 + o.e), 0.5 * o.ratio);
  const Result r = run(o, 0.0);
  const double ratio = -r.jt / r.jn;
  const double w_ref = spin_from_impulse(r.jt);
  std::cout << fmt::format("sliding, theta = {:.1f} deg, mu = {}, e = {}: J_t/J_n = {:.6f} "
                           "(error {:+.3e}), w/w_ref = {:.6f}, J_n/(m v_n) = {:.5f}\n",
                           std::atan(o.ratio) * 180.0 / kPi, o.mu, o.e, ratio, ratio / o.mu - 1.0,
                           r.wy / w_ref, r.jn / (kMass * kVn));
  EXPECT_NEAR(r.jn, (1.0 + o.e) * kMass * kVn, 0.01 * (1.0 + o.e) * kMass * kVn);
  EXPECT_NEAR(ratio, o.mu, 1e-9 * o.mu);
  EXPECT_NEAR(r.wy, w_ref, 0.01 * std::abs(w_ref));
  EXPECT_GT(r.vtc_out, 0.0) << "the contact point stopped: not gross sliding";
}

INSTANTIATE_TEST_SUITE_P(
    Angles, GrossSliding,
    ::testing::Values(Oblique{0.1, 2.0, 1.0}, Oblique{0.1, 3.0, 1.0}, Oblique{0.1, 6.0, 1.0},
                      Oblique{0.1, 3.0, 0.9}, Oblique{0.2, 4.0, 0.9}, Oblique{0.1, 3.0, 0.7},
                      Oblique{0.1, 3.0, 0.5}, Oblique{0.1, 3.0, 0.3}, Oblique{0.1, 3.0, 0.9, true},
                      Oblique{0.1, 3.0, 0.5, true}, Oblique{0.1, 3.0, 0.3, true}));

class Sticking : public ::testing::TestWithParam<Oblique> {};

TEST_P(Sticking, ContactPointTangentialVelocityReverses) {
  const Oblique o = GetParam();
  ASSERT_LT(o.ratio, 3.5 * o.mu / 1.5); // tan(theta) below 7 mu/2 with a margin
  const Result r = run(o, 1.0);
  const double w_ref = spin_from_impulse(r.jt);
  std::cout << fmt::format("sticking, theta = {:.1f} deg, mu = {}: v_tc,out/v_tc,in = {:.6f} "
                           "(error {:+.3e}), w/w_ref = {:.6f}\n",
                           std::atan(o.ratio) * 180.0 / kPi, o.mu, r.vtc_out / r.vtc_in,
                           r.vtc_out / r.vtc_in + 1.0, r.wy / w_ref);
  EXPECT_NEAR(r.vtc_out, -r.vtc_in, 0.01 * std::abs(r.vtc_in));
  EXPECT_NEAR(r.wy, w_ref, 0.01 * std::abs(w_ref));
  // Reversal of v_t,c with m_t = 2m/7 needs J_t = -2 m_t v_t: a check of the spin's share.
  EXPECT_NEAR(-r.jt, 4.0 / 7.0 * kMass * r.vtc_in, 0.01 * 4.0 / 7.0 * kMass * r.vtc_in);
}

INSTANTIATE_TEST_SUITE_P(Angles, Sticking,
                         ::testing::Values(Oblique{0.5, 0.1, 1.0}, Oblique{0.5, 0.2, 1.0},
                                           Oblique{0.5, 0.5, 1.0}, Oblique{0.5, 1.0, 1.0},
                                           Oblique{kInf, 5.0, 1.0}));

} // namespace
} // namespace fluidem
