// The ContactTable's coefficients from the materials, against values worked out by hand from the
// mixing rules of [Zhu07 Table 1] (E* = 1/((1-nu_a^2)/E_a + (1-nu_b^2)/E_b), Mindlin's
// 1/G* = (2-nu_a)/G_a + (2-nu_b)/G_b, k_t = 8 G* sqrt(R* delta) [Chang08 eq. 2.16]; Di Renzo &
// Di Maio 2004), a rigid wall (the particle's own compliance alone), infinite friction, and the
// refusals: e = 0 (no dashpot whose force never pulls reaches it, docs/contact.md) and
// contact.stiffness_ratio with Hertz (k_t follows from the materials). Exact to round-off:
// relative 1e-14.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>

#include "../../common/contact_case.hpp"
#include "contact/contact_table.hpp"
#include "contact/kernels/normal_damping.hpp"
#include "contact/kernels/tangential_force.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {
namespace {

constexpr double kTol = 1e-14;

CaseSpec two_species(const std::string& normal) {
  CaseSpec s;
  s.domain.lo = {0.0, 0.0, 0.0};
  s.domain.hi = {0.1, 0.1, 0.1};
  s.species.push_back(test::glass_species_spec("glass"));
  s.species.push_back(test::glass_species_spec("steel"));
  s.contact.normal.name = normal;
  if (normal == "linear" || normal == "walton_braun")
    s.contact.normal.coefficients["stiffness"] = 1000.0;
  return s;
}

TEST(ContactTable, MindlinShearStiffnessMixesGivenShearModuli) {
  CaseSpec s = two_species("hertz");
  MaterialSpec& a = s.species[0].material;
  MaterialSpec& b = s.species[1].material;
  // glass: E = 6e10, G = 2.5e10 (nu = E/(2G) - 1 = 0.2); steel: E = 2e11, nu = 0.3 (G = 2e11/2.6).
  a.youngs_modulus = 6e10, a.shear_modulus = 2.5e10, a.poisson_ratio = 0.2;
  b.youngs_modulus = 2e11, b.poisson_ratio = 0.3;
  const ContactTable t(s);
  const double ga = 2.5e10, gb = 2e11 / 2.6;
  const double g_star = 1.0 / ((2.0 - 0.2) / ga + (2.0 - 0.3) / gb);
  const double e_star = 1.0 / ((1.0 - 0.04) / 6e10 + (1.0 - 0.09) / 2e11);
  EXPECT_NEAR(t.pair(0, 1).kt, 8.0 * g_star, kTol * 8.0 * g_star);
  EXPECT_NEAR(t.pair(1, 0).kt, 8.0 * g_star, kTol * 8.0 * g_star);
  EXPECT_NEAR(t.pair(0, 1).e_star, e_star, kTol * e_star);
  EXPECT_NEAR(t.pair(0, 1).kn, 4.0 / 3.0 * e_star, kTol * e_star);
  // Like materials: G* = G/(2 (2 - nu)).
  EXPECT_NEAR(t.pair(0, 0).kt, 8.0 * ga / 3.6, kTol * 8.0 * ga);
}

TEST(ContactTable, RigidWallLeavesTheParticlesOwnStiffness) {
  CaseSpec s = two_species("hertz");
  MaterialSpec& p = s.species[0].material;
  p.youngs_modulus = 6e10, p.poisson_ratio = 0.2;
  for (auto& w : s.domain.wall_material) w.youngs_modulus = std::numeric_limits<double>::infinity();
  s.domain.wall_material[2].youngs_modulus = 1e25; // the old work-around, for comparison
  const ContactTable t(s);
  const double e_star = 6e10 / (1.0 - 0.04), g = 6e10 / 2.4;
  for (int f : {0, 4}) {
    EXPECT_EQ(t.wall(0, f).e_star, e_star) << f;
    EXPECT_NEAR(t.wall(0, f).kt, 8.0 * g / (2.0 - 0.2), kTol * 8.0 * g) << f;
  }
  EXPECT_NEAR(t.wall(0, 2).e_star, e_star, 1e-14 * e_star + 6e10 * 6e10 / 1e25);
}

TEST(ContactTable, InfiniteFrictionNeverSlidesAndVanishesWithoutLoad) {
  CaseSpec s = two_species("linear");
  s.species[0].material.friction = std::numeric_limits<double>::infinity();
  for (auto& w : s.domain.wall_material) w.friction = std::numeric_limits<double>::infinity();
  const ContactTable t(s);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(t.pair(0, 1).mu, inf); // the mean of inf and 0.4
  EXPECT_EQ(t.pair(1, 1).mu, 0.4);
  EXPECT_EQ(t.wall(1, 4).mu, inf);
  // A huge tangential force sticks under any load; without load there is no friction (and no
  // NaN from inf * 0).
  Vec3 delta{1.0, 0.0, 0.0};
  const auto stuck =
      kernels::tangential_spring(delta, {0.0, 0.0, 0.0}, 1e12, 0.0, t.pair(0, 1).mu, 1e-300, 1e-6);
  EXPECT_FALSE(stuck.sliding);
  EXPECT_EQ(stuck.force.x, -1e12);
  Vec3 delta0{1.0, 0.0, 0.0};
  const auto unloaded =
      kernels::tangential_spring(delta0, {0.0, 0.0, 0.0}, 1e12, 0.0, t.pair(0, 1).mu, 0.0, 1e-6);
  EXPECT_EQ(unloaded.force.x, 0.0);
  EXPECT_EQ(delta0.x, 0.0);
}

TEST(ContactTable, NormalDampingIsCalibratedForTheFlooredForce) {
  for (const std::string m : {"linear", "hertz"}) {
    CaseSpec s = two_species(m);
    s.species[0].material.restitution = 0.3;
    s.species[1].material.restitution = 0.7;
    s.domain.wall_material[4].restitution = 0.9;
    const ContactTable t(s);
    const double scale = m == "linear" ? 2.0 : std::sqrt(5.0);
    EXPECT_EQ(t.pair(0, 1).normal_damping, scale * kernels::floored_damping_ratio(0.5));
    EXPECT_EQ(t.wall(0, 4).normal_damping, scale * kernels::floored_damping_ratio(0.9));
  }
}

TEST(ContactTable, RefusesFullyPlasticContactsWithTheReason) {
  for (const std::string m : {"linear", "hertz"}) {
    CaseSpec s = two_species(m);
    s.species[1].material.restitution = 0.0;
    s.species[0].material.restitution = 0.0;
    try {
      const ContactTable t(s);
      ADD_FAILURE() << "e = 0 accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("species[0].restitution"), std::string::npos) << what;
      EXPECT_NE(what.find("never pulls"), std::string::npos) << what;
      EXPECT_NE(what.find("hard_sphere"), std::string::npos) << what;
    }
    // A wall of e = 0 too; but not on a face that has no contacts (periodic axis).
    CaseSpec w = two_species(m);
    w.domain.wall_material[0].restitution = 0.0;
    EXPECT_THROW(ContactTable{w}, InputError);
    w.domain.periodic[0] = true;
    const ContactTable ok(w);
    EXPECT_EQ(std::memcmp(&ok.wall(0, 0), &ok.wall(0, 2), sizeof(PairParams)), 0);
  }
}

// Walton & Braun [Zhu07 Table 1]: kn = k1 (the stiffness key), normal_damping = k1/k2 = e^2 of
// the pair's mixed e (the arithmetic mean, as for the other models), k_t = stiffness_ratio k1
// ("auto": the linear model's [Deen07 eq. 43]); the duration pi/2 sqrt(m*/k1) (1 + e).
TEST(ContactTable, WaltonBraunUnloadsWithK1OverESquared) {
  CaseSpec s = two_species("walton_braun");
  s.species[0].material.restitution = 0.3;
  s.species[1].material.restitution = 0.7;
  s.domain.wall_material[4].restitution = 0.9;
  const ContactTable t(s);
  EXPECT_EQ(t.pair(0, 1).kn, 1000.0);
  EXPECT_NEAR(t.pair(0, 1).normal_damping, 0.25, kTol);
  EXPECT_NEAR(t.wall(0, 4).normal_damping, 0.81, kTol);
  const double pi2 = std::numbers::pi * std::numbers::pi, le = std::log(0.5);
  // beta0 = 0 (the default tangential restitution): ln beta0 taken as 0
  EXPECT_NEAR(t.pair(0, 1).kt, 1000.0 * 2.0 / 7.0 * pi2 / (pi2 + le * le), kTol * 1000.0);
  s.contact.normal.coefficients["stiffness_ratio"] = 0.5;
  EXPECT_EQ(ContactTable(s).pair(0, 1).kt, 500.0);
  // The pair of glass beads (m* = m/2): the loading and the unloading half-periods.
  const double ma = sphere_mass(0.5 * s.species[0].diameter, s.species[0].density);
  const double mb = sphere_mass(0.5 * s.species[1].diameter, s.species[1].density);
  int rows = 0;
  for (const auto& row : t.durations())
    if (row.species_a == 0 && row.species_b == 1 && row.face < 0) {
      const double m_eff = ma * mb / (ma + mb);
      EXPECT_NEAR(row.duration, 0.5 * std::numbers::pi * std::sqrt(m_eff / 1000.0) * 1.5,
                  1e-12 * row.duration);
      ++rows;
    }
  EXPECT_EQ(rows, 1);
}

// Mindlin-Deresiewicz [Zhu07 Table 1]: slip_factor = E*/(4 G*) of the pair, which is
// (2 - nu)/(2 (1 - nu)) for like materials and for a rigid wall; infinite friction refused.
TEST(ContactTable, MindlinDeresiewiczSlipFactorMixesTheMaterials) {
  CaseSpec s = two_species("hertz");
  s.contact.tangential.name = "mindlin_deresiewicz";
  MaterialSpec& a = s.species[0].material;
  MaterialSpec& b = s.species[1].material;
  a.youngs_modulus = 6e10, a.poisson_ratio = 0.2;
  b.youngs_modulus = 2e11, b.poisson_ratio = 0.3;
  for (auto& w : s.domain.wall_material) w.youngs_modulus = std::numeric_limits<double>::infinity();
  const ContactTable t(s);
  EXPECT_NEAR(t.pair(0, 0).slip_factor, 1.8 / 1.6, kTol);
  EXPECT_NEAR(t.pair(1, 1).slip_factor, 1.7 / 1.4, kTol);
  EXPECT_NEAR(t.wall(0, 4).slip_factor, 1.8 / 1.6, kTol); // rigid wall: the particle's own
  const double inv_e = 0.96 / 6e10 + 0.91 / 2e11;
  const double inv_g = 1.8 * 2.4 / 6e10 + 1.7 * 2.6 / 2e11;
  EXPECT_NEAR(t.pair(0, 1).slip_factor, inv_g / (4.0 * inv_e), kTol);
  s.species[1].material.friction = std::numeric_limits<double>::infinity();
  s.species[0].material.friction = std::numeric_limits<double>::infinity();
  try {
    const ContactTable inf(s);
    ADD_FAILURE() << "friction = inf accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mindlin_deresiewicz"), std::string::npos) << e.what();
  }
}

