// Non-contact pair kernels of src/noncontact/kernels/ against independent references and their
// exact properties.
//
// 1. Reference data: tests/models/noncontact/{van_der_waals,coulomb,liquid_bridge}.toml, computed
//    by tools/noncontact_reference.py with mpmath (40 digits) from the published formulas, the
//    potentials by mpmath.quad of the force (not the C++'s closed forms or Gauss rule). One
//    parametrised test per case; force, potential, stiffness, bridge energy and rupture distance
//    within relative 1e-9 (the file's `tolerance`; absolute 1e-300 where the expected value is
//    0). The bridge potential and energy come from the kernel's 32-point Gauss-Legendre rule,
//    whose error against mpmath.quad is < 2e-11 over 1e-5 <= V* <= 0.1, 0 <= theta <= 0.7 (the
//    script prints it): 1e-9 holds for them too.
// 2. Properties that hold exactly (or to the stated difference error): -dU/dgap = F by central
//    difference, continuity at the cut-offs, the constant vdW force inside h0, the plain Coulomb
//    limit, Derjaguin radius identities, the liquid conservation of the distribution rule, the
//    lubrication force's 1/S law and its floor, and Willett's contact force against the
//    small-bridge limit 2 pi R gamma (within the fit's accuracy only: see the test).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>
#include <limits>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>
#include <toml++/toml.h>
#include <vector>

#include "noncontact/kernels/coulomb.hpp"
#include "noncontact/kernels/liquid_bridge.hpp"
#include "noncontact/kernels/van_der_waals.hpp"

