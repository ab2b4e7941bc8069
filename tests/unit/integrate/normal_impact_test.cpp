// Head-on impacts through the whole Simulation (case text -> insertion -> neighbour list ->
// contact kernels -> velocity Verlet), checked against references independent of the code:
//
// * Linear spring-dashpot whose force never pulls [Deen07 eq. 24-26; Schwager & Poeschel 2008]:
//   a damped harmonic oscillator in the overlap until the force k delta + eta delta' vanishes.
//   The damping ratio zeta(e) that rebounds with e and the duration of the force pulse, in
//   units of sqrt(m*/k), come from tools/contact_reference.py (the ODE's exact solution solved
//   for its rebound speed with mpmath; tests/models/normal_damping.toml).
// * Hertz, elastic [Hertz 1882; Johnson 1985, "Contact Mechanics", §11.4]: F = K delta^{3/2},
//   K = 4/3 E* sqrt(R*). Energy: 1/2 m* v^2 = 2/5 K delta_max^{5/2}, so
//   delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^{2/5}, and
//   t_c = 2 int_0^{delta_max} d(delta)/sqrt(v^2 - 4K/(5m*) delta^{5/2})
//       = 2 (delta_max/v) int_0^1 dx/sqrt(1 - x^{5/2}) = (4/5) B(2/5, 1/2) delta_max / v
//       = 2.94328 delta_max / v. A rigid wall: E* = E/(1 - nu^2) of the particle alone.
// * Hertz with Tsuji's damping [Chang08 eq. 2.22]: the scaled impact equation depends on alpha
//   only, so the calibrated restitution e holds at every impact speed.
// * e = 0 is refused (no damping reaches it when the force never pulls, docs/contact.md); the
//   nearest, e = 0.01, rebounds at 1% of the impact speed.
//
// Tolerances: the rebound speed within 1e-3 of the impact speed, |e_measured - e| <= 1e-3, at
// every e (dt = t_c/397 of the elastic or the calibrated contact): the error is of first order
// in dt, from the steps in which the force starts (the dashpot's jump) and is cut off at zero;
// measured at most 5.8e-4 (Hertz, e = 0.1; 2.7e-4 with dt halved), 5.0e-4 (linear, e = 0.1), and
// 2.3e-4 at e = 0.01. Durations of the force pulse within 1% (counted in whole steps: +-1 step =
// 0.25%; measured at most 0.8%, e = 0.01); Hertz duration within 2% and Hertz maximum overlap
// within 1%.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kD = 0.004;      // m, particle diameter
constexpr double kR = 0.5 * kD;   // m
constexpr double kRho = 2700.0;   // kg/m^3
constexpr double kBox = 0.04;     // m, cubic domain: walls 4.5 diameters away from the impact
constexpr double kC = 0.5 * kBox; // m, centre of the domain
const double kMass = 4.0 / 3.0 * kPi * kR * kR * kR * kRho; // solid sphere, kg
// dt = t_c / 397.3: fine enough for ~0.1% and not commensurate with t_c, so the step count that
// measures the duration does not land on the reference by construction.
constexpr double kStepsPerContact = 397.3;

struct Material {
  double youngs = 1.0e7, poisson = 0.25, restitution = 0.9, friction = 0.3;
};

std::string material_keys(const Material& m) {
  return fmt::format("youngs_modulus = {:.17g}\npoisson_ratio = {:.17g}\nrestitution = {:.17g}\n"
                     "friction = {:.17g}\n",
                     m.youngs, m.poisson, m.restitution, m.friction);
}

/// [[insert]] of one particle centred at `x` moving with `v`: a lattice region exactly one
/// diameter wide holds exactly one site, at region lo + r.
std::string one_particle(const std::array<double, 3>& x, const std::array<double, 3>& v) {
  return fmt::format("[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\n"
                     "region = {{ lo = [{:.17g}, {:.17g}, {:.17g}], hi = [{:.17g}, {:.17g}, "
                     "{:.17g}] }}\nvelocity = [{:.17g}, {:.17g}, {:.17g}]\n",
                     x[0] - kR, x[1] - kR, x[2] - kR, x[0] + kR, x[1] + kR, x[2] + kR, v[0], v[1],
                     v[2]);
}

