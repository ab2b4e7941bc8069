// Coarse-grained parcels [Chang08 §2.2.3] through the whole Simulation (integrate/coarse_graining,
// docs/coarse-graining.md):
// (1) A parcel of W real particles has their mass, volume and momentum [Chang08 eq. 2.24-2.26]
//     and the diameter W^(1/3) d1 [eq. 2.27] (1e-14 relative: round-off of the sphere volume).
// (2) Head-on binary collisions of two parcels against two real particles (W = 8, 27; linear
//     spring-dashpot and Hertz-Tsuji; the real pair's impact speed): each scaling keeps what
//     docs/coarse-graining.md derives it keeps and changes the rest by the derived factor
//     (s = W^(1/3)): ratio parcel/real of
//                               overlap/diameter   contact duration   restitution
//       chang08, linear              1                  s                 1
//       chang08, Hertz               s^(-1/5)           s^(4/5)           1
//       scale_invariant              1                  s                 1
//       collision_time               1/s                1                 1
//     to 1e-3 (the tolerance). The time step is the same fraction (1/2000) of each
//     pair's own computed contact duration, the crossing times of the gap are interpolated
//     linearly between steps and the largest overlap is the largest of the steps' (errors
//     O((dt/t_c)^2) ~ 1e-6); the dashpots are calibrated on the restitution, which the
//     dimensionless impact equation then fixes [Deen07 eq. 24-26; Chang08 eq. 2.22].
// (3) The resolved case of a coarse-grained run is the user's (species diameter, stiffness), and
//     reads back into the same simulated parcels, bit for bit.
// (4) What has no derived scaling is refused with the key named.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"
#include "io/case_writer.hpp"

