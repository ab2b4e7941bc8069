// The contact loop's batch kernel reads what all of a batch's contacts have alike once for all
// lanes (contact_forces.cpp, Uniformity): the contact parameters when there is one species
// (walls: one material), and also the particles' radius and mass when every particle has the
// same (a monodisperse bed: the batch's radius and mass columns are then not filled), or each
// contact's own values otherwise. The three paths must give the same bits for the same inputs:
// the forces, torques and their non-conservative parts on every particle, the statistics and the
// contact history after three calls (the later ones read the history the earlier ones left),
// compared between
//   * one species, equal particles (Particles) and the same particles as two species of one
//     material (PerContact);
//   * one species, radii spread by +-1% (Params) and the same as two species (PerContact),
// with Hertz and linear springs, tangential history and rolling springs (and Walton & Braun's
// spring with the Mindlin-Deresiewicz tangential force), in a closed box (wall
// contacts) with more than 4096 particles (the threaded slab loop) and with fewer (one batch
// through all slabs). A reference computed independently of the loop is not needed here: the
// loop's forces are checked against recomputation in contact_record_test.cpp; this test pins
// that the fast paths are the general path.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "../../common/contact_case.hpp"
#include "contact/contact_forces.hpp"

namespace fluidem {
namespace {

constexpr double kD = 0.003;
constexpr double kL = 0.06; // box edge along x and y
constexpr double kH = 0.06; // box height

CaseSpec make_spec(int species, const std::string& normal) {
  CaseSpec s;
  s.simulation.dimension = 3;
  s.domain.lo = {0.0, 0.0, 0.0};
  s.domain.hi = {kL, kL, kH};
  for (int k = 0; k < species; ++k) // d = kD
    s.species.push_back(test::glass_species_spec(k == 0 ? "glass" : "glass_b"));
  s.contact.normal.name = normal;
  if (normal == "jkr")
    s.contact.normal.coefficients["adhesion_energy"] = 0.2;
  else if (normal != "hertz")
    s.contact.normal.coefficients["stiffness"] = 2000.0;
  // Walton & Braun's spring (history of its own) with the Mindlin-Deresiewicz tangential force.
  s.contact.tangential.name = normal == "walton_braun" ? "mindlin_deresiewicz" : "history";
  s.contact.rolling.name = "spring_dashpot";
  return s;
}

/// A jittered lattice of `layers` layers, spacing 0.97 d, random velocities and spins, the
/// first layer on the floor and the outer columns against the side walls. Species alternate
/// between 0 and species - 1 by particle; radii are d/2 or spread by +-1% (`spread`).
ParticleStore make_particles(int layers, int species, bool spread) {
  ParticleStore p;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double a = 0.97 * kD;
  const int nxy = static_cast<int>((kL - kD) / a) + 1;
  std::int64_t id = 0;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < nxy; ++j)
      for (int i = 0; i < nxy; ++i) {
        const Vec3 x{0.49 * kD + i * a + 0.02 * kD * u(rng), 0.49 * kD + j * a + 0.02 * kD * u(rng),
                     0.49 * kD + k * a + 0.02 * kD * u(rng)};
        const Vec3 v{0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)};
        const double r = 0.5 * kD * (spread ? 1.0 + 0.01 * u(rng) : 1.0);
        p.add(x, v, r, 2500.0, static_cast<int>(id % species), id);
        ++id;
        const std::size_t n = p.size() - 1;
        p.wx[n] = 50.0 * u(rng), p.wy[n] = 50.0 * u(rng), p.wz[n] = 50.0 * u(rng);
      }
  return p;
}

struct Result {
  std::vector<double> acc, history, wall_history;
  ContactStats stats;
};

Result run(int layers, int species, bool spread, const std::string& normal) {
  const CaseSpec spec = make_spec(species, normal);
  const ContactTable table(spec);
  const ParticleStore p = make_particles(layers, species, spread);
  NeighbourList nl(test::box_of(spec), 0.1 * kD, contact_history_width(table));
  nl.build(p);
  ContactScratch nc;
  Result r;
  for (int call = 0; call < 3; ++call) r.stats = compute_contact_forces(p, nl, table, 1e-5, nc);
  r.acc = nc.acc;
  r.history = nl.history;
  r.wall_history = nl.wall_history;
  return r;
}

void expect_bitwise_equal(const Result& a, const Result& b) {
  ASSERT_EQ(a.acc.size(), b.acc.size());
  for (std::size_t k = 0; k < a.acc.size(); ++k)
    ASSERT_EQ(std::memcmp(&a.acc[k], &b.acc[k], sizeof(double)), 0)
        << "particle " << k / ContactScratch::kAcc << " sum " << k % ContactScratch::kAcc << ": "
        << a.acc[k] << " vs " << b.acc[k];
  EXPECT_EQ(a.history, b.history);
  EXPECT_EQ(a.wall_history, b.wall_history);
  EXPECT_EQ(a.stats.n_contacts, b.stats.n_contacts);
  EXPECT_EQ(a.stats.elastic_energy, b.stats.elastic_energy);
  EXPECT_EQ(a.stats.spring_losses, b.stats.spring_losses);
  EXPECT_EQ(a.stats.max_force2, b.stats.max_force2);
  EXPECT_EQ(a.stats.max_overlap_ratio, b.stats.max_overlap_ratio);
}

struct Case {
  const char* name;
  int layers; // 1: 400 particles (one batch through all slabs); 13: 5200 (threaded slab loop)
  const char* normal;
};

class UniformBatches : public ::testing::TestWithParam<Case> {};

TEST_P(UniformBatches, EqualParticlesGiveThePerContactBits) {
  const Case& c = GetParam();
  const Result one = run(c.layers, 1, false, c.normal);
  ASSERT_GT(one.stats.n_contacts, 0);
  expect_bitwise_equal(one, run(c.layers, 2, false, c.normal));
}

TEST_P(UniformBatches, SpreadRadiiGiveThePerContactBits) {
  const Case& c = GetParam();
  const Result one = run(c.layers, 1, true, c.normal);
  ASSERT_GT(one.stats.n_contacts, 0);
  expect_bitwise_equal(one, run(c.layers, 2, true, c.normal));
}

INSTANTIATE_TEST_SUITE_P(Beds, UniformBatches,
                         ::testing::Values(Case{"hertz_small", 1, "hertz"},
                                           Case{"hertz_threaded", 13, "hertz"},
                                           Case{"linear_small", 1, "linear"},
                                           Case{"walton_braun_small", 1, "walton_braun"},
                                           Case{"walton_braun_threaded", 13, "walton_braun"},
                                           Case{"jkr_small", 1, "jkr"},
                                           Case{"jkr_threaded", 13, "jkr"}),
                         [](const auto& tp) { return std::string(tp.param.name); });

} // namespace
} // namespace fluidem
