// Head-on impacts with the Walton & Braun hysteretic normal spring [Zhu07 Table 1; Walton & Braun
// 1986, J. Rheol. 30:949] through the whole Simulation (case text -> insertion -> neighbour list
// -> contact loop with the normal model's history -> velocity Verlet), against the analytic
// impact: loading on k1 from 0 to delta_max = v sqrt(m*/k1) (half a period of sqrt(k1/m*)),
// unloading on k2 = k1/e^2 until the force vanishes at delta0 = delta_max (1 - e^2) (half a period
// of sqrt(k2/m*)), so the rebound speed is v sqrt(k1/k2) = e v at every impact speed, and the
// force pulse lasts pi/2 sqrt(m*/k1) (1 + e). Energy: the loading work 1/2 k1 delta_max^2 splits
// into the recoverable 1/2 k2 (delta - delta0)^2 (the contact's elastic energy) and the part the
// unloading line does not give back (spring_loss, in the dissipated energy), so
// e_kin + e_rot + e_el + e_dsp stays the initial kinetic energy.
//
// Tolerances: |e_measured - e| <= 1e-3 (dt = t_c/397.3; measured below 1e-4), the force pulse
// within 1% (counted in whole steps), the energy balance within 1e-3 of the initial energy at
// every step (velocity Verlet on a piecewise linear force; measured ~1e-5), and the dissipated
// energy at the end (1 - e^2) of the initial kinetic energy within 1e-3 of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <ostream>
#include <string>

#include <fmt/format.h>

#include "analysis/energies.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kD = 0.004; // m
constexpr double kR = 0.5 * kD;
constexpr double kRho = 2700.0;
constexpr double kBox = 0.04;
constexpr double kC = 0.5 * kBox;
constexpr double kK1 = 1.0e5; // N/m: the overlap at 5 m/s is 3% of a diameter (pair)
const double kMass = 4.0 / 3.0 * kPi * kR * kR * kR * kRho;

std::string one_particle(double x, double y, double z, double vx, double vz) {
  return fmt::format("[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\n"
                     "region = {{ lo = [{:.17g}, {:.17g}, {:.17g}], hi = [{:.17g}, {:.17g}, "
                     "{:.17g}] }}\nvelocity = [{:.17g}, 0.0, {:.17g}]\n",
                     x - kR, y - kR, z - kR, x + kR, y + kR, z + kR, vx, vz);
}

struct WbImpact {
  bool wall;
  double v; // impact speed, m/s
  double e; // the restitution of the contact (the particle's for a pair, the wall's)
};
void PrintTo(const WbImpact& w, std::ostream* os) {
  *os << (w.wall ? "wall" : "pair") << "_v" << w.v << "_e" << w.e;
}

double pulse(double m_eff, double e) {
  return 0.5 * kPi * std::sqrt(m_eff / kK1) * (1.0 + e);
}

std::string case_text(const WbImpact& w, double dt) {
  const double e_particle = w.wall ? 0.3 : w.e, e_wall = w.wall ? w.e : 0.3;
  std::string t = fmt::format("[simulation]\ndimension = 3\nend_time = 1.0\ntime_step = {:.17g}\n"
                              "gravity = [0.0, 0.0, 0.0]\n\n[domain]\nlo = [0.0, 0.0, 0.0]\n"
                              "hi = [{:.17g}, {:.17g}, {:.17g}]\n\n[walls]\nrestitution = {}\n"
                              "friction = 0.3\n\n[[species]]\nname = \"s\"\ndiameter = {:.17g}\n"
                              "density = {:.17g}\nrestitution = {}\nfriction = 0.3\n\n",
                              dt, kBox, kBox, kBox, e_wall, kD, kRho, e_particle);
  // 1% of a diameter apart, approaching head-on (pair along x, wall: down onto z_lo)
  const double gap = 0.01 * kD;
  if (w.wall) {
    t += one_particle(kC, kC, kR + gap, 0.0, -w.v);
  } else {
    const double off = kR + 0.5 * gap;
    t += one_particle(kC - off, kC, kC, 0.5 * w.v, 0.0) +
         one_particle(kC + off, kC, kC, -0.5 * w.v, 0.0);
  }
  t += fmt::format("\n[contact]\nnormal = \"walton_braun\"\nstiffness = {:.17g}\n", kK1);
  return t;
}