struct ImpactCase {
  bool hertz = false;
  double stiffness = 1.0e4; // N/m, linear model
  Material particle, wall;
  double dt = 0.0;
};

std::string case_text(const ImpactCase& s, const std::string& inserts) {
  std::string t = fmt::format("[simulation]\ndimension = 3\nend_time = 1.0\ntime_step = {:.17g}\n"
                              "gravity = [0.0, 0.0, 0.0]\n\n[domain]\nlo = [0.0, 0.0, 0.0]\n"
                              "hi = [{:.17g}, {:.17g}, {:.17g}]\n\n",
                              s.dt, kBox, kBox, kBox);
  t += "[walls]\n" + material_keys(s.wall) + "\n";
  t += fmt::format("[[species]]\nname = \"s\"\ndiameter = {:.17g}\ndensity = {:.17g}\n", kD, kRho);
  t += material_keys(s.particle) + "\n" + inserts + "\n[contact]\n";
  t += s.hertz ? "normal = \"hertz\"\n"
               : fmt::format("normal = \"linear\"\nstiffness = {:.17g}\n", s.stiffness);
  return t;
}

struct Impact {
  double restitution = 0.0; // rebound speed / impact speed (normal components)
  double duration = 0.0;    // s, steps with an overlap x dt
  double pulse = 0.0;       // s, steps with a contact force x dt
  double max_overlap = 0.0; // m
};

/// Advance step by step until the contact has come and gone; measure it.
Impact run_impact(const std::string& text, bool wall) {
  Simulation sim(read_case_string(text, "impact.toml"));
  const auto& p = sim.particles();
  const std::size_t expected = wall ? 1 : 2;
  EXPECT_EQ(p.size(), expected);
  // Normal approach speed: pair along x (particle 0 left, moving +x); wall: -z onto z_lo.
  auto approach = [&] { return wall ? -p.vz[0] : p.vx[0] - p.vx[1]; };
  const double v_in = approach();
  long first = -1, last = -1, pushing = 0;
  double max_ratio = 0.0;
  for (long step = 1; step <= 100000; ++step) {
    sim.advance(1);
    if (sim.contact_stats().n_contacts > 0) {
      if (first < 0) first = step;
      last = step;
      if (sim.contact_stats().max_force2 > 0.0) ++pushing;
      max_ratio = std::max(max_ratio, sim.contact_stats().max_overlap_ratio);
    } else if (first >= 0) {
      break;
    }
  }
  EXPECT_GT(first, 0) << "no contact";
  EXPECT_LT(last, 100000) << "contact never ended";
  Impact r;
  r.restitution = -approach() / v_in;
  r.duration = static_cast<double>(last - first + 1) * sim.time_step();
  r.pulse = static_cast<double>(pushing) * sim.time_step();
  r.max_overlap = max_ratio * kD; // ratio = overlap / smaller diameter (wall: / diameter)
  return r;
}

/// Duration of the force pulse of the linear spring-dashpot calibrated for e, in units of
/// sqrt(m*/k) (tools/contact_reference.py; pi for e = 1).
double linear_pulse(double e) {
  struct Row {
    double e, pulse;
  };
  static constexpr Row rows[] = {{1.0, kPi},
                                 {0.9, 3.074854457883249},
                                 {0.7, 2.918428016218161},
                                 {0.5, 2.7152891946310884},
                                 {0.3, 2.4213141942505154},
                                 {0.1, 1.8521618362955852},
                                 {0.01, 0.958024951390744}};
  for (const Row& r : rows)
    if (r.e == e) return r.pulse;
  ADD_FAILURE() << "no reference pulse for e = " << e;
  return 0.0;
}
double linear_duration(double m_eff, double k, double e) {
  return linear_pulse(e) * std::sqrt(m_eff / k);
}

