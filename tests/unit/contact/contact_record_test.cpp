// ContactRecord filled by the soft-sphere contact loop (contact/contact_forces.hpp): checked
// against independent recomputations from the particle arrays, not against the loop's formulas.
//
// * Newton's third law and completeness: summing each recorded force onto i (+F) and its partner
//   particle (-F) gives exactly the contact force arrays p.f* (to round-off of the different
//   summation order, 1e-12 relative to the largest force), and r_i (n x F) + T_roll onto i,
//   r_j (n x F) - T_roll onto j gives the torque arrays (the tangential torque is r (n x F_t)
//   and n x F = n x F_t).
// * Geometry: overlap = r_i + r_j - |x_j - x_i| (minimum image) for pairs and r_i - gap for
//   walls, normal = (x_j - x_i)/|x_j - x_i|, contact point x_i + (r_i - overlap/2) n (pairs) and
//   on the wall plane (walls), to 1e-12 relative.
// * One sample per touching contact (== ContactStats::n_contacts); disabled record: untouched;
//   forces are bitwise the same with and without recording; the record is bitwise the same with
//   one and two OpenMP threads (> 4096 particles: the parallel slab loop runs).
// * A view packed by the integrator (ScratchState::Packed) gives the same forces.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "../../common/contact_case.hpp"
#include "contact/contact_forces.hpp"

namespace fluidem {
namespace {

constexpr double kD = 0.003;
constexpr double kL = 0.06; // box edge along x and y (periodic); z has walls
constexpr double kH = 0.04; // box height

CaseSpec make_spec() {
  CaseSpec s;
  s.simulation.dimension = 3;
  s.simulation.gravity = {0.0, 0.0, -9.81};
  s.domain.lo = {0.0, 0.0, 0.0};
  s.domain.hi = {kL, kL, kH};
  s.domain.periodic = {true, true, false};
  s.species.push_back(test::glass_species_spec("glass")); // d = kD
  s.contact.normal.name = "hertz";
  s.contact.tangential.name = "history";
  s.contact.rolling.name = "spring_dashpot";
  return s;
}

/// A jittered lattice of 20 x 20 per layer, spacing 0.97 d: most neighbours overlap slightly; the
/// first layer touches the floor. Random velocities and spins.
ParticleStore make_particles(std::size_t layers) {
  ParticleStore p;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double a = 0.97 * kD;
  const int nxy = static_cast<int>(kL / a);
  std::int64_t id = 1000; // ids differ from indices
  for (std::size_t k = 0; k < layers; ++k)
    for (int j = 0; j < nxy; ++j)
      for (int i = 0; i < nxy; ++i) {
        const Vec3 x{(i + 0.5) * kL / nxy + 0.02 * kD * u(rng),
                     (j + 0.5) * kL / nxy + 0.02 * kD * u(rng),
                     0.49 * kD + static_cast<double>(k) * a + 0.02 * kD * u(rng)};
        const Vec3 v{0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng)};
        p.add(x, v, 0.5 * kD * (1.0 + 0.01 * u(rng)), 2500.0, 0, id);
        id += 3;
        const std::size_t n = p.size() - 1;
        p.wx[n] = 50.0 * u(rng), p.wy[n] = 50.0 * u(rng), p.wz[n] = 50.0 * u(rng);
      }
  return p;
}

struct Result {
  ParticleStore p;
  ContactStats stats;
  ContactRecord rec;
  ContactScratch nc; ///< holds the forces and torques
};

Result run(std::size_t layers, bool record, int threads = 0) {
  const CaseSpec spec = make_spec();
  const ContactTable table(spec);
  Result r;
  r.p = make_particles(layers);
  NeighbourList nl(test::box_of(spec), 0.1 * kD, contact_history_width(table));
  nl.build(r.p);
  r.rec.enabled = record;
  const int saved = omp_get_max_threads();
  if (threads > 0) omp_set_num_threads(threads);
  // Two calls: the second has tangential and rolling history, and must replace the record.
  for (int call = 0; call < 2; ++call) {
    std::fill(r.nc.acc.begin(), r.nc.acc.end(), 1.0); // overwritten
    r.stats = compute_contact_forces(r.p, nl, table, 1e-5, r.nc, &r.rec);
  }
  omp_set_num_threads(saved);
  return r;
}

double min_image(double d, double l, bool periodic) {
  return periodic ? d - l * std::nearbyint(d / l) : d;
}

TEST(ContactRecord, SumsToForceArraysAndMatchesGeometry) {
  const Result r = run(3, true);
  const auto& p = r.p;
  const auto& s = r.rec.samples;
  ASSERT_GT(s.size(), p.size()); // dense: more contacts than particles
  EXPECT_EQ(static_cast<long>(s.size()), r.stats.n_contacts);
  const std::size_t n = p.size();
  std::vector<Vec3> f(n), t(n);
  double fmax = 0.0, tmax = 0.0;
  long walls = 0;
  bool walls_last = true, seen_wall = false;
  for (const auto& c : s) {
    ASSERT_GE(c.i, 0);
    const auto i = static_cast<std::size_t>(c.i);
    EXPECT_EQ(c.id_i, p.id[i]);
    EXPECT_GT(c.overlap, 0.0);
    EXPECT_NEAR(norm(c.normal), 1.0, 1e-12);
    const Vec3 xi = p.position(i);
    const Vec3 tn = cross(c.normal, c.force);
    f[i] += c.force;
    if (c.j >= 0) {
      walls_last &= !seen_wall;
      const auto j = static_cast<std::size_t>(c.j);
      EXPECT_EQ(c.id_j, p.id[j]);
      const Vec3 d{min_image(p.x[j] - p.x[i], kL, true), min_image(p.y[j] - p.y[i], kL, true),
                   p.z[j] - p.z[i]};
      const double dist = norm(d);
      EXPECT_NEAR(c.overlap, p.radius[i] + p.radius[j] - dist, 1e-12 * kD);
      EXPECT_NEAR(norm(c.normal - d / dist), 0.0, 1e-12);
      const Vec3 cp = xi + d / dist * (p.radius[i] - 0.5 * c.overlap);
      EXPECT_NEAR(norm(c.contact_point - cp), 0.0, 1e-12 * kD);
      f[j] -= c.force;
      t[i] += tn * p.radius[i] + c.torque_roll;
      t[j] += tn * p.radius[j] - c.torque_roll;
    } else {
      seen_wall = true;
      ++walls;
      const int face = static_cast<int>(-1 - c.id_j);
      ASSERT_TRUE(face == 4 || face == 5) << face; // only z has walls
      const double wall_z = face == 4 ? 0.0 : kH;
      EXPECT_NEAR(c.overlap, p.radius[i] - std::abs(p.z[i] - wall_z), 1e-12 * kD);
      EXPECT_EQ(c.normal.z, face == 4 ? -1.0 : 1.0);
      EXPECT_NEAR(c.contact_point.z, wall_z, 1e-15);
      EXPECT_EQ(c.contact_point.x, xi.x);
      t[i] += tn * p.radius[i] + c.torque_roll;
    }
    fmax = std::max(fmax, norm(c.force));
    tmax = std::max(tmax, norm(tn) * kD);
  }
  EXPECT_TRUE(walls_last) << "wall contacts must follow all pair contacts";
  EXPECT_GT(walls, 10);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 fi = r.nc.force(i), ti = r.nc.torque(i);
    EXPECT_NEAR(f[i].x, fi.x, 1e-12 * fmax) << i;
    EXPECT_NEAR(f[i].y, fi.y, 1e-12 * fmax) << i;
    EXPECT_NEAR(f[i].z, fi.z, 1e-12 * fmax) << i;
    EXPECT_NEAR(t[i].x, ti.x, 1e-12 * tmax) << i;
    EXPECT_NEAR(t[i].y, ti.y, 1e-12 * tmax) << i;
    EXPECT_NEAR(t[i].z, ti.z, 1e-12 * tmax) << i;
  }
}