double total_energy(const Simulation& sim) {
  const Energies e = sim.energies();
  return e.kinetic + e.rotational + sim.contact_stats().elastic_energy + sim.dissipated_energy();
}

class WaltonBraunImpact : public ::testing::TestWithParam<WbImpact> {};

TEST_P(WaltonBraunImpact, ReboundsWithSqrtK1OverK2AndTheEnergyBalanceCloses) {
  const WbImpact w = GetParam();
  const double m_eff = w.wall ? kMass : 0.5 * kMass;
  const double tc = pulse(m_eff, w.e);
  Simulation sim(read_case_string(case_text(w, tc / 397.3), "walton_braun.toml"));
  const auto& p = sim.particles();
  ASSERT_EQ(p.size(), w.wall ? 1u : 2u);
  auto approach = [&] { return w.wall ? -p.vz[0] : p.vx[0] - p.vx[1]; };
  const double v_in = approach();
  const double e0 = total_energy(sim);
  double worst = 0.0;
  long first = -1, pushing = 0;
  bool ended = false;
  for (long step = 1; step <= 100000 && !ended; ++step) {
    sim.advance(1);
    worst = std::max(worst, std::abs(total_energy(sim) - e0) / e0);
    if (sim.contact_stats().n_contacts > 0) {
      if (first < 0) first = step;
      if (sim.contact_stats().max_force2 > 0.0) ++pushing;
    } else if (first >= 0) {
      ended = true;
    }
  }
  ASSERT_TRUE(ended) << "the contact never ended";
  const double e = -approach() / v_in;
  const double t_pulse = static_cast<double>(pushing) * sim.time_step();
  const double dissipated = sim.dissipated_energy() / e0;
  std::cout << fmt::format("walton_braun {} v = {} m/s e = {}: rebound ratio {:.7f} (error "
                           "{:+.3e}), pulse error {:+.3e}, energy balance worst {:.3e}, "
                           "dissipated {:.6f} of (1 - e^2) = {:.6f}\n",
                           w.wall ? "wall" : "pair", w.v, w.e, e, e - w.e, t_pulse / tc - 1.0,
                           worst, dissipated, 1.0 - w.e * w.e);
  EXPECT_NEAR(e, w.e, 1e-3);
  EXPECT_NEAR(t_pulse, tc, 0.01 * tc);
  EXPECT_LT(worst, 1e-3);
  EXPECT_NEAR(dissipated, 1.0 - w.e * w.e, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Speeds, WaltonBraunImpact,
                         ::testing::Values(WbImpact{false, 0.1, 0.8}, WbImpact{false, 1.0, 0.8},
                                           WbImpact{false, 5.0, 0.8}, WbImpact{false, 1.0, 0.3},
                                           WbImpact{false, 1.0, 1.0}, WbImpact{true, 0.1, 0.6},
                                           WbImpact{true, 1.0, 0.6}, WbImpact{true, 5.0, 0.6},
                                           WbImpact{true, 1.0, 0.95}),
                         [](const ::testing::TestParamInfo<WbImpact>& param_info) {
                           std::string s = ::testing::PrintToString(param_info.param);
                           for (char& ch : s)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return s;
                         });

TEST(WaltonBraunImpact, PlasticLimitIsRefused) {
  // e = 0 would need k2 = inf: refused as for the other soft-sphere models.
  WbImpact w{false, 1.0, 0.0};
  EXPECT_THROW(Simulation(read_case_string(case_text(w, 1e-7), "walton_braun.toml")), InputError);
}

} // namespace
} // namespace fluidem