/// Elastic Hertz impact [Johnson 1985 §11.4]: maximum overlap and duration.
double hertz_delta_max(double m_eff, double e_star, double r_eff, double v) {
  return std::pow(15.0 * m_eff * v * v / (16.0 * e_star * std::sqrt(r_eff)), 0.4);
}
double hertz_duration(double m_eff, double e_star, double r_eff, double v) {
  // 2 int_0^1 (1 - x^{5/2})^{-1/2} dx = (4/5) B(2/5, 1/2) = 2.943275
  const double factor = 0.8 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  EXPECT_NEAR(factor, 2.94328, 1e-5);
  return factor * hertz_delta_max(m_eff, e_star, r_eff, v) / v;
}
double e_star_of(const Material& a, const Material& b) {
  return 1.0 /
         ((1.0 - a.poisson * a.poisson) / a.youngs + (1.0 - b.poisson * b.poisson) / b.youngs);
}

std::string pair_inserts(double v, double gap) {
  const double off = kR + 0.5 * gap;
  return one_particle({kC - off, kC, kC}, {0.5 * v, 0.0, 0.0}) +
         one_particle({kC + off, kC, kC}, {-0.5 * v, 0.0, 0.0});
}
std::string wall_insert(double v, double gap) {
  return one_particle({kC, kC, kR + gap}, {0.0, 0.0, -v});
}

// ---- Linear spring-dashpot ------------------------------------------------------------------

class LinearPairImpact : public ::testing::TestWithParam<double> {};

TEST_P(LinearPairImpact, RestitutionAndForcePulseMatchTheCalibration) {
  const double e = GetParam();
  ImpactCase s;
  s.particle.restitution = e;
  s.wall.restitution = 0.3; // must not matter: no wall contact
  const double m_eff = 0.5 * kMass;
  const double tc = linear_duration(m_eff, s.stiffness, e);
  s.dt = tc / kStepsPerContact;
  const Impact r = run_impact(case_text(s, pair_inserts(1.0, 0.01 * kD)), false);
  std::cout << fmt::format("linear pair e = {}: rebound ratio {:.6f} (error {:+.3e}), force "
                           "pulse {:.6e} s vs {:.6e} s (error {:+.3e}), overlap {:.6e} s\n",
                           e, r.restitution, r.restitution / e - 1.0, r.pulse, tc,
                           r.pulse / tc - 1.0, r.duration);
  EXPECT_NEAR(r.restitution, e, 1e-3);
  EXPECT_NEAR(r.pulse, tc, 0.01 * tc);
}

INSTANTIATE_TEST_SUITE_P(Restitution, LinearPairImpact,
                         ::testing::Values(0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0));

TEST(LinearWallImpact, UsesTheWallsRestitution) {
  // Particle e = 0.3, wall e = 0.7: a particle-wall contact takes the wall's e [contact_table]
  // and the particle's full mass (a wall of infinite mass).
  ImpactCase s;
  s.particle.restitution = 0.3;
  s.wall.restitution = 0.7;
  const double tc = linear_duration(kMass, s.stiffness, 0.7);
  s.dt = tc / kStepsPerContact;
  const Impact r = run_impact(case_text(s, wall_insert(1.0, 0.01 * kD)), true);
  std::cout << fmt::format("linear wall e_w = 0.7: rebound ratio {:.6f} (error {:+.3e}), "
                           "pulse error {:+.3e}\n",
                           r.restitution, r.restitution / 0.7 - 1.0, r.pulse / tc - 1.0);
  EXPECT_NEAR(r.restitution, 0.7, 1e-3);
  EXPECT_NEAR(r.pulse, tc, 0.01 * tc);
}

// ---- Hertz ----------------------------------------------------------------------------------

Material glass_like(double e) {
  Material m;
  m.youngs = 5.0e10; // keeps delta_max / d ~ 0.2% at 2 m/s
  m.poisson = 0.25;
  m.restitution = e;
  return m;
}