TEST(ContactRecord, OffChangesNothingAndRecordsNothing) {
  const Result on = run(2, true);
  const Result off = run(2, false);
  EXPECT_TRUE(off.rec.samples.empty());
  EXPECT_EQ(on.nc.acc, off.nc.acc); // forces, torques and their non-conservative parts
  EXPECT_EQ(on.stats.n_contacts, off.stats.n_contacts);
}

bool same(const ContactSample& a, const ContactSample& b) {
  auto eq = [](const Vec3& u, const Vec3& v) { return u.x == v.x && u.y == v.y && u.z == v.z; };
  return a.id_i == b.id_i && a.id_j == b.id_j && a.i == b.i && a.j == b.j &&
         a.overlap == b.overlap && eq(a.normal, b.normal) && eq(a.force, b.force) &&
         eq(a.torque_roll, b.torque_roll) && eq(a.contact_point, b.contact_point);
}

TEST(ContactRecord, DoesNotDependOnThreadCount) {
  const Result a = run(12, true, 1);
  const Result b = run(12, true, 2);
  ASSERT_GT(a.p.size(), 4096u);
  ASSERT_EQ(a.rec.samples.size(), b.rec.samples.size());
  for (std::size_t k = 0; k < a.rec.samples.size(); ++k)
    ASSERT_TRUE(same(a.rec.samples[k], b.rec.samples[k])) << k;
}

// ScratchState::Packed: the integrator packs each particle's view right after its drift
// (ContactScratch::pack) and the contact loop then skips its own packing. The forces must be
// bitwise those of a loop that packs the view itself; a view packed for another particle count
// is refused (a logic error, not forces from stale data).
TEST(ContactScratchState, PackedByParticleGivesTheSameForces) {
  const CaseSpec spec = make_spec();
  const ContactTable table(spec);
  const ParticleStore p = make_particles(3);
  NeighbourList nl(test::box_of(spec), 0.1 * kD, contact_history_width(table));
  nl.build(p);
  NeighbourList nl_packed = nl;
  ContactScratch stale, packed;
  stale.acc.assign(ContactScratch::kAcc * p.size(), 1.0); // overwritten
  const ContactStats a = compute_contact_forces(p, nl, table, 1e-5, stale);
  packed.resize(p.size());
  std::fill(packed.acc.begin(), packed.acc.end(), 1.0); // zeroed by pack()
  for (std::size_t i = 0; i < p.size(); ++i) packed.pack(p, i);
  const ContactStats b =
      compute_contact_forces(p, nl_packed, table, 1e-5, packed, nullptr, ScratchState::Packed);
  ASSERT_GT(a.n_contacts, static_cast<long>(p.size()));
  EXPECT_EQ(a.n_contacts, b.n_contacts);
  EXPECT_EQ(stale.acc, packed.acc);
  EXPECT_EQ(stale.view, packed.view);
  EXPECT_EQ(nl.history, nl_packed.history);

  ContactScratch short_view;
  short_view.resize(p.size() - 1);
  EXPECT_THROW(
      compute_contact_forces(p, nl, table, 1e-5, short_view, nullptr, ScratchState::Packed),
      std::logic_error);
}

} // namespace
} // namespace fluidem
