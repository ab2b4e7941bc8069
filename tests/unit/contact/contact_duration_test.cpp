// The contact durations of `fluidem check` and of the time step (ContactTable) against their
// analytic values, for a head-on impact:
//   * Hertz, elastic (e = 1): t_c = 2 (delta_max / v) int_0^1 dx / sqrt(1 - x^(5/2)) with
//     delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5) [Johnson, Contact Mechanics (1985),
//     eq. 11.24: t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5)]; the integral is (2/5) B(2/5, 1/2),
//     here from std::tgamma, independent of the table's integration of the impact ODE
//     (contact/kernels/normal_damping.hpp). v is the impact speed: twice the characteristic
//     velocity for two particles meeting head-on (each at that speed), the characteristic velocity
//     against a wall at rest (issue 32, item 24: the pairs were given one particle's speed, 2^(1/5)
//     = 15% too long). Tolerance 1e-9 relative (measured: 5.5e-13; the table's RK4 takes some 20000
//     steps through the impact).
//   * linear: the force pulse of the impact whose force never pulls
//   (tests/common/linear_impact.hpp,
//     from the explicit solution), independent of the speed. Tolerance 1e-9 relative.
// m* = m/2 and R* = d/4 for a pair of one species, m and d/2 against a wall.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "../../common/contact_case.hpp"
#include "../../common/linear_impact.hpp"
#include "contact/contact_table.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {
namespace {

constexpr double kV = 1.3; // characteristic velocity, m/s

CaseSpec two_species(const std::string& normal, double e) {
  CaseSpec s;
  s.simulation.dimension = 3;
  s.domain.lo = {0.0, 0.0, 0.0};
  s.domain.hi = {0.1, 0.1, 0.1};
  s.domain.periodic = {true, true, false}; // walls z_lo and z_hi only
  for (const char* name : {"glass", "steel"}) {
    SpeciesSpec sp = test::glass_species_spec(name);
    sp.material.restitution = e;
    s.species.push_back(sp);
  }
  s.species[1].diameter = 0.005;
  s.species[1].density = 7800.0;
  s.species[1].material.youngs_modulus = 2e8;
  s.species[1].material.poisson_ratio = 0.3;
  for (auto& w : s.domain.wall_material) {
    w.youngs_modulus = 5e7;
    w.poisson_ratio = 0.2;
    w.restitution = e;
  }
  s.contact.normal.name = normal;
  if (normal == "linear") s.contact.normal.coefficients["stiffness"] = 800.0;
  s.contact.characteristic_velocity = kV;
  return s;
}

double duration_of(const ContactTable& t, const std::string& pair) {
  for (const auto& row : t.durations())
    if (row.pair == pair) return row.duration;
  ADD_FAILURE() << "no contact duration for " << pair;
  return 0.0;
}

/// Elastic Hertz impact of reduced mass m and radius r, moduli E* at speed v [Johnson 1985].
double hertz_elastic_duration(double m, double r, double e_star, double v) {
  const double integral =
      0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9); // (2/5) B(2/5, 1/2)
  const double delta_max = std::pow(15.0 * m * v * v / (16.0 * e_star * std::sqrt(r)), 0.4);
  return 2.0 * delta_max / v * integral;
}

double e_part(const MaterialSpec& m) {
  return (1.0 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus;
}

TEST(ContactDuration, HertzHeadOnPairsMeetAtTwiceTheParticleSpeed) {
  const CaseSpec s = two_species("hertz", 1.0);
  const ContactTable t(s);
  ASSERT_EQ(t.characteristic_velocity(), kV);
  const auto& g = s.species[0];
  const auto& st = s.species[1];
  const double mg = sphere_mass(0.5 * g.diameter, g.density);
  const double ms = sphere_mass(0.5 * st.diameter, st.density);
  // The Johnson constant itself: 2 (15/16)^(2/5) (2/5) B(2/5, 1/2) = 2.868.
  EXPECT_NEAR(hertz_elastic_duration(1.0, 1.0, 1.0, 1.0), 2.868, 5e-4);

  struct Expected {
    const char* pair;
    double m, r, e_star, v;
  };
  const Expected cases[] = {
      {"glass-glass", 0.5 * mg, 0.25 * g.diameter, 0.5 / e_part(g.material), 2.0 * kV},
      {"glass-steel", mg * ms / (mg + ms),
       0.5 * g.diameter * 0.5 * st.diameter / (0.5 * g.diameter + 0.5 * st.diameter),
       1.0 / (e_part(g.material) + e_part(st.material)), 2.0 * kV},
      {"steel-steel", 0.5 * ms, 0.25 * st.diameter, 0.5 / e_part(st.material), 2.0 * kV},
      {"glass-wall z_lo", mg, 0.5 * g.diameter,
       1.0 / (e_part(g.material) + e_part(s.domain.wall_material[4])), kV},
      {"steel-wall z_hi", ms, 0.5 * st.diameter,
       1.0 / (e_part(st.material) + e_part(s.domain.wall_material[5])), kV},
  };
  for (const Expected& c : cases) {
    SCOPED_TRACE(c.pair);
    const double want = hertz_elastic_duration(c.m, c.r, c.e_star, c.v);
    EXPECT_NEAR(duration_of(t, c.pair) / want, 1.0, 1e-9) << want;
  }
  // Walls on z only: no x or y rows.
  EXPECT_EQ(t.durations().size(), 3u + 2u * 2u);
  EXPECT_EQ(t.shortest_contact_duration(),
            std::min({duration_of(t, "glass-glass"), duration_of(t, "glass-steel"),
                      duration_of(t, "steel-steel"), duration_of(t, "glass-wall z_lo"),
                      duration_of(t, "glass-wall z_hi"), duration_of(t, "steel-wall z_lo"),
                      duration_of(t, "steel-wall z_hi")}));
}

TEST(ContactDuration, LinearIsTheForcePulse) {
  const double e = 0.7;
  const CaseSpec s = two_species("linear", e);
  const ContactTable t(s);
  const auto& g = s.species[0];
  const double mg = sphere_mass(0.5 * g.diameter, g.density);
  const double pair = test::linear_impact_for_restitution(0.5 * mg, 800.0, e).duration;
  const double wall = test::linear_impact_for_restitution(mg, 800.0, e).duration;
  EXPECT_NEAR(duration_of(t, "glass-glass") / pair, 1.0, 1e-9);
  EXPECT_NEAR(duration_of(t, "glass-wall z_lo") / wall, 1.0, 1e-9);
}

// A species without particles has no durations and no say in the time step (issue 32, item 9:
// 4000 unused species cost a row and a Hertz impact integration per pair).
TEST(ContactDuration, SpeciesWithoutParticlesHaveNoRows) {
  const CaseSpec s = two_species("hertz", 0.9);
  const ContactTable all(s);
  const ContactTable glass_only(s, {true, false});
  EXPECT_EQ(glass_only.durations().size(), 1u + 2u);
  for (const auto& row : glass_only.durations())
    EXPECT_EQ(row.pair.find("steel"), std::string::npos);
  EXPECT_EQ(glass_only.shortest_contact_duration(),
            std::min(duration_of(all, "glass-glass"), duration_of(all, "glass-wall z_lo")));
  EXPECT_FALSE(glass_only.has_particles(1));
  // Its wall coefficients are kept (the contact loop compares all species' walls).
  EXPECT_EQ(glass_only.wall(1, 4).kn, all.wall(1, 4).kn);
}

} // namespace
} // namespace fluidem