TEST(HertzPairImpact, ElasticDurationAndMaxOverlapMatchHertzTheory) {
  for (double v : {0.5, 2.0}) {
    ImpactCase s;
    s.hertz = true;
    s.particle = glass_like(1.0);
    s.wall = glass_like(1.0);
    const double m_eff = 0.5 * kMass, r_eff = 0.5 * kR;
    const double e_star = e_star_of(s.particle, s.particle);
    const double tc = hertz_duration(m_eff, e_star, r_eff, v);
    const double dmax = hertz_delta_max(m_eff, e_star, r_eff, v);
    s.dt = tc / kStepsPerContact;
    const Impact r = run_impact(case_text(s, pair_inserts(v, 0.5 * dmax)), false);
    std::cout << fmt::format("hertz pair e = 1, v = {} m/s: rebound ratio {:.6f}, duration "
                             "{:.6e} s vs {:.6e} s (error {:+.3e}), max overlap {:.6e} m vs "
                             "{:.6e} m (error {:+.3e})\n",
                             v, r.restitution, r.duration, tc, r.duration / tc - 1.0, r.max_overlap,
                             dmax, r.max_overlap / dmax - 1.0);
    EXPECT_NEAR(r.restitution, 1.0, 0.01) << "v = " << v;
    EXPECT_NEAR(r.duration, tc, 0.02 * tc) << "v = " << v;
    EXPECT_NEAR(r.max_overlap, dmax, 0.01 * dmax) << "v = " << v;
  }
}

struct HertzDamped {
  double e, v;
};
void PrintTo(const HertzDamped& h, std::ostream* os) {
  *os << "e" << h.e << "_v" << h.v; // also the ctest name suffix
}

class HertzPairRestitution : public ::testing::TestWithParam<HertzDamped> {};

