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
#include "../../common/jittered_bed.hpp"
#include "contact/contact_forces.hpp"

namespace fluidem {
namespace {

using test::jittered_bed;
using test::jittered_bed_spec;
constexpr double kD = test::kJitteredD;

struct Result {
  std::vector<double> acc, history, wall_history;
  ContactStats stats;
};

Result run(int layers, int species, bool spread, const std::string& normal) {
  const CaseSpec spec = jittered_bed_spec(species, normal);
  const ContactTable table(spec);
  const ParticleStore p = jittered_bed(layers, species, spread);
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
