// The JKR adhesive normal contact (normal = "jkr") [Zhu07 2.2; Johnson, Kendall & Roberts 1971;
// Thornton & Yin 1991] in the contact loop and through the whole Simulation.
//
// 1. Quasi-static pull-off (contact loop, prescribed positions): a pair of 3 mm glass spheres
//    (E* = E/(2 (1 - nu^2)), R* = r/2) and a sphere on the floor (R* = r, the wall of the same
//    material), pushed to delta = 2 delta_c and pulled apart in steps of ~delta_c/4000, the
//    neighbour list rebuilt before every call with a skin of two steps (so the attached pair in
//    tension is in the list through the list's reach, ContactTable::attached_reach). Against the
//    closed forms of JKR (Johnson 1985, 5.5; derived in docs/contact.md):
//      * no contact in tension before the first touch (at -delta_c/2);
//      * at the first touch the force jumps to -8/9 F_c (within 1%: the touch is at
//        delta = delta_c/4000, not 0);
//      * the largest tensile force F_c = 3/2 pi w R* within 1% (measured ~1e-7);
//      * the break at delta = -delta_c, delta_c = 3/4 (pi^2 w^2 R*/E*^2)^{1/3}, within one
//        step's travel (the last attached overlap above -delta_c, the first free one within
//        delta_c/4000 below it);
//      * the elastic energy is the potential of the branch: its change over the path equals
//        the trapezoidal integral of the force within 1e-4 of U(-delta_c) (the trapezoid's error
//        near the break, where F ~ sqrt(delta + delta_c)); the breaking call books the branch's
//        potential at the break, pi w a_f^2 (3/5 + 2/5 16^{-2/3}) (tools/jkr_reference.py checks
//        this closed form against mpmath.quad), into spring_loss within 1e-12.
// 2. Impact (Simulation, a 2 mm sphere onto the floor, no gravity): with no dashpot the only
//    loss is the break's, U_b = U(-delta_c), so the sphere sticks below the sticking speed
//    v_s = sqrt(2 U_b/m*) (tools/jkr_reference.py: v_s = 5.4874e-3 m/s for this case, from
//    mpmath.quad along the branch) and separates above it with v_out^2 = v^2 - v_s^2. Checked:
//    it stays attached at 0.95 v_s, separates at 1.05 v_s (the 5% on the threshold) and at
//    2 v_s, there with v_out within 1% of sqrt(v^2 - v_s^2) and the dissipated energy within 1%
//    of U_b; e_kin + e_el + e_dsp stays the initial kinetic energy within 1% of it at every
//    step (velocity Verlet; the force jumps at the touch).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "../../common/contact_case.hpp"
#include "analysis/energies.hpp"
#include "contact/contact_forces.hpp"
#include "contact/kernels/normal_force.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kW = 0.05;                                  // J/m^2
constexpr double kEStar = 1e7 / (2.0 * (1.0 - 0.25 * 0.25)); // glass on glass (or the wall)
constexpr double kWallEStar = kEStar;                        // walls: E = 1e7, nu = 0.25
constexpr double kL = 0.03;                                  // box edge

double detach(double r_eff, double e_star) {
  return 0.75 * std::cbrt(kPi * kPi * kW * kW * r_eff / (e_star * e_star));
}

struct PullOff {
  bool wall;
};

class JkrPullOff : public ::testing::TestWithParam<PullOff> {};