TEST_P(HertzPairRestitution, IsTheCalibratedOneAtEverySpeed) {
  const auto [e, v] = GetParam();
  ImpactCase s;
  s.hertz = true;
  s.particle = glass_like(e);
  s.wall = glass_like(1.0);
  const double m_eff = 0.5 * kMass, r_eff = 0.5 * kR;
  const double e_star = e_star_of(s.particle, s.particle);
  s.dt = hertz_duration(m_eff, e_star, r_eff, v) / kStepsPerContact;
  const double dmax = hertz_delta_max(m_eff, e_star, r_eff, v);
  const Impact r = run_impact(case_text(s, pair_inserts(v, 0.5 * dmax)), false);
  std::cout << fmt::format("hertz pair e = {}, v = {} m/s: rebound ratio {:.6f} (error {:+.3e})\n",
                           e, v, r.restitution, r.restitution / e - 1.0);
  EXPECT_NEAR(r.restitution, e, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Speeds, HertzPairRestitution,
                         ::testing::Values(HertzDamped{0.9, 0.5}, HertzDamped{0.9, 2.0},
                                           HertzDamped{0.7, 1.0}, HertzDamped{0.5, 0.5},
                                           HertzDamped{0.5, 2.0}, HertzDamped{0.3, 1.0},
                                           HertzDamped{0.1, 0.5}, HertzDamped{0.1, 2.0},
                                           HertzDamped{0.01, 1.0}));

TEST(HertzWallImpact, UsesTheWallsMaterial) {
  // Wall E and nu differ from the particle's: E* mixes both [Johnson 1985 eq. 4.22]; the wall
  // has infinite mass and radius (m* = m, R* = r).
  Material wall;
  wall.youngs = 2.0e10;
  wall.poisson = 0.3;
  for (double e_w : {1.0, 0.6}) {
    ImpactCase s;
    s.hertz = true;
    s.particle = glass_like(0.3);
    wall.restitution = e_w;
    s.wall = wall;
    const double v = 1.0;
    const double e_star = e_star_of(s.particle, s.wall);
    const double tc = hertz_duration(kMass, e_star, kR, v);
    const double dmax = hertz_delta_max(kMass, e_star, kR, v);
    s.dt = tc / kStepsPerContact;
    const Impact r = run_impact(case_text(s, wall_insert(v, 0.5 * dmax)), true);
    std::cout << fmt::format("hertz wall e_w = {}: rebound ratio {:.6f} (error {:+.3e}), "
                             "duration error {:+.3e}, max overlap error {:+.3e}\n",
                             e_w, r.restitution, r.restitution / e_w - 1.0, r.duration / tc - 1.0,
                             r.max_overlap / dmax - 1.0);
    EXPECT_NEAR(r.restitution, e_w, 1e-3);
    if (e_w == 1.0) {
      EXPECT_NEAR(r.duration, tc, 0.02 * tc);
      EXPECT_NEAR(r.max_overlap, dmax, 0.01 * dmax);
    }
  }
}

TEST(HertzWallImpact, RigidWallLeavesTheParticlesOwnStiffness) {
  // walls.youngs_modulus = "rigid": E* = E/(1 - nu^2) of the particle alone; the same impact as
  // on a wall of E = 1e25 Pa (the old work-around), to 1e-9.
  for (double e_w : {1.0, 0.6}) {
    ImpactCase s;
    s.hertz = true;
    s.particle = glass_like(0.3);
    s.wall.restitution = e_w;
    const double v = 1.0;
    const double e_star = s.particle.youngs / (1.0 - s.particle.poisson * s.particle.poisson);
    const double r_eff = kR;
    const double tc = 0.8 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9) *
                      hertz_delta_max(kMass, e_star, r_eff, v) / v;
    const double dmax = hertz_delta_max(kMass, e_star, r_eff, v);
    s.dt = tc / kStepsPerContact;
    std::string rigid = case_text(s, wall_insert(v, 0.5 * dmax));
    const std::string soft_wall = material_keys(s.wall);
    const std::string youngs = fmt::format("youngs_modulus = {:.17g}\n", s.wall.youngs);
    ASSERT_NE(rigid.find(soft_wall), std::string::npos);
    rigid.replace(rigid.find(youngs), youngs.size(), "youngs_modulus = \"rigid\"\n");
    std::string stiff = rigid;
    stiff.replace(stiff.find("\"rigid\""), 7, "1e25");
    const Impact r = run_impact(rigid, true);
    const Impact r25 = run_impact(stiff, true);
    std::cout << fmt::format("hertz rigid wall e_w = {}: rebound ratio {:.6f}, duration error "
                             "{:+.3e}, max overlap error {:+.3e}\n",
                             e_w, r.restitution, r.duration / tc - 1.0, r.max_overlap / dmax - 1.0);
    EXPECT_NEAR(r.restitution, e_w, 1e-3);
    EXPECT_NEAR(r25.restitution, r.restitution, 1e-9);
    EXPECT_NEAR(r25.max_overlap, r.max_overlap, 1e-9 * r.max_overlap);
    if (e_w == 1.0) {
      EXPECT_NEAR(r.duration, tc, 0.02 * tc);
      EXPECT_NEAR(r.max_overlap, dmax, 0.01 * dmax);
    }
  }
}

TEST(PlasticImpact, IsRefusedWithTheReason) {
  // e = 0: no dashpot whose force never pulls stops a head-on impact (docs/contact.md).
  for (bool hertz : {false, true}) {
    ImpactCase s;
    s.hertz = hertz;
    s.particle = glass_like(0.0);
    s.dt = 1e-7;
    const std::string text = case_text(s, pair_inserts(1.0, 0.01 * kD));
    try {
      Simulation sim(read_case_string(text, "impact.toml"));
      ADD_FAILURE() << "e = 0 accepted (hertz: " << hertz << ")";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("species[0].restitution"), std::string::npos) << what;
      EXPECT_NE(what.find("never pulls"), std::string::npos) << what;
    }
  }
}

} // namespace
} // namespace fluidem