TEST(ContactTable, RefusesAStiffnessRatioWithHertz) {
  CaseSpec s = two_species("hertz");
  s.contact.normal.coefficients["stiffness_ratio"] = 0.5;
  EXPECT_THROW(ContactTable{s}, InputError);
  s.contact.normal.name = "linear";
  s.contact.normal.coefficients["stiffness"] = 1000.0;
  const ContactTable t(s);
  EXPECT_EQ(t.pair(0, 1).kt, 500.0);
  EXPECT_EQ(t.wall(0, 4).kt, 500.0);
}

// JKR contacts pull at negative overlaps, where mindlin_deresiewicz's slip distance (mu delta_n
// ...) would be negative: the pair of models is refused, naming contact.tangential.
TEST(ContactTable, RefusesMindlinDeresiewiczWithJkr) {
  CaseSpec s = two_species("jkr");
  s.contact.normal.coefficients["adhesion_energy"] = 0.1;
  s.contact.tangential.name = "mindlin_deresiewicz";
  try {
    const ContactTable t(s);
    ADD_FAILURE() << "jkr with mindlin_deresiewicz accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("contact.tangential: \"mindlin_deresiewicz\" cannot "
                                         "follow normal = \"jkr\""),
              std::string::npos)
        << e.what();
  }
  s.contact.tangential.name = "history";
  EXPECT_NO_THROW(ContactTable{s});
}

} // namespace
} // namespace fluidem