namespace fluidem::kernels {
namespace {

namespace fs = std::filesystem;

constexpr double kInf = std::numeric_limits<double>::infinity();

fs::path model_file(const std::string& name) {
  return fs::path(FLUIDEM_SOURCE_DIR) / "tests" / "models" / "noncontact" / (name + ".toml");
}

double number(const toml::table& t, const std::string& key, const std::string& where) {
  const toml::node* n = t.get(key);
  if (n == nullptr) throw std::runtime_error(where + ": missing '" + key + "'");
  const auto v = n->value<double>();
  if (!v) throw std::runtime_error(where + ": '" + key + "' is not a number");
  return *v;
}

/// A case: named inputs and named expected values, as read from a reference file.
struct RefCase {
  std::string file;
  std::string name;
  toml::table in;
  toml::table expected;
  double tolerance = 1e-9;
};

void PrintTo(const RefCase& c, std::ostream* os) {
  *os << c.file << ":" << c.name;
}

std::vector<RefCase> load(const std::string& kernel, const std::string& array = "case") {
  std::vector<RefCase> out;
  const toml::table root = toml::parse_file(model_file(kernel).string());
  const double tol = root["tolerance"].value_or(1e-9);
  const toml::array* cases = root[array].as_array();
  if (cases == nullptr) throw std::runtime_error(kernel + ": no [[" + array + "]]");
  for (const toml::node& n : *cases) {
    RefCase c;
    c.file = kernel + ".toml";
    c.in = *n.as_table();
    c.name = c.in["name"].value_or(std::string("?"));
    if (const toml::table* e = c.in["expected"].as_table()) c.expected = *e;
    c.tolerance = tol;
    out.push_back(c);
  }
  return out;
}

/// Empty if got matches expected within the relative tolerance (absolute 1e-300 at 0).
std::string compare(const std::string& what, double got, double expected, double tol) {
  const bool ok = expected == 0.0 ? std::fabs(got) <= 1e-300
                                  : std::fabs(got - expected) <= tol * std::fabs(expected);
  if (ok) return {};
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s: got %.17g, expected %.17g (rel. diff %.3g)\n", what.c_str(),
                got, expected, expected == 0.0 ? got : (got - expected) / expected);
  return buf;
}

std::string check_expected(const RefCase& c, const std::string& key, double got) {
  if (!c.expected.contains(key)) return {};
  return compare(key, got, number(c.expected, key, c.file + ":" + c.name), c.tolerance);
}

// ---------------------------------------------------------------------------------------------
// 1. Reference files
// ---------------------------------------------------------------------------------------------

class VanDerWaalsReference : public ::testing::TestWithParam<RefCase> {};

TEST_P(VanDerWaalsReference, ForcePotentialStiffness) {
  const RefCase& c = GetParam();
  const std::string w = c.file + ":" + c.name;
  const PairForce p =
      van_der_waals(number(c.in, "hamaker", w), number(c.in, "r_eff", w), number(c.in, "h0", w),
                    number(c.in, "h_c", w), number(c.in, "gap", w));
  std::string err = check_expected(c, "force", p.force);
  err += check_expected(c, "potential", p.potential);
  err += check_expected(c, "stiffness", p.stiffness);
  EXPECT_TRUE(err.empty()) << w << "\n" << err;
}

INSTANTIATE_TEST_SUITE_P(File, VanDerWaalsReference, ::testing::ValuesIn(load("van_der_waals")));

class CoulombReference : public ::testing::TestWithParam<RefCase> {};

TEST_P(CoulombReference, ForcePotentialStiffness) {
  const RefCase& c = GetParam();
  const std::string w = c.file + ":" + c.name;
  const double k =
      coulomb_constant(number(c.in, "q_i", w), number(c.in, "q_j", w), number(c.in, "eps_r", w));
  const double r = number(c.in, "r", w), r_c = number(c.in, "r_c", w);
  const PairForce p = coulomb_shifted(k, r, r_c);
  std::string err = check_expected(c, "k", k);
  err += check_expected(c, "force", p.force);
  err += check_expected(c, "potential", p.potential);
  err += check_expected(c, "stiffness", p.stiffness);
  // Without cut-off effects (r_c >> r): the plain Coulomb force within the tolerance; the
  // potential differs from k/r by the shift -2k/r_c + k r/r_c^2, i.e. relative 2 r/r_c.
  if (c.expected.contains("plain_force")) {
    err += compare("plain_force", p.force, number(c.expected, "plain_force", w), c.tolerance);
    err += compare("plain_potential", p.potential, number(c.expected, "plain_potential", w),
                   2.0 * r / r_c * (1.0 + 1e-6) + c.tolerance);
  }
  EXPECT_TRUE(err.empty()) << w << "\n" << err;
}

INSTANTIATE_TEST_SUITE_P(File, CoulombReference, ::testing::ValuesIn(load("coulomb")));

class LiquidBridgeReference : public ::testing::TestWithParam<RefCase> {};

TEST_P(LiquidBridgeReference, ForcePotentialStiffnessEnergy) {
  const RefCase& c = GetParam();
  const std::string w = c.file + ":" + c.name;
  const double r_i = number(c.in, "r_i", w), r_j = number(c.in, "r_j", w);
  const double v = number(c.in, "volume", w), theta = number(c.in, "theta", w);
  const double gamma = number(c.in, "gamma", w), gap = number(c.in, "gap", w);
  const PairForce p = liquid_bridge_capillary(r_i, r_j, v, theta, gamma, gap);
  std::string err = check_expected(c, "force", p.force);
  err += check_expected(c, "force", liquid_bridge_capillary_force(r_i, r_j, v, theta, gamma, gap));
  err += check_expected(c, "potential", p.potential);
  err += check_expected(c, "stiffness", p.stiffness);
  err += check_expected(c, "energy", liquid_bridge_energy(r_i, r_j, v, theta, gamma));
  err += check_expected(c, "rupture_distance", liquid_bridge_rupture_distance(v, theta));
  EXPECT_TRUE(err.empty()) << w << "\n" << err;
}

INSTANTIATE_TEST_SUITE_P(File, LiquidBridgeReference, ::testing::ValuesIn(load("liquid_bridge")));

class LiquidBridgeViscousReference : public ::testing::TestWithParam<RefCase> {};

TEST_P(LiquidBridgeViscousReference, Force) {
  const RefCase& c = GetParam();
  const std::string w = c.file + ":" + c.name;
  const double f = liquid_bridge_viscous(number(c.in, "mu_l", w), number(c.in, "r_i", w),
                                         number(c.in, "r_j", w), number(c.in, "v_n", w),
                                         number(c.in, "gap", w), number(c.in, "s_min", w));
  const std::string err = compare("force", f, number(c.in, "force", w), c.tolerance);
  EXPECT_TRUE(err.empty()) << w << "\n" << err;
}

INSTANTIATE_TEST_SUITE_P(File, LiquidBridgeViscousReference,
                         ::testing::ValuesIn(load("liquid_bridge", "viscous")));

class LiquidBridgeVolumeReference : public ::testing::TestWithParam<RefCase> {};

TEST_P(LiquidBridgeVolumeReference, Volume) {
  const RefCase& c = GetParam();
  const std::string w = c.file + ":" + c.name;
  const double v = liquid_bridge_volume(
      number(c.in, "v_i", w), static_cast<int>(c.in["n_i"].value_or(int64_t{0})),
      number(c.in, "v_j", w), static_cast<int>(c.in["n_j"].value_or(int64_t{0})));
  const std::string err = compare("volume", v, number(c.in, "volume", w), c.tolerance);
  EXPECT_TRUE(err.empty()) << w << "\n" << err;
}

INSTANTIATE_TEST_SUITE_P(File, LiquidBridgeVolumeReference,
                         ::testing::ValuesIn(load("liquid_bridge", "volume")));

// ---------------------------------------------------------------------------------------------
// 2. Properties
// ---------------------------------------------------------------------------------------------

// van der Waals: A = 6.5e-20 J, R* = 0.25 um, h0 = 0.165 nm, h_c = 10 nm.
constexpr double kA = 6.5e-20, kReff = 2.5e-7, kH0 = 1.65e-10, kHc = 1e-8;

TEST(VanDerWaalsProperties, ConstantForceInsideH0) {
  const double f0 = van_der_waals(kA, kReff, kH0, kHc, kH0).force;
  EXPECT_DOUBLE_EQ(f0, -kA * kReff / (6.0 * kH0 * kH0));
  for (const double gap : {-1e-9, -1e-10, 0.0, 5e-11, 1.6e-10}) {
    EXPECT_EQ(van_der_waals(kA, kReff, kH0, kHc, gap).force, f0) << gap;
    EXPECT_EQ(van_der_waals(kA, kReff, kH0, kHc, gap).stiffness, 0.0) << gap;
  }
}

TEST(VanDerWaalsProperties, PotentialDerivativeIsMinusForce) {
  // central difference, step 1e-5 of the gap: truncation error ~ (step/gap)^2 ~ 1e-10, rounding
  // ~ 1e-16 |U| / (1e-5 gap |F|); checked within 1e-6
  for (const double gap : {-5e-10, 5e-11, 3e-10, 1e-9, 4e-9, 9e-9}) {
    const double h = 1e-5 * std::max(std::fabs(gap), kH0);
    const double du = (van_der_waals(kA, kReff, kH0, kHc, gap + h).potential -
                       van_der_waals(kA, kReff, kH0, kHc, gap - h).potential) /
                      (2.0 * h);
    const double f = van_der_waals(kA, kReff, kH0, kHc, gap).force;
    EXPECT_NEAR(-du, f, 1e-6 * std::fabs(f)) << gap;
  }
}

TEST(VanDerWaalsProperties, PotentialContinuousAtCutOffAndH0) {
  const double u_in = van_der_waals(kA, kReff, kH0, kHc, kHc * (1.0 - 1e-12)).potential;
  const double u_scale = kA * kReff / (6.0 * kHc);
  EXPECT_LT(std::fabs(u_in), 1e-10 * u_scale);
  EXPECT_EQ(van_der_waals(kA, kReff, kH0, kHc, kHc).potential, 0.0);
  EXPECT_EQ(van_der_waals(kA, kReff, kH0, kHc, kHc).force, 0.0);
  // at h0 both branches of the potential meet
  const double below = van_der_waals(kA, kReff, kH0, kHc, kH0 * (1.0 - 1e-12)).potential;
  const double at = van_der_waals(kA, kReff, kH0, kHc, kH0).potential;
  EXPECT_NEAR(below, at, 1e-10 * std::fabs(at));
}

// Coulomb: k of two 1 fC charges in air, cut-off 1 mm.
TEST(CoulombProperties, ForceAndPotentialVanishContinuouslyAtCutOff) {
  const double k = coulomb_constant(1e-15, 2e-15, 1.0), r_c = 1e-3;
  const PairForce in = coulomb_shifted(k, r_c * (1.0 - 1e-6), r_c);
  const double f_scale = k / (r_c * r_c), u_scale = k / r_c;
  EXPECT_LT(std::fabs(in.force), 3e-6 * f_scale);
  EXPECT_LT(std::fabs(in.potential), 1e-11 * u_scale);
  const PairForce at = coulomb_shifted(k, r_c, r_c);
  EXPECT_EQ(at.force, 0.0);
  EXPECT_EQ(at.potential, 0.0);
}

TEST(CoulombProperties, PotentialDerivativeIsMinusForce) {
  const double k = coulomb_constant(1e-15, -3e-15, 2.0), r_c = 1e-3;
  for (const double r : {1e-5, 1e-4, 5e-4, 9e-4}) {
    const double h = 1e-5 * r;
    const double du =
        (coulomb_shifted(k, r + h, r_c).potential - coulomb_shifted(k, r - h, r_c).potential) /
        (2.0 * h);
    const double f = coulomb_shifted(k, r, r_c).force;
    EXPECT_NEAR(-du, f, 1e-6 * std::fabs(f)) << r;
  }
}

TEST(CoulombProperties, SignsAndStiffness) {
  const double rep = coulomb_constant(1e-15, 1e-15, 1.0);
  const double att = coulomb_constant(1e-15, -1e-15, 1.0);
  EXPECT_GT(coulomb_shifted(rep, 1e-4, 1e-2).force, 0.0);
  EXPECT_LT(coulomb_shifted(att, 1e-4, 1e-2).force, 0.0);
  const double r = 1e-4, h = 1e-6 * r;
  const double df =
      (coulomb_shifted(rep, r + h, 1e-2).force - coulomb_shifted(rep, r - h, 1e-2).force) /
      (2.0 * h);
  EXPECT_NEAR(coulomb_shifted(rep, r, 1e-2).stiffness, std::fabs(df), 1e-6 * std::fabs(df));
}

// Liquid bridge: water on 0.5 mm spheres.
constexpr double kR = 5e-4, kGamma = 0.0728;

TEST(LiquidBridgeProperties, PotentialDerivativeIsMinusForceAndStiffness) {
  for (const double vstar : {1e-5, 1e-3, 0.05}) {
    for (const double theta : {0.0, 0.5}) {
      const double v = vstar * kR * kR * kR;
      const double s_c = liquid_bridge_rupture_distance(v, theta);
      for (const double frac : {0.01, 0.1, 0.4, 0.8}) {
        const double s = frac * s_c, h = 1e-4 * s_c;
        const auto at = [&](double g) {
          return liquid_bridge_capillary(kR, 2 * kR, v, theta, kGamma, g);
        };
        const double du = (at(s + h).potential - at(s - h).potential) / (2.0 * h);
        const double df = (at(s + h).force - at(s - h).force) / (2.0 * h);
        const PairForce p = at(s);
        // difference truncation ~ (h/s)^2 |F''/F|, Gauss error 1e-11 |U| / h: within 1e-5
        EXPECT_NEAR(-du, p.force, 1e-5 * std::fabs(p.force)) << vstar << " " << theta << " " << s;
        EXPECT_NEAR(p.stiffness, std::fabs(df), 1e-4 * std::fabs(df) + 1e-9 * std::fabs(p.force))
            << vstar << " " << theta << " " << s;
      }
    }
  }
}

TEST(LiquidBridgeProperties, RuptureAndTouching) {
  const double v = 1e-3 * kR * kR * kR, theta = 0.3;
  const double s_c = liquid_bridge_rupture_distance(v, theta);
  EXPECT_DOUBLE_EQ(s_c, (1.0 + 0.15) * std::cbrt(v));
  // ruptured beyond S_c; the potential goes continuously to 0 there (the force does not)
  const PairForce out = liquid_bridge_capillary(kR, kR, v, theta, kGamma, s_c);
  EXPECT_EQ(out.force, 0.0);
  EXPECT_EQ(out.potential, 0.0);
  const PairForce in = liquid_bridge_capillary(kR, kR, v, theta, kGamma, s_c * (1.0 - 1e-9));
  EXPECT_LT(in.force, 0.0);
  const double e = liquid_bridge_energy(kR, kR, v, theta, kGamma);
  EXPECT_LT(std::fabs(in.potential), 1e-8 * e);
  // at contact the potential is minus the bridge energy (the same rule)
  const PairForce c0 = liquid_bridge_capillary(kR, kR, v, theta, kGamma, 0.0);
  EXPECT_NEAR(c0.potential, -e, 1e-14 * e);
  // overlapping: the contact force, the potential continued linearly
  for (const double gap : {-1e-9, -1e-6}) {
    const PairForce p = liquid_bridge_capillary(kR, kR, v, theta, kGamma, gap);
    EXPECT_EQ(p.force, c0.force);
    EXPECT_NEAR(p.potential, c0.potential + std::fabs(c0.force) * gap, 1e-14 * e);
    EXPECT_EQ(p.stiffness, 0.0);
  }
  // continuous at contact from the open side
  const PairForce eps = liquid_bridge_capillary(kR, kR, v, theta, kGamma, 1e-9 * s_c);
  EXPECT_NEAR(eps.force, c0.force, 1e-9 * std::fabs(c0.force));
}

TEST(LiquidBridgeProperties, DerjaguinRadius) {
  EXPECT_DOUBLE_EQ(willett_radius(kR, kR), kR);
  EXPECT_DOUBLE_EQ(willett_radius(kR, kInf), 2.0 * kR);
  EXPECT_DOUBLE_EQ(willett_radius(kR, 3.0 * kR), 1.5 * kR);
  EXPECT_DOUBLE_EQ(lubrication_radius(kR, kR), 0.5 * kR);
  EXPECT_DOUBLE_EQ(lubrication_radius(kR, kInf), kR);
  const double v = 1e-3 * kR * kR * kR;
  for (const double gap : {0.0, 1e-6, 1e-5}) {
    // a sphere on a wall is the equal-sphere pair of radius 2 R_i; the pair is symmetric
    const PairForce wall = liquid_bridge_capillary(kR, kInf, v, 0.2, kGamma, gap);
    const PairForce twice = liquid_bridge_capillary(2 * kR, 2 * kR, v, 0.2, kGamma, gap);
    EXPECT_EQ(wall.force, twice.force);
    EXPECT_EQ(wall.potential, twice.potential);
    const PairForce ij = liquid_bridge_capillary(kR, 3 * kR, v, 0.2, kGamma, gap);
    const PairForce ji = liquid_bridge_capillary(3 * kR, kR, v, 0.2, kGamma, gap);
    EXPECT_EQ(ij.force, ji.force);
    const PairForce eq = liquid_bridge_capillary(1.5 * kR, 1.5 * kR, v, 0.2, kGamma, gap);
    EXPECT_NEAR(ij.force, eq.force, 1e-15 * std::fabs(eq.force));
  }
}

TEST(LiquidBridgeProperties, SmallBridgeContactForceNearTwoPiRGamma) {
  // Not exact: Willett's fit at contact, 2 pi R gamma exp(f1), is within its 3% of the small-
  // bridge limit 2 pi R gamma cos(theta) (Fisher's toroidal bridge as beta -> 0) only where the
  // fit holds: for theta = 0 the ratio is 1.0023 at V* = 1e-5, 0.951 at 1e-4, 0.919 at 1e-3 (the
  // finite bridge is weaker: toroidal 0.976, 0.957, 0.926), and exp(f1) grows unphysically
  // below V* ~ 1e-6 (1.116 at 1e-6). So: 1e-5 within 1%, and monotonic in V* above it.
  const double f_limit = 2.0 * std::numbers::pi * kR * kGamma;
  const auto f0 = [&](double vstar) {
    return -liquid_bridge_capillary(kR, kR, vstar * kR * kR * kR, 0.0, kGamma, 0.0).force;
  };
  EXPECT_NEAR(f0(1e-5) / f_limit, 1.0, 0.01);
  double prev = f0(1e-5);
  for (const double vstar : {3e-5, 1e-4, 1e-3, 1e-2, 0.1}) {
    EXPECT_LT(f0(vstar), prev) << vstar;
    prev = f0(vstar);
  }
  // the wall (R = 2 R_i): twice the pair's force
  const double wall = -liquid_bridge_capillary(kR, kInf, 8e-5 * kR * kR * kR, 0.0, kGamma, 0).force;
  EXPECT_NEAR(wall / (2.0 * f_limit), 1.0, 0.01);
}

TEST(LiquidBridgeProperties, ViscousForce) {
  const double mu = 1e-3, s_min = 1e-7;
  const double f1 = liquid_bridge_viscous(mu, kR, kR, 0.01, 1e-5, s_min);
  EXPECT_DOUBLE_EQ(f1, -6.0 * std::numbers::pi * mu * 0.25 * kR * kR * 0.01 / 1e-5);
  EXPECT_LT(f1, 0.0); // separating: pulled together
  EXPECT_GT(liquid_bridge_viscous(mu, kR, kR, -0.01, 1e-5, s_min), 0.0);
  EXPECT_DOUBLE_EQ(liquid_bridge_viscous(mu, kR, kR, 0.01, 2e-5, s_min), 0.5 * f1);
  EXPECT_EQ(liquid_bridge_viscous(mu, kR, kR, 0.01, 1e-9, s_min),
            liquid_bridge_viscous(mu, kR, kR, 0.01, s_min, s_min));
  EXPECT_EQ(liquid_bridge_viscous(mu, kR, kR, 0.01, -1e-6, s_min),
            liquid_bridge_viscous(mu, kR, kR, 0.01, s_min, s_min));
}

TEST(LiquidBridgeProperties, DistributionConservesLiquid) {
  // particle 0 (liquid 6e-12) with bridges to 1 (3e-12, 2 bridges), 2 (dry), a wall
  const double v0 = 6e-12, v1 = 3e-12;
  const double b01 = liquid_bridge_volume(v0, 3, v1, 2);
  const double b02 = liquid_bridge_volume(v0, 3, 0.0, 1);
  const double b0w = liquid_bridge_volume(v0, 3, 0.0, 0);
  EXPECT_DOUBLE_EQ(b02, 2e-12);
  EXPECT_DOUBLE_EQ(b0w, 2e-12);
  EXPECT_DOUBLE_EQ(b01, 2e-12 + 1.5e-12);
  // particle 0's shares add up to its liquid
  EXPECT_DOUBLE_EQ((b01 - v1 / 2) + b02 + b0w, v0);
  EXPECT_EQ(liquid_bridge_volume(v0, 3, v1, 2), liquid_bridge_volume(v1, 2, v0, 3));
}

} // namespace
} // namespace fluidem::kernels
