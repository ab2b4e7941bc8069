// The rank-independent contact loop (contact/ordered_contacts.hpp) against
//   * the batched half-list loop (contact_forces.hpp), an independent implementation of the
//     same contact laws: per-particle forces, torques and their non-conservative parts agree to
//     1e-12 of the largest sum (the two add a particle's contacts in different orders) over
//     three calls (the later ones read the histories the earlier ones left), and so do the
//     elastic energy and the contact count;
//   * itself, bitwise, when the store is split as between two ranks (each half's own particles
//     first, the other half after them as ghosts, in another order), and with 1 or 2 threads:
//     the property the MPI runs rest on (docs/parallel.md);
//   * Newton's third law, exactly: a pair's two rows give forces of opposite sign, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <omp.h>
#include <random>
#include <vector>

#include "../../common/jittered_bed.hpp"
#include "contact/contact_forces.hpp"
#include "contact/ordered_contacts.hpp"

namespace fluidem {
namespace {

using test::jittered_bed;
using test::jittered_bed_spec;
constexpr double kD = test::kJitteredD;
constexpr double kSkin = 0.1 * kD;
constexpr double kDt = 1e-5;

/// A rank's view of p: the particles `own` first (in p's order), the others behind them as
/// ghosts (in reverse order), and the rows of the own particles built on them.
struct RankView {
  ParticleStore local;
  std::size_t owned = 0;
  ContactTable table;
  OrderedRows rows;
  RankView(const CaseSpec& spec, const ParticleStore& p, const std::vector<bool>& own)
      : table(spec), rows(test::box_of(spec), contact_history_width(table), 0.0) {
    std::vector<std::uint32_t> order;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (own[i]) order.push_back(static_cast<std::uint32_t>(i));
    owned = order.size();
    for (std::size_t i = p.size(); i-- > 0;)
      if (!own[i]) order.push_back(static_cast<std::uint32_t>(i));
    local = p;
    local.permute(order);
    rows.build(local, owned, kSkin, KeptHistory{});
  }
};

/// Per particle id: its twelve sums after `calls` calls of the ordered loop on the particles
/// `own` of p (the others as ghosts behind them, in reverse order).
std::map<std::int64_t, std::vector<double>> ordered_sums(const CaseSpec& spec,
                                                         const ParticleStore& p,
                                                         const std::vector<bool>& own, int calls,
                                                         OrderedContactStats* stats = nullptr) {
  RankView r(spec, p, own);
  OrderedContactSums sums;
  OrderedContactStats st;
  for (int c = 0; c < calls; ++c)
    st = compute_ordered_contact_forces(r.local, r.rows, r.table, kDt, sums);
  if (stats) *stats = st;
  std::map<std::int64_t, std::vector<double>> out;
  for (std::size_t i = 0; i < r.owned; ++i)
    out[r.local.id[i]].assign(sums.acc.begin() + static_cast<std::ptrdiff_t>(12 * i),
                              sums.acc.begin() + static_cast<std::ptrdiff_t>(12 * i + 12));
  return out;
}

/// The batched half-list loop (contact_forces.hpp) on p, three calls (the later ones read the
/// histories the earlier ones left): the last call's stats, its sums in nc, its contacts in
/// `record` (when given).
ContactStats batched_loop(const CaseSpec& spec, const ParticleStore& p, ContactScratch& nc,
                          ContactRecord* record = nullptr) {
  const ContactTable table(spec);
  NeighbourList nl(test::box_of(spec), kSkin, contact_history_width(table));
  nl.build(p);
  ContactStats st;
  for (int c = 0; c < 3; ++c) st = compute_contact_forces(p, nl, table, kDt, nc, record);
  return st;
}

class OrderedContacts : public ::testing::TestWithParam<const char*> {};

TEST_P(OrderedContacts, AgreesWithTheBatchedLoop) {
  const CaseSpec spec = jittered_bed_spec(2, GetParam());
  const ParticleStore p = jittered_bed(2, 2, true);
  ContactScratch nc;
  const ContactStats fast = batched_loop(spec, p, nc);
  OrderedContactStats st;
  const auto ordered = ordered_sums(spec, p, std::vector<bool>(p.size(), true), 3, &st);
  ASSERT_GT(fast.n_contacts, 100);
  EXPECT_EQ(st.contacts, fast.n_contacts);
  double largest = 0.0;
  for (const double v : nc.acc) largest = std::max(largest, std::abs(v));
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int m = 0; m < 12; ++m)
      ASSERT_NEAR(ordered.at(p.id[i])[static_cast<std::size_t>(m)], nc.acc[12 * i + m],
                  1e-12 * largest)
          << "particle " << p.id[i] << " sum " << m;
  EXPECT_EQ(st.max_force2, fast.max_force2); // a maximum: no order
  EXPECT_NEAR(st.max_overlap_ratio, fast.max_overlap_ratio, 1e-15);
}

void expect_same_bits(const std::map<std::int64_t, std::vector<double>>& a,
                      const std::map<std::int64_t, std::vector<double>>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [id, sums] : a)
    ASSERT_EQ(std::memcmp(sums.data(), b.at(id).data(), 12 * sizeof(double)), 0)
        << "particle " << id;
}

