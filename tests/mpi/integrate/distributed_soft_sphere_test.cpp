// The soft-sphere DEM on MPI ranks gives the bits of one rank (docs/parallel.md). Run by ctest
// under mpirun with 1, 2, 3 and 4 ranks (oversubscribed on two cores): a bed of 5200 glass
// spheres (Hertz, tangential history, rolling springs; periodic along x, walls elsewhere)
// released from a jittered lattice with overlaps of up to a few percent of a diameter and random
// velocities (the particles cross the ranks' cut planes, migrate with their histories, and the
// lists are rebuilt several times) runs 300 steps on all ranks, cut into columns, slabs and
// 2 x 2 boxes; its particles (sorted by id: every array of the store, and each particle's
// dissipated and elastic energy) and its totals must equal bit for bit those of the same bed
// stepped by one rank alone (Communicator::self(), on the root) with 2 threads. A control with
// one velocity changed by 1e-12 must differ.
#include <gtest/gtest.h>

#include <cstring>
#include <omp.h>

#include "../../common/jittered_bed.hpp"
#include "integrate/distributed_soft_sphere.hpp"

namespace fluidem {
namespace {

constexpr long kSteps = 300;

CaseSpec bed_spec() {
  CaseSpec s = test::jittered_bed_spec(2, "hertz");
  s.domain.periodic = {true, false, false};
  return s;
}

/// FNV-1a over bytes.
struct Hash {
  std::uint64_t h = 1469598103934665603ull;
  template <class T>
  void add(const std::vector<T>& v) {
    const auto* b = reinterpret_cast<const unsigned char*>(v.data());
    for (std::size_t k = 0; k < v.size() * sizeof(T); ++k) h = (h ^ b[k]) * 1099511628211ull;
  }
};

struct Outcome {
  std::uint64_t hash = 0;
  DistributedSoftSphere::Totals totals;
  long builds = 0;
};

DistributedSoftSphere::Settings settings(std::array<int, 3> grid) {
  const CaseSpec spec = bed_spec();
  DistributedSoftSphere::Settings s;
  s.dt = 1e-5;
  s.skin = 0.1 * test::kJitteredD;
  s.gravity = {0.0, 0.0, -9.81};
  s.cells.cells = {20, 20, 20};
  s.cells.lo = spec.domain.lo;
  s.cells.hi = spec.domain.hi;
  s.cells.periodic = spec.domain.periodic;
  s.process_grid = grid;
  return s;
}

/// The hash of the id-sorted particles and their energies (root), the totals, the builds.
/// Collective.
Outcome outcome(const Communicator& comm, const DistributedSoftSphere& dem) {
  Outcome o;
  o.totals = dem.totals();
  o.builds = dem.builds();
  const DistributedState g = dem.gather();
  if (comm.root()) {
    Hash h;
    g.particles.for_each_array([&](const auto& a) { h.add(a); });
    h.add(g.dissipated);
    h.add(g.elastic);
    o.hash = h.h;
  }
  return o;
}

Outcome run(const Communicator& comm, std::array<int, 3> grid, double nudge = 0.0) {
  const CaseSpec spec = bed_spec();
  ParticleStore all = test::jittered_bed(13, 2, true);
  all.vx[100] += nudge;
  DistributedSoftSphere dem(comm, std::make_unique<ContactTable>(spec), test::box_of(spec),
                            settings(grid), all);
  dem.advance(kSteps);
  return outcome(comm, dem);
}

void expect_same_totals(const DistributedSoftSphere::Totals& a,
                        const DistributedSoftSphere::Totals& b) {
  EXPECT_EQ(std::memcmp(&a.kinetic, &b.kinetic, sizeof(double)), 0);
  EXPECT_EQ(a.rotational, b.rotational);
  EXPECT_EQ(a.potential, b.potential);
  EXPECT_EQ(a.elastic, b.elastic);
  EXPECT_EQ(a.dissipated, b.dissipated);
  EXPECT_EQ(a.contacts, b.contacts);
  EXPECT_EQ(a.particles, b.particles);
  EXPECT_EQ(a.max_overlap_ratio, b.max_overlap_ratio);
}

/// The reference: one rank alone, two threads (the contact loop and the kicks go threaded above
/// 4096 particles), computed once per process on the root.
const Outcome& one_rank() {
  static const Outcome o = [] {
    const int threads = omp_get_max_threads();
    omp_set_num_threads(2);
    Outcome r = run(Communicator::self(), {0, 0, 0});
    omp_set_num_threads(threads);
    return r;
  }();
  return o;
}

void expect_one_rank_bits(std::array<int, 3> grid) {
  const Communicator& world = Communicator::world();
  const Outcome many = run(world, grid);
  if (!world.root()) return;
  const Outcome& one = one_rank();
  EXPECT_GT(one.builds, 2); // the lists were rebuilt (and the particles migrated) on the way
  EXPECT_EQ(many.builds, one.builds);
  EXPECT_EQ(many.hash, one.hash) << "ranks " << world.size();
  expect_same_totals(many.totals, one.totals);
}

TEST(DistributedSoftSphere, ColumnsGiveTheBitsOfOneRank) {
  expect_one_rank_bits({Communicator::world().size(), 1, 1});
}

TEST(DistributedSoftSphere, SlabsGiveTheBitsOfOneRank) {
  expect_one_rank_bits({1, 1, Communicator::world().size()});
}

TEST(DistributedSoftSphere, TwoByTwoGivesTheBitsOfOneRank) {
  if (Communicator::world().size() != 4) GTEST_SKIP() << "2 x 2 boxes need 4 ranks";
  expect_one_rank_bits({2, 2, 1});
}

TEST(DistributedSoftSphere, ChosenGridGivesTheBitsOfOneRank) {
  expect_one_rank_bits({0, 0, 0});
}

TEST(DistributedSoftSphere, StateGatheredHalfwayContinuesOnOneRank) {
  // The state at step 150 (particles, contact sums, energies and the histories keyed by partner
  // id, gathered from all ranks) continued by one rank for 150 steps: the bits of the
  // uninterrupted run (what a checkpoint written on P ranks and read on 1 must give).
  const Communicator& world = Communicator::world();
  const CaseSpec spec = bed_spec();
  DistributedSoftSphere dem(world, std::make_unique<ContactTable>(spec), test::box_of(spec),
                            settings({0, 0, 0}), test::jittered_bed(13, 2, true));
  dem.advance(kSteps / 2);
  const DistributedState half = dem.gather(true);
  if (!world.root()) return;
  std::size_t loaded = half.history.key.size();
  EXPECT_GT(loaded, 1000u); // contacts alive at the cut keep their history
  DistributedSoftSphere rest(Communicator::self(), std::make_unique<ContactTable>(spec),
                             test::box_of(spec), settings({0, 0, 0}), half);
  rest.advance(kSteps - kSteps / 2);
  EXPECT_EQ(outcome(Communicator::self(), rest).hash, one_rank().hash);
}

TEST(DistributedSoftSphere, RebalancedSlabsGiveTheBitsOfOneRank) {
  // Slabs along gravity over a bed in the lower two thirds of the box: the even cuts leave the
  // top ranks few particles. A balance by each particle's work (1 + its row's length) at step
  // 100 moves the cut planes down through the bed while contacts straddle them and particles
  // cross them; a measured one (timings) at step 200 moves them again. The particles must
  // reach their new owners with their histories: the bits of one rank.
  const Communicator& world = Communicator::world();
  const CaseSpec spec = bed_spec();
  DistributedSoftSphere dem(world, std::make_unique<ContactTable>(spec), test::box_of(spec),
                            settings({1, 1, world.size()}), test::jittered_bed(13, 2, true));
  const std::vector<int> before = dem.decomposition().cuts(2);
  dem.advance(100);
  dem.rebalance(false);
  if (world.size() > 1) {
    EXPECT_NE(dem.decomposition().cuts(2), before);
  }
  dem.advance(100);
  dem.rebalance(true);
  dem.advance(kSteps - 200);
  const Outcome o = outcome(world, dem);
  if (world.root()) {
    EXPECT_EQ(o.hash, one_rank().hash);
  }
}

/// Three spheres at the first cut plane x_c of columns (the box's middle on one rank): A rests
/// on the fixed sphere B across the plane (A's centre on the low side, B's on the high side,
/// overlap 1e-5 d: a contact held by gravity, sliding along y, with tangential and rolling
/// history), and C flies along x at 5 m/s, 3 d before the plane: it crosses it at step 180.
ParticleStore straddling(double x_c) {
  constexpr double d = test::kJitteredD;
  const double y0 = 0.03, z0 = 0.02;
  ParticleStore p;
  p.add({x_c + 0.25 * d, y0, z0}, {}, 0.5 * d, 2500.0, 0, 0);                              // B
  p.add({x_c - 0.25 * d, y0, z0 + 0.866014 * d}, {0.0, 0.05, 0.0}, 0.5 * d, 2500.0, 0, 1); // A
  p.add({x_c - 3.0 * d, y0 + 3.0 * d, z0}, {5.0, 0.0, 0.0}, 0.5 * d, 2500.0, 0, 2);        // C
  for (int k = 0; k < 6; ++k) // apart, at rest on the low side: the balance moves the plane
    p.add({x_c - 5.0 * d, y0 - 4.0 * d + 1.5 * k * d, z0}, {}, 0.5 * d, 2500.0, 0, 3 + k);
  p.inv_mass[0] = 0.0, p.inv_inertia[0] = 0.0;
  return p;
}

/// The hash of the three spheres after 300 steps, with a balance by work at step 150 (whose cut
/// planes must move when there are some); the contact must be alive then.
std::uint64_t straddling_run(const Communicator& comm, double x_c) {
  const CaseSpec spec = bed_spec();
  DistributedSoftSphere dem(comm, std::make_unique<ContactTable>(spec), test::box_of(spec),
                            settings({comm.size(), 1, 1}), straddling(x_c));
  dem.advance(150);
  const DistributedState mid = dem.gather(true);
  if (comm.root()) {
    EXPECT_GE(mid.history.key.size(), 2u); // A-B, in both rows
  }
  const std::vector<int> before = dem.decomposition().cuts(0);
  dem.rebalance(false);
  if (comm.size() > 1) {
    EXPECT_NE(dem.decomposition().cuts(0), before);
  }
  dem.advance(150);
  const DistributedState end = dem.gather(true);
  if (comm.root()) {
    EXPECT_GT(end.particles.x[2], x_c + 0.5 * test::kJitteredD); // C crossed the first plane
  }
  return outcome(comm, dem).hash;
}

TEST(DistributedSoftSphere, ContactAcrossAMovingCutPlaneWhileAParticleCrosses) {
  // The contact straddling the cut plane keeps its history while C crosses the plane and the
  // balance moves the plane (it leaves the ranks with a particle each): the bits of one rank.
  const Communicator& world = Communicator::world();
  const CaseSpec spec = bed_spec();
  const Decomposition columns(settings({world.size(), 1, 1}).cells, world.size(), 2,
                              {world.size(), 1, 1});
  const double cell = test::kJitteredL / 20.0;
  const double x_c = world.size() > 1 ? cell * columns.cuts(0)[1] : 0.5 * test::kJitteredL;
  const std::uint64_t many = straddling_run(world, x_c);
  if (!world.root()) return;
  EXPECT_EQ(many, straddling_run(Communicator::self(), x_c));
}

/// Three lines of 19 touching spheres along y (0.001 d apart), at rest on the floor of a box
/// closed along x, in x cells 0, 3 and 5: the even cuts of 3 columns, {0, 6, 13, 20}, give all
/// three to rank 0. Each line costs the same work (19 particles + 36 row entries), so a balance
/// by work cuts at {0, 1, 4, 20}: the line in cell 5 goes from rank 0 to rank 2, whose new box
/// (cells 4-19) is 3 cells (9 mm) from rank 0's (cell 0), farther than the halo (2 d + 2 skin =
/// 6.6 mm): the two ranks are not neighbours any more.
ParticleStore three_lines() {
  constexpr double d = test::kJitteredD;
  ParticleStore p;
  std::int64_t id = 0;
  for (const double x : {0.5 * d, 3.5 * d, 5.5 * d})
    for (int j = 0; j < 19; ++j, ++id)
      p.add({x, 0.5 * d + j * 1.001 * d, 0.5 * d}, {}, 0.5 * d, 2500.0, 0, id);
  return p;
}

/// The hash after 40 steps, a balance by work and 60 more; the owners of the last line's first
/// sphere before and after the balance.
std::uint64_t far_balance_run(const Communicator& comm, int* before, int* after) {
  CaseSpec spec = bed_spec();
  spec.domain.periodic = {false, false, false};
  DistributedSoftSphere::Settings s = settings({comm.size(), 1, 1});
  s.cells.periodic = spec.domain.periodic;
  const ParticleStore start = three_lines();
  const std::size_t moved = 38;
  DistributedSoftSphere dem(comm, std::make_unique<ContactTable>(spec), test::box_of(spec), s,
                            start);
  dem.advance(40);
  *before = dem.decomposition().owner(start.x[moved], start.y[moved], start.z[moved]);
  dem.rebalance(false);
  *after = dem.decomposition().owner(start.x[moved], start.y[moved], start.z[moved]);
  dem.advance(60);
  return outcome(comm, dem).hash;
}

TEST(DistributedSoftSphere, BalanceThatSendsParticlesToAFarRank) {
  // Regression: the migration after a balance went to the neighbouring ranks only (in the new
  // cuts), and the run stopped with "particle ... left the ranks next to its own" when the
  // planes moved far (seen in CI at 3 ranks, planes moved by noisy measured timings). Here, at
  // 3 ranks, the planes move far by design; at every rank count the run must give the bits of
  // one rank.
  const Communicator& world = Communicator::world();
  int before = 0, after = 0;
  const std::uint64_t many = far_balance_run(world, &before, &after);
  if (!world.root()) return;
  if (world.size() == 3) {
    EXPECT_EQ(before, 0);
    EXPECT_EQ(after, 2);
  }
  int one_before = 0, one_after = 0;
  EXPECT_EQ(many, far_balance_run(Communicator::self(), &one_before, &one_after));
}

TEST(DistributedSoftSphere, AnotherStartGivesOtherBits) {
  const Communicator& world = Communicator::world();
  const Outcome nudged = run(world, {0, 0, 0}, 1e-12);
  if (world.root()) {
    EXPECT_NE(nudged.hash, one_rank().hash);
  }
}

} // namespace
} // namespace fluidem