namespace fluidem {
namespace {

constexpr double kD = 0.002, kRho = 2500.0, kBox = 0.2, kV = 1.0;

std::string collision_case(bool hertz, double w, const std::string& scaling) {
  // Two particles on the x axis, a gap of 1% of their diameter, approaching at kV.
  const double d2 = kD * std::cbrt(w), r2 = 0.5 * d2, c = 0.5 * kBox, off = r2 + 0.005 * d2;
  auto one = [&](double x, double v) {
    return fmt::format("[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\n"
                       "region = {{ lo = [{0:.17g}, {1:.17g}, {1:.17g}], hi = [{2:.17g}, "
                       "{3:.17g}, {3:.17g}] }}\nvelocity = [{4:.17g}, 0.0, 0.0]\n",
                       x - r2, c - r2, x + r2, c + r2, v);
  };
  std::string t = fmt::format(
      "[simulation]\nend_time = 0.01\ntime_step_fraction = 0.0005\ngravity = [0.0, 0.0, 0.0]\n"
      "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [{0}, {0}, {0}]\n"
      "[[species]]\nname = \"s\"\ndiameter = {1:.17g}\ndensity = {2}\nyoungs_modulus = 1e7\n"
      "restitution = 0.8\nfriction = 0.3\n",
      kBox, kD, kRho);
  t += one(c - off, 0.5 * kV) + one(c + off, -0.5 * kV);
  t += hertz ? "[contact]\nnormal = \"hertz\"\n"
             : "[contact]\nnormal = \"linear\"\nstiffness = 1000.0\n";
  t += fmt::format("characteristic_velocity = {}\n", kV);
  if (w != 1.0)
    t += fmt::format("[coarse_graining]\nratio = {}\ncontact_scaling = \"{}\"\n", w, scaling);
  return t;
}

struct Collision {
  double overlap_ratio = 0.0; // largest overlap / diameter
  double duration = 0.0;      // s, from the gap's closing to its opening (interpolated)
  double restitution = 0.0;   // separation speed / approach speed
};

Collision collide(const std::string& text) {
  Simulation sim(read_case_string(text, "collision.toml"));
  const ParticleStore& p = sim.particles();
  EXPECT_EQ(p.size(), 2u);
  const double d = 2.0 * p.radius[0];
  auto gap = [&] { return std::abs(p.x[1] - p.x[0]) - d; };
  const double v_in = p.vx[0] - p.vx[1];
  const double dt = sim.time_step();
  double g_prev = gap(), t_on = -1.0, t_off = -1.0, max_overlap = 0.0;
  for (long step = 1; step < 200000 && t_off < 0.0; ++step) {
    sim.advance(1);
    const double g = gap(), t = static_cast<double>(step) * dt;
    if (g_prev > 0.0 && g <= 0.0) t_on = t - dt * g / (g - g_prev); // g linear between steps
    if (g_prev <= 0.0 && g > 0.0) t_off = t - dt * g / (g - g_prev);
    max_overlap = std::max(max_overlap, -g);
    g_prev = g;
  }
  EXPECT_GT(t_on, 0.0);
  EXPECT_GT(t_off, t_on);
  Collision c;
  c.overlap_ratio = max_overlap / d;
  c.duration = t_off - t_on;
  c.restitution = (p.vx[1] - p.vx[0]) / v_in;
  return c;
}

struct Expected {
  double overlap_exponent, duration_exponent; // ratio = s^exponent
};

void check_scaling(bool hertz, const std::string& scaling, Expected e) {
  const Collision real = collide(collision_case(hertz, 1.0, scaling));
  for (const double w : {8.0, 27.0}) {
    const double s = std::cbrt(w);
    const Collision cg = collide(collision_case(hertz, w, scaling));
    const double overlap = cg.overlap_ratio / real.overlap_ratio;
    const double duration = cg.duration / real.duration;
    const double e_ratio = cg.restitution / real.restitution;
    std::printf("%s %s W = %g: overlap/d x %.6f (derived %.6f), duration x %.6f (derived %.6f), "
                "restitution %.6f vs %.6f\n",
                hertz ? "hertz" : "linear", scaling.c_str(), w, overlap,
                std::pow(s, e.overlap_exponent), duration, std::pow(s, e.duration_exponent),
                cg.restitution, real.restitution);
    EXPECT_NEAR(overlap / std::pow(s, e.overlap_exponent), 1.0, 1e-3) << "W = " << w;
    EXPECT_NEAR(duration / std::pow(s, e.duration_exponent), 1.0, 1e-3) << "W = " << w;
    EXPECT_NEAR(e_ratio, 1.0, 1e-3) << "W = " << w;
  }
  EXPECT_NEAR(real.restitution, 0.8, 2e-3); // the calibration holds (normal_impact_test: 1e-3)
}

TEST(CoarseGraining, ParcelCarriesTheMassVolumeAndMomentumOfItsRealParticles) {
  for (const double w : {8.0, 27.0, 64.0, 10.0}) {
    Simulation real(read_case_string(collision_case(false, 1.0, "chang08"), "real.toml"));
    Simulation cg(read_case_string(collision_case(false, w, "chang08"), "cg.toml"));
    const ParticleStore &a = real.particles(), &b = cg.particles();
    const double s = std::cbrt(w);
    EXPECT_NEAR(b.radius[0] / (s * a.radius[0]), 1.0, 1e-14);                  // eq. 2.27
    EXPECT_NEAR(b.mass[0] / (w * a.mass[0]), 1.0, 1e-14);                      // eq. 2.24
    const double va = std::pow(a.radius[0], 3), vb = std::pow(b.radius[0], 3); // volume ~ r^3
    EXPECT_NEAR(vb / (w * va), 1.0, 1e-14);                                    // eq. 2.25
    EXPECT_NEAR(b.mass[0] * b.vx[0] / (w * a.mass[0] * a.vx[0]), 1.0, 1e-14);  // momentum
    EXPECT_NEAR(b.mass[0] / vb / (a.mass[0] / va), 1.0, 1e-14);                // eq. 2.26
  }
}

TEST(CoarseGraining, Chang08LinearKeepsOverlapRatioAndRestitution) {
  check_scaling(false, "chang08", {0.0, 1.0});
}
TEST(CoarseGraining, Chang08HertzAsPrintedStiffensTheContact) {
  check_scaling(true, "chang08", {-0.2, 0.8});
}
TEST(CoarseGraining, ScaleInvariantKeepsOverlapRatioAndRestitution) {
  check_scaling(false, "scale_invariant", {0.0, 1.0});
  check_scaling(true, "scale_invariant", {0.0, 1.0});
}
TEST(CoarseGraining, CollisionTimeKeepsTheContactDuration) {
  check_scaling(false, "collision_time", {-1.0, 0.0});
  check_scaling(true, "collision_time", {-1.0, 0.0});
}

TEST(CoarseGraining, ResolvedCaseIsTheUsersAndReadsBackBitwise) {
  const std::string text = collision_case(false, 8.0, "chang08");
  Simulation sim(read_case_string(text, "cg.toml"));
  const CaseSpec resolved = sim.resolved_case();
  EXPECT_EQ(resolved.species[0].diameter, kD);
  EXPECT_EQ(resolved.contact.normal.coefficients.at("stiffness"), 1000.0);
  EXPECT_EQ(sim.spec().species[0].diameter, 2.0 * kD);
  EXPECT_EQ(sim.spec().contact.normal.coefficients.at("stiffness"), 2000.0); // eq. 2.38
  Simulation again(read_case_string(write_case_toml(resolved), "resolved.toml"));
  EXPECT_EQ(again.spec().species[0].diameter, sim.spec().species[0].diameter);
  EXPECT_EQ(again.time_step(), sim.time_step());
  EXPECT_TRUE(again.particles().x == sim.particles().x);
  EXPECT_TRUE(again.particles().mass == sim.particles().mass);
}

TEST(CoarseGraining, WhatHasNoScalingIsRefusedNamingTheKey) {
  const std::string base = collision_case(false, 8.0, "chang08");
  const auto refused = [&](const std::string& extra, const std::string& key) {
    try {
      Simulation sim(read_case_string(base + extra, "cg.toml"));
      ADD_FAILURE() << "accepted: " << extra;
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(key), std::string::npos) << m;
      EXPECT_NE(m.find("coarse_graining.ratio"), std::string::npos) << m;
    }
  };
  refused("[van_der_waals]\nhamaker = 1e-20\nmin_separation = 4e-10\nrange = 1e-4\n",
          "van_der_waals");
  EXPECT_THROW(read_case_string(base + "[coarse_graining.x]\n", "cg.toml"), InputError);
  try {
    read_case_string(collision_case(false, 1.0, "") + "[coarse_graining]\nratio = 0.5\n", "c");
    ADD_FAILURE() << "ratio 0.5 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("coarse_graining.ratio"), std::string::npos);
  }
}

} // namespace
} // namespace fluidem