TEST_P(OrderedContacts, TwoRanksHalvesGiveTheSameBits) {
  const CaseSpec spec = jittered_bed_spec(2, GetParam());
  const ParticleStore p = jittered_bed(2, 2, true);
  const auto whole = ordered_sums(spec, p, std::vector<bool>(p.size(), true), 3);
  std::vector<bool> left(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) left[i] = p.x[i] < 0.5 * test::kJitteredL;
  std::vector<bool> right(left.size());
  std::transform(left.begin(), left.end(), right.begin(), [](bool b) { return !b; });
  auto halves = ordered_sums(spec, p, left, 3);
  halves.merge(ordered_sums(spec, p, right, 3));
  expect_same_bits(whole, halves);
}

TEST_P(OrderedContacts, ThreadsGiveTheSameBits) {
  // 5200 particles: above the threaded loops' 4096.
  const CaseSpec spec = jittered_bed_spec(2, GetParam());
  const ParticleStore p = jittered_bed(13, 2, true);
  const std::vector<bool> all(p.size(), true);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = ordered_sums(spec, p, all, 3);
  omp_set_num_threads(2);
  const auto two = ordered_sums(spec, p, all, 3);
  omp_set_num_threads(threads);
  expect_same_bits(one, two);
}

/// The contacts the ordered loop records on the particles `own` of p (others as ghosts), at
/// the third call.
std::vector<KeyedContact> ordered_record(const CaseSpec& spec, const ParticleStore& p,
                                         const std::vector<bool>& own) {
  RankView r(spec, p, own);
  OrderedContactSums sums;
  std::vector<KeyedContact> record;
  for (int c = 0; c < 3; ++c)
    compute_ordered_contact_forces(r.local, r.rows, r.table, kDt, sums, c == 2 ? &record : nullptr);
  return record;
}