TEST_P(JkrPullOff, BreaksAtMinusDeltaCAfterThePullOffForce) {
  const bool wall = GetParam().wall;
  CaseSpec spec;
  spec.simulation.dimension = 3;
  spec.domain.lo = {0.0, 0.0, 0.0};
  spec.domain.hi = {kL, kL, kL};
  spec.species.push_back(test::glass_species_spec("glass"));
  spec.contact.normal.name = "jkr";
  spec.contact.normal.coefficients["adhesion_energy"] = kW;
  const ContactTable table(spec);
  const double r = 0.5 * spec.species[0].diameter;
  const double r_eff = wall ? r : 0.5 * r;
  const double e_star = wall ? kWallEStar : kEStar;
  const double dc = detach(r_eff, e_star), fc = 1.5 * kPi * kW * r_eff;
  ASSERT_GE(table.attached_reach(r), dc);
  // Particle 0 stays; the overlap is set by particle 1's position (pair) or 0's height (wall).
  ParticleStore p;
  const double c = 0.5 * kL;
  if (wall) {
    p.add({c, c, r}, {0.0, 0.0, 0.0}, r, 2500.0, 0, 0);
  } else {
    p.add({c, c, c}, {0.0, 0.0, 0.0}, r, 2500.0, 0, 0);
    p.add({c + 2.0 * r, c, c}, {0.0, 0.0, 0.0}, r, 2500.0, 0, 1);
  }
  auto set_overlap = [&](double delta) {
    if (wall)
      p.z[0] = r - delta;
    else
      p.x[1] = c + 2.0 * r - delta;
  };
  // The skin: two steps' travel (a run's list holds what moved less than its skin since the
  // build: an attached pair that breaks in a step is still listed, and books its break).
  const double step = dc / 4000.37; // (not a divisor of 3 delta_c: no overlap at -delta_c exactly)
  NeighbourList nl(test::box_of(spec), 2.0 * step, contact_history_width(table),
                   table.attached_reach(r));
  ContactScratch nc;
  // The force pushing the pair apart, N (on particle 0: along -x for the pair, +z on the floor).
  auto call = [&](double delta, double& force) {
    set_overlap(delta);
    nl.build(p);
    const ContactStats st = compute_contact_forces(p, nl, table, 1e-6, nc);
    force = wall ? nc.acc[2] : -nc.acc[0];
    return st;
  };
  double f = 0.0;
  EXPECT_EQ(call(-0.5 * dc, f).n_contacts, 0u) << "attached before touching";
  EXPECT_EQ(f, 0.0);
  ContactStats st = call(step, f);
  ASSERT_EQ(st.n_contacts, 1u);
  EXPECT_NEAR(f, -8.0 / 9.0 * fc, 0.01 * fc) << "the force at the first touch";
  double delta = step;
  for (; delta < 2.0 * dc; delta += step) call(delta, f); // compress
  const double u_start = call(delta, f).elastic_energy;
  double f_prev = f, work = 0.0, largest_tension = 0.0, last_attached = delta, u_last = u_start;
  bool broke = false;
  double break_loss = 0.0;
  for (int k = 0; k < 1000000 && !broke; ++k) {
    const double next = delta - step;
    st = call(next, f);
    if (st.n_contacts == 0) {
      broke = true;
      break_loss = st.spring_losses;
      delta = next;
      break;
    }
    work += 0.5 * (f + f_prev) * (next - delta);
    largest_tension = std::max(largest_tension, -f);
    f_prev = f, delta = next, last_attached = next, u_last = st.elastic_energy;
  }
  ASSERT_TRUE(broke);
  const double p_f = r_eff * std::sqrt(2.0 * kPi * kW / e_star); // a_f^{3/2}
  const double a_f2 = std::cbrt(p_f * p_f * p_f * p_f);
  const double u_break = kPi * kW * a_f2 * (0.6 + 0.4 / std::cbrt(256.0));
  std::cout << fmt::format("jkr pull-off {}: F_max/F_c - 1 = {:+.3e}, break between {:.6f} and "
                           "{:.6f} delta_c (step {:.1e} delta_c), energy change vs work {:+.3e} "
                           "of U_b, break loss/U_b - 1 = {:+.3e}\n",
                           wall ? "wall" : "pair", largest_tension / fc - 1.0, last_attached / dc,
                           delta / dc, step / dc, (u_last - u_start - work) / u_break,
                           break_loss / u_break - 1.0);
  EXPECT_NEAR(largest_tension, fc, 0.01 * fc);
  EXPECT_GT(last_attached, -dc);
  EXPECT_LE(delta, -dc);
  EXPECT_GT(delta, -dc - step);
  EXPECT_NEAR(u_last - u_start, work, 1e-4 * u_break);
  EXPECT_NEAR(break_loss, u_break, 1e-12 * u_break);
  EXPECT_NEAR(
      break_loss,
      kernels::jkr_break_energy(4.0 / 3.0 * e_star, std::sqrt(2.0 * kPi * kW / e_star), r_eff),
      1e-14 * u_break);
}

INSTANTIATE_TEST_SUITE_P(Contacts, JkrPullOff, ::testing::Values(PullOff{false}, PullOff{true}),
                         [](const auto& param_info) {
                           return param_info.param.wall ? "wall" : "pair";
                         });