TEST_P(OrderedContacts, RecordsEachContactOnceAsTheBatchedLoopSeesIt) {
  // The contacts recorded by two "ranks" (halves of the bed, each with the other's particles as
  // ghosts) together against the batched loop's record (contact_forces.hpp, an independent
  // implementation): the same contacts, each once, keyed by ids, with the same overlap, the
  // smaller diameter and the contact point x_i + (r_i - overlap/2) n (from either body: the
  // same point) to round-off, 1e-12 of a diameter, and the same force, normal and rolling
  // torque (on the lower id) to 1e-12 relative.
  const CaseSpec spec = jittered_bed_spec(2, GetParam());
  const ParticleStore p = jittered_bed(2, 2, true);
  ContactScratch nc;
  ContactRecord batched;
  batched.enabled = true;
  batched_loop(spec, p, nc, &batched);
  std::map<std::pair<std::int64_t, std::int64_t>, ContactSample> expected;
  for (const ContactSample& c : batched.samples)
    expected[c.j >= 0 ? std::pair{std::min(c.id_i, c.id_j), std::max(c.id_i, c.id_j)}
                      : std::pair{c.id_i, c.id_j}] = c;
  ASSERT_GT(expected.size(), 100u);
  std::vector<bool> left(p.size()), right(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    left[i] = p.x[i] < 0.5 * test::kJitteredL;
    right[i] = !left[i];
  }
  std::vector<KeyedContact> got = ordered_record(spec, p, left);
  const std::vector<KeyedContact> other = ordered_record(spec, p, right);
  got.insert(got.end(), other.begin(), other.end());
  ASSERT_EQ(got.size(), expected.size()); // each contact once over the two halves
  std::size_t walls = 0;
  for (const KeyedContact& k : got) {
    const auto it = expected.find({k.a, k.b});
    ASSERT_NE(it, expected.end()) << k.a << " " << k.b;
    const ContactSample& c = it->second;
    walls += k.b < 0 ? 1 : 0;
    if (k.b >= 0) {
      EXPECT_LT(k.a, k.b);
    }
    EXPECT_NEAR(k.overlap, c.overlap, 1e-12 * kD);
    const double d = k.b < 0 ? 2.0 * p.radius[static_cast<std::size_t>(c.i)]
                             : 2.0 * std::min(p.radius[static_cast<std::size_t>(c.i)],
                                              p.radius[static_cast<std::size_t>(c.j)]);
    EXPECT_EQ(k.diameter, d);
    EXPECT_NEAR(norm(k.contact_point - c.contact_point), 0.0, 1e-12 * kD) << k.a << " " << k.b;
    // Force, normal and rolling torque on a (the batched loop's are on its i: a or b).
    const double s = c.id_i == k.a ? 1.0 : -1.0;
    EXPECT_NEAR(norm(k.force - c.force * s), 0.0, 1e-12 * norm(c.force)) << k.a << " " << k.b;
    EXPECT_NEAR(norm(k.normal - c.normal * s), 0.0, 1e-14) << k.a << " " << k.b;
    EXPECT_NEAR(norm(k.torque_roll - c.torque_roll * s), 0.0, 1e-12 * norm(c.torque_roll) + 1e-300)
        << k.a << " " << k.b;
  }
  EXPECT_GT(walls, 0u);
}

INSTANTIATE_TEST_SUITE_P(Models, OrderedContacts,
                         ::testing::Values("hertz", "linear", "walton_braun", "jkr"));

TEST(OrderedContactsPair, NewtonsThirdLawHoldsBitwise) {
  // Two glass spheres overlapping by 2% of d, moving and spinning: the two rows evaluate the
  // pair from the lower id's side; the forces are exact opposites, the torques r_i (n x F_t) +-
  // T_roll of each.
  const CaseSpec spec = jittered_bed_spec(1, "hertz");
  ParticleStore p;
  p.add({0.03, 0.03, 0.03}, {0.1, -0.2, 0.05}, 0.5 * kD, 2500.0, 0, 7);
  p.add({0.03 + 0.98 * kD, 0.03 + 0.001 * kD, 0.03}, {-0.3, 0.0, 0.1}, 0.5 * kD, 2500.0, 0, 3);
  p.wx[0] = 20.0, p.wz[1] = -30.0;
  const ContactTable table(spec);
  OrderedRows rows(test::box_of(spec), contact_history_width(table), 0.0);
  rows.build(p, 2, kSkin, KeptHistory{});
  OrderedContactSums sums;
  const OrderedContactStats st = compute_ordered_contact_forces(p, rows, table, kDt, sums);
  EXPECT_EQ(st.contacts, 1);
  EXPECT_EQ(st.deepest_id, 3); // the lower id of the pair
  EXPECT_GT(std::abs(sums.acc[0]), 0.0);
  for (int m : {0, 1, 2, 6, 7, 8})
    EXPECT_EQ(sums.acc[static_cast<std::size_t>(m)], -sums.acc[12 + static_cast<std::size_t>(m)]);
  // The pair's elastic energy is counted once, at the lower id (particle 1 here).
  EXPECT_EQ(sums.elastic[0], 0.0);
  EXPECT_GT(sums.elastic[1], 0.0);
  // The two rows keep the same history (seen from the lower id).
  ASSERT_EQ(rows.history.size(), 2u * static_cast<std::size_t>(rows.history_width()));
  for (int m = 0; m < rows.history_width(); ++m)
    EXPECT_EQ(rows.history[static_cast<std::size_t>(m)],
              rows.history[static_cast<std::size_t>(rows.history_width() + m)]);
}

} // namespace
} // namespace fluidem