// --- impact ----------------------------------------------------------------------------------

constexpr double kImpactR = 1e-3, kRho = 2500.0;
constexpr double kStickingSpeed = 5.4873982477596081e-3; // tools/jkr_reference.py
const double kMass = 4.0 / 3.0 * kPi * kImpactR * kImpactR * kImpactR * kRho;

std::string impact_case(double v, double dt) {
  const double gap = 1e-6, z = kImpactR + gap, c = 0.5 * kL;
  return fmt::format(
      "[simulation]\ndimension = 3\nend_time = 1.0\ntime_step = {:.17g}\n"
      "gravity = [0.0, 0.0, 0.0]\n\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [{:.17g}, {:.17g}, "
      "{:.17g}]\n\n[walls]\nrestitution = 0.9\nfriction = 0.3\n\n[[species]]\nname = \"s\"\n"
      "diameter = {:.17g}\ndensity = {:.17g}\nrestitution = 0.9\nfriction = 0.3\n\n"
      "[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\n"
      "region = {{ lo = [{:.17g}, {:.17g}, {:.17g}], hi = [{:.17g}, {:.17g}, {:.17g}] }}\n"
      "velocity = [0.0, 0.0, {:.17g}]\n\n[contact]\nnormal = \"jkr\"\nadhesion_energy = {}\n",
      dt, kL, kL, kL, 2.0 * kImpactR, kRho, c - kImpactR, c - kImpactR, z - kImpactR, c + kImpactR,
      c + kImpactR, z + kImpactR, -v, kW);
}

double total_energy(const Simulation& sim) {
  const Energies e = sim.energies();
  return e.kinetic + e.rotational + sim.contact_stats().elastic_energy + sim.dissipated_energy();
}

struct ImpactResult {
  bool separated;
  double v_out, dissipated, worst;
};

ImpactResult impact(double v) {
  constexpr double kDt = 2e-7;
  Simulation sim(read_case_string(impact_case(v, kDt), "jkr.toml"));
  const auto& p = sim.particles();
  EXPECT_EQ(p.size(), 1u);
  const double e0 = total_energy(sim);
  double worst = 0.0;
  bool touched = false, separated = false;
  for (long step = 1; step <= 40000 && !separated; ++step) {
    sim.advance(1);
    worst = std::max(worst, std::abs(total_energy(sim) - e0) / e0);
    if (sim.contact_stats().n_contacts > 0)
      touched = true;
    else if (touched)
      separated = true;
  }
  EXPECT_TRUE(touched);
  return {separated, p.vz[0], sim.dissipated_energy(), worst};
}

TEST(JkrImpact, SticksBelowTheStickingSpeedAndSeparatesAbove) {
  const double ub = 0.5 * kMass * kStickingSpeed * kStickingSpeed;
  const ImpactResult slow = impact(0.95 * kStickingSpeed);
  const ImpactResult just = impact(1.05 * kStickingSpeed);
  const double v_fast = 2.0 * kStickingSpeed;
  const ImpactResult fast = impact(v_fast);
  const double expected = std::sqrt(v_fast * v_fast - kStickingSpeed * kStickingSpeed);
  std::cout << fmt::format("jkr impact: 0.95 v_s separated {} (energy worst {:.2e}); 1.05 v_s "
                           "separated {} v_out/v_s {:.4f} (energy worst {:.2e}); 2 v_s v_out/"
                           "expected - 1 = {:+.3e}, dissipated/U_b - 1 = {:+.3e}, energy worst "
                           "{:.2e}\n",
                           slow.separated, slow.worst, just.separated, just.v_out / kStickingSpeed,
                           just.worst, fast.v_out / expected - 1.0, fast.dissipated / ub - 1.0,
                           fast.worst);
  EXPECT_FALSE(slow.separated);
  EXPECT_TRUE(just.separated);
  EXPECT_TRUE(fast.separated);
  EXPECT_NEAR(fast.v_out, expected, 0.01 * expected);
  EXPECT_NEAR(fast.dissipated, ub, 0.01 * ub);
  EXPECT_LT(slow.worst, 0.01);
  EXPECT_LT(just.worst, 0.01);
  EXPECT_LT(fast.worst, 0.01);
}

} // namespace
} // namespace fluidem
