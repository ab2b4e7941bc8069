#include "contact/contact_forces.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <omp.h>
#include <stdexcept>
#include <string>
#include <utility>

#include "contact/contact_evaluate.hpp"
#include "contact/kernels/normal_force.hpp"
#include "contact/models/model_list.hpp"
#include "core/parallel.hpp"
#include "core/simd_clones.hpp"

namespace fluidem {

int contact_history_width(const ContactTable& t) {
  return t.history_width();
}

namespace {

using contact_kernel::add_released_energy;
using contact_kernel::adhesive;
using contact_kernel::evaluate;
using contact_kernel::kHistoryWidth;
using contact_models::ContactInput;
using contact_models::ContactOutput;

/// `flag` as 0 or 1 in an integer register that the compiler cannot see through: in a loop
/// that adds it to a counter (the contact walk's batch fill) GCC may otherwise branch on the
/// compare it comes from, which is taken about every other time (a mispredicted branch per
/// entry; bench/RESULTS.md).
[[gnu::always_inline]] inline int opaque_flag(bool flag) {
  int t = flag ? 1 : 0;
  __asm__("" : "+r"(t));
  return t;
}

/// Touching contacts (pairs of one slab, or wall contacts of one chunk), by field (structure of
/// arrays): the inputs of the contact kernel, its outputs, and the contacts' history, for `n`
/// contacts (kSize at most: ~30 kB, in L1).
template <int HistoryWidth>
struct ContactBatch {
  static constexpr int kSize = 64;
  static constexpr int kHistory = HistoryWidth;
  using Column = double[kSize];
  int n = 0;
  std::uint32_t i[kSize], j[kSize], e[kSize]; ///< particles (j: pairs only) and list entry
  int params[kSize];                          ///< index of the contact's parameters
  // inputs: pairs: the separation j - i; walls: the normal, the overlap and the gap
  Column d[3], wall_gap;
  // inputs: radii, inverse masses, v_i - v_j, angular velocities, 1/I_i + 1/I_j (walls: v_i,
  // w_i, 1/I_i)
  Column ri, rj, inv_mi, inv_mj, dv[3], wi[3], wj[3], inv_inertia_sum;
  Column hist[HistoryWidth > 0 ? HistoryWidth : 1]; ///< in: before the step; out: after it
  // outputs (ContactOutput's fields) and the unit normal and overlap (inputs for walls)
  Column force[3], torque_unit[3], torque_roll[3], nc_force[3], nc_torque_unit[3],
      nc_torque_roll[3], normal[3], elastic, spring_loss, overlap;
  static Vec3 get(const Column (&c)[3], int k) { return {c[0][k], c[1][k], c[2][k]}; }
};

// The batch kernel is compiled for AVX-512, AVX2 and the x86-64 baseline (core/simd_clones.hpp).

/// What the contacts of a batch have alike, so that the kernel reads it once for all lanes
/// instead of a lane at a time (GCC emulates such a gather with a load and an insert per lane
/// and field: ~12 instructions per contact for the parameters).
enum class Uniformity {
  PerContact, ///< nothing: each contact's parameters through b.params
  Params,     ///< the parameters params[0] (one species; walls of one material)
  Particles,  ///< those, and every particle has the same radius and mass (a monodisperse bed):
              ///< the batch's radius and inverse mass columns are not filled
};

/// Pass 2 of the contact loop: evaluate the batch's contacts, several at once (see compute()).
/// Pairs [Deen07 eq. 12]: relative contact-point velocity from both particles; walls: a partner
/// of infinite mass and radius at rest, whose normal never turns. The effective mass from the
/// inverse masses, 1/m* = 1/m_i + 1/m_j: a fixed particle (1/m = 0) is a partner of infinite
/// mass like a wall, m* = m_i (the list holds no pair of two fixed particles, and no wall entry
/// of one: NeighbourList::build).
/// U: what every contact of the batch has alike (Uniformity); with Uniformity::Particles the
/// particles' radius and inverse mass are r0 and im0, and their columns are not read.
template <class Normal, class Tangential, class Rolling, bool Wall, Uniformity U, int HW>
FLUIDEM_SIMD_CLONES void evaluate_batch(ContactBatch<HW>& b, const PairParams* params, double r0,
                                        double im0, double dt) {
  const int n = b.n;
  constexpr bool same_particles = U == Uniformity::Particles;
#pragma GCC ivdep
  for (int k = 0; k < n; ++k) {
    const double ri = same_particles ? r0 : b.ri[k];
    const double inv_mi = same_particles ? im0 : b.inv_mi[k];
    const Vec3 dv{b.dv[0][k], b.dv[1][k], b.dv[2][k]};
    const Vec3 wi{b.wi[0][k], b.wi[1][k], b.wi[2][k]};
    ContactInput c;
    c.inv_inertia_sum = Rolling::has_torque ? b.inv_inertia_sum[k] : 0.0; // rolling only
    if constexpr (Wall) {
      c.n = b.get(b.normal, k);
      c.fixed_normal = true;
      c.overlap = b.overlap[k];
      c.v_rel = dv + cross(wi * ri, c.n);
      c.w_rel = wi;
      c.r_eff = ri;
      c.m_eff = 1.0 / inv_mi;
    } else {
      const Vec3 dvec{b.d[0][k], b.d[1][k], b.d[2][k]};
      const double rj = same_particles ? r0 : b.rj[k];
      const double inv_mj = same_particles ? im0 : b.inv_mj[k];
      const double rsum = ri + rj, inv_msum = inv_mi + inv_mj, rm = rsum * inv_msum;
      const double d = std::sqrt(norm2(dvec));
      // 1/d and 1/(rsum (1/mi + 1/mj)) from one division (the divider bounds this loop).
      const double inv_drm = 1.0 / (d * rm);
      const double inv_d = rm * inv_drm;
      c.n = Vec3{dvec.x * inv_d, dvec.y * inv_d, dvec.z * inv_d};
      c.overlap = rsum - d;
      const Vec3 wj{b.wj[0][k], b.wj[1][k], b.wj[2][k]};
      c.v_rel = dv + cross(wi * ri + wj * rj, c.n);
      c.w_rel = wi - wj;
      const double inv = d * inv_drm;     // 1/(rsum (1/mi + 1/mj))
      c.r_eff = ri * rj * inv_msum * inv; // r* = ri rj / rsum
      c.m_eff = rsum * inv;               // m* = 1 / (1/mi + 1/mj)
      // Separation one step earlier: positions moved by v dt with the current velocities.
      c.d_prev = dvec + dv * dt;
    }
    double hist[HW > 0 ? HW : 1];
    for (int m = 0; m < HW; ++m) hist[m] = b.hist[m][k];
    const PairParams& pp = U != Uniformity::PerContact ? params[0] : params[b.params[k]];
    const auto out = evaluate<Normal, Tangential, Rolling>(c, pp, hist, dt);
    for (int m = 0; m < HW; ++m) b.hist[m][k] = hist[m];
    // Only the columns the model fills: without tangential or rolling forces their torques
    // are zero, and the last pass does not read them (fewer stores and loads per contact).
    for (int a = 0; a < 3; ++a) {
      b.force[a][k] = out.force[a];
      b.nc_force[a][k] = out.nc_force[a];
      if constexpr (Tangential::has_force) {
        b.torque_unit[a][k] = out.torque_unit[a];
        b.nc_torque_unit[a][k] = out.nc_torque_unit[a];
      }
      if constexpr (Rolling::has_torque) {
        b.torque_roll[a][k] = out.torque_roll[a];
        b.nc_torque_roll[a][k] = out.nc_torque_roll[a];
      }
      if constexpr (!Wall) b.normal[a][k] = c.n[a];
    }
    b.elastic[k] = out.elastic;
    b.spring_loss[k] = out.spring_loss;
    if constexpr (!Wall) b.overlap[k] = c.overlap;
  }
}

/// Four doubles in one vector register (AVX; two SSE2 registers in the baseline clone). The
/// helpers taking and returning them are inlined into the functions of this file that use them
/// (their templates are instantiated at its end): no call between translation units passes one,
/// so GCC's note on the AVX calling convention (-Wpsabi) does not apply (in this file: it is
/// given where the templates are instantiated, at the file's end).
#pragma GCC diagnostic ignored "-Wpsabi"
using Quad = double __attribute__((vector_size(32)));
using QuadIndex = std::int64_t __attribute__((vector_size(32)));
[[gnu::always_inline]] inline Quad load_quad(const double* p) {
  Quad q;
  std::memcpy(&q, p, sizeof q);
  return q;
}
[[gnu::always_inline]] inline void store_quad(double* p, Quad q) {
  std::memcpy(p, &q, sizeof q);
}

/// Rows r0 .. r3 (four columns' values at contacts k .. k+3), turned so that contact[q] holds
/// contact k+q's four values (r0[q], .., r3[q]): a 4 x 4 transposition in eight shuffles.
[[gnu::always_inline]] inline void transpose(Quad r0, Quad r1, Quad r2, Quad r3,
                                             Quad (&contact)[4]) {
  const Quad u0 = __builtin_shuffle(r0, r1, QuadIndex{0, 4, 2, 6});
  const Quad u1 = __builtin_shuffle(r0, r1, QuadIndex{1, 5, 3, 7});
  const Quad u2 = __builtin_shuffle(r2, r3, QuadIndex{0, 4, 2, 6});
  const Quad u3 = __builtin_shuffle(r2, r3, QuadIndex{1, 5, 3, 7});
  contact[0] = __builtin_shuffle(u0, u2, QuadIndex{0, 1, 4, 5});
  contact[1] = __builtin_shuffle(u1, u3, QuadIndex{0, 1, 4, 5});
  contact[2] = __builtin_shuffle(u0, u2, QuadIndex{2, 3, 6, 7});
  contact[3] = __builtin_shuffle(u1, u3, QuadIndex{2, 3, 6, 7});
}

/// The batch's output columns pass 3 adds into the particles' sums (ContactScratch::acc:
/// force | torque | their non-conservative parts), kSize contacts each; the torque columns of a
/// model without them are not read.
template <int kSize>
struct AddColumns {
  const double (*force)[kSize], (*torque_unit)[kSize], (*nc_force)[kSize], (*nc_torque_unit)[kSize],
      (*torque_roll)[kSize], (*nc_torque_roll)[kSize];
};

/// Pass 3's additions into the particles' sums: for each contact in the batch's order, into j's
/// (pairs) -F, r_j (n x F_t) - T_r, -F_nc, r_j (n x F_t,nc) - T_r,nc, then into i's F,
/// r_i (n x F_t) + T_r, F_nc, r_i (n x F_t,nc) + T_r,nc (the tangential terms with a tangential
/// force, the rolling torques T_r with a rolling model). The same products and additions, in the
/// same order, as one element at a time (subtracting f is adding -1 * f, exactly; 1 * f is f; a
/// model without a tangential force adds +0 torques, which leave the sums as they are: they
/// start at +0 and a sum of doubles is -0 only if every term is), here a quad at a time: a
/// particle's twelve sums in three loads, adds and stores; the columns turned into three quads
/// per contact, four contacts at a time (transpose).
/// SameRadius: every particle's radius is r0 (ri and rj are not read).
template <bool Pairs, bool Tangential, bool Rolling, bool SameRadius, int kSize>
FLUIDEM_SIMD_CLONES void add_to_particles(int n, const std::uint32_t* i, const std::uint32_t* j,
                                          const double* ri, const double* rj, double r0,
                                          const AddColumns<kSize>& col, double* acc) {
  constexpr std::size_t kWidth = ContactScratch::kAcc;
  static_assert(kWidth == 12);
  // The quads' lanes: (F.x F.y F.z T.x), (T.y T.z F_nc.x F_nc.y), (F_nc.z T_nc.x T_nc.y T_nc.z);
  // which lanes hold torques, as shuffle indices that take those lanes from the second operand.
  constexpr QuadIndex kTorqueLanes[3] = {{0, 1, 2, 7}, {4, 5, 2, 3}, {0, 5, 6, 7}};
  // value * scale (forces 1 for i or -1 for j, torques the particle's radius), plus (i) or
  // minus (j) the rolling torques on the torque lanes, added into the sums at a.
  auto add = [&kTorqueLanes](double* a, const Quad(&value)[3], const Quad(&roll)[3], double r,
                             double sign) {
    const Quad rs = Quad{} + r, signs = Quad{} + sign; // broadcast
    for (int part = 0; part < 3; ++part) {
      Quad v = value[part] * __builtin_shuffle(signs, rs, kTorqueLanes[part]);
      if constexpr (Rolling)
        v = __builtin_shuffle(v, sign > 0.0 ? v + roll[part] : v - roll[part], kTorqueLanes[part]);
      store_quad(a + 4 * part, load_quad(a + 4 * part) + v);
    }
  };
  const Quad zero{};
  // Column c at contacts k .. k+3 (zero for a torque column the model does not have).
  auto rows = [&](const double(*c)[kSize], int m, int k, bool present) {
    return present ? load_quad(c[m] + k) : zero;
  };
  int k = 0;
  for (; k + 4 <= n; k += 4) {
    Quad a[4], b[4], c[4], ra[4], rb[4], rc[4];
    transpose(rows(col.force, 0, k, true), rows(col.force, 1, k, true), rows(col.force, 2, k, true),
              rows(col.torque_unit, 0, k, Tangential), a);
    transpose(rows(col.torque_unit, 1, k, Tangential), rows(col.torque_unit, 2, k, Tangential),
              rows(col.nc_force, 0, k, true), rows(col.nc_force, 1, k, true), b);
    transpose(rows(col.nc_force, 2, k, true), rows(col.nc_torque_unit, 0, k, Tangential),
              rows(col.nc_torque_unit, 1, k, Tangential),
              rows(col.nc_torque_unit, 2, k, Tangential), c);
    if constexpr (Rolling) {
      transpose(zero, zero, zero, rows(col.torque_roll, 0, k, true), ra);
      transpose(rows(col.torque_roll, 1, k, true), rows(col.torque_roll, 2, k, true), zero, zero,
                rb);
      transpose(zero, rows(col.nc_torque_roll, 0, k, true), rows(col.nc_torque_roll, 1, k, true),
                rows(col.nc_torque_roll, 2, k, true), rc);
    }
    for (int q = 0; q < 4; ++q) {
      const Quad value[3] = {a[q], b[q], c[q]};
      const Quad roll[3] = {Rolling ? ra[q] : zero, Rolling ? rb[q] : zero, Rolling ? rc[q] : zero};
      if constexpr (Pairs)
        add(acc + kWidth * j[k + q], value, roll, SameRadius ? r0 : rj[k + q], -1.0);
      add(acc + kWidth * i[k + q], value, roll, SameRadius ? r0 : ri[k + q], 1.0);
    }
  }
  for (; k < n; ++k) { // the last contacts one element at a time, the same operations
    auto at = [k](const double(*c)[kSize], int m, bool present) { return present ? c[m][k] : 0.0; };
    const double v[12] = {at(col.force, 0, true),
                          at(col.force, 1, true),
                          at(col.force, 2, true),
                          at(col.torque_unit, 0, Tangential),
                          at(col.torque_unit, 1, Tangential),
                          at(col.torque_unit, 2, Tangential),
                          at(col.nc_force, 0, true),
                          at(col.nc_force, 1, true),
                          at(col.nc_force, 2, true),
                          at(col.nc_torque_unit, 0, Tangential),
                          at(col.nc_torque_unit, 1, Tangential),
                          at(col.nc_torque_unit, 2, Tangential)};
    const double roll[12] = {0.0,
                             0.0,
                             0.0,
                             at(col.torque_roll, 0, Rolling),
                             at(col.torque_roll, 1, Rolling),
                             at(col.torque_roll, 2, Rolling),
                             0.0,
                             0.0,
                             0.0,
                             at(col.nc_torque_roll, 0, Rolling),
                             at(col.nc_torque_roll, 1, Rolling),
                             at(col.nc_torque_roll, 2, Rolling)};
    auto add_scalar = [&v, &roll](double* a, double r, double sign) {
      for (int m = 0; m < 12; ++m) {
        const bool torque = (m >= 3 && m < 6) || m >= 9;
        double x = v[m] * (torque ? r : sign);
        if (Rolling && torque) x = sign > 0.0 ? x + roll[m] : x - roll[m];
        a[m] += x;
      }
    };
    if constexpr (Pairs) add_scalar(acc + kWidth * j[k], SameRadius ? r0 : rj[k], -1.0);
    add_scalar(acc + kWidth * i[k], SameRadius ? r0 : ri[k], 1.0);
  }
}

/// The largest of `init` and the squared forces |F|^2 = (F_x^2 + F_y^2) + F_z^2 of the batch's
/// first n contacts (columns `force`), four at a time: a maximum does not depend on the order it
/// is taken in, so this is bitwise the one-by-one scan (NaN never taken, as with f2 > m).
template <int kSize>
FLUIDEM_SIMD_CLONES double largest_force2(int n, const double (*force)[kSize], double init) {
  Quad m = Quad{} + init;
  int k = 0;
  for (; k + 4 <= n; k += 4) {
    const Quad fx = load_quad(force[0] + k), fy = load_quad(force[1] + k),
               fz = load_quad(force[2] + k);
    const Quad f2 = fx * fx + fy * fy + fz * fz;
    m = f2 > m ? f2 : m;
  }
  double largest = init;
  for (int q = 0; q < 4; ++q) largest = m[q] > largest ? m[q] : largest;
  for (; k < n; ++k) {
    const double f2 =
        force[0][k] * force[0][k] + force[1][k] * force[1][k] + force[2][k] * force[2][k];
    largest = f2 > largest ? f2 : largest;
  }
  return largest;
}

/// The groups of consecutive slabs the contact loop's phases run over (compute()): group g is
/// slabs [starts[g], starts[g + 1]), each of at least two slabs (one when there is a single
/// slab). Beds of up to kCachedParticles: pairs of slabs (the last group two or three), which
/// is all even slabs, then all odd ones: their data stay in the cache anyway, and a thread's
/// share is cut at any even slab. Larger beds: about 16 groups of about equal particle counts
/// (the first slab at or after each sixteenth of the particles), which read most slabs once per
/// step and share out evenly between the threads. Fixed by the slabs alone, so that the order
/// of the force additions does not depend on the threads.
void slab_group_starts(const std::vector<std::uint32_t>& slab_start, int nslab,
                       std::vector<int>& starts) {
  constexpr int kGroups = 16;
  constexpr std::size_t kCachedParticles = 32768; // ~16 MB of particle and list data
  starts.clear();
  if (nslab < 1) return;
  starts.push_back(0);
  const std::size_t n = slab_start[nslab];
  if (n <= kCachedParticles) {
    for (int sl = 2; sl <= nslab - 2; sl += 2) starts.push_back(sl);
  } else {
    for (int g = 1; g < kGroups; ++g) {
      const std::size_t share = n * static_cast<std::size_t>(g) / kGroups;
      const int sl =
          static_cast<int>(std::lower_bound(slab_start.begin(), slab_start.begin() + nslab, share) -
                           slab_start.begin());
      if (sl >= starts.back() + 2 && sl <= nslab - 2) starts.push_back(sl);
    }
  }
  starts.push_back(nslab);
}

/// The wall entries are cut into chunks of about kWallChunk that never split one particle's
/// entries (they are sorted by particle), so the chunks run in parallel without races; each
/// keeps its own statistics and samples, joined in chunk order: the result does not depend on
/// the number of threads. The chunks are small enough to share out evenly (2048 entries gave one
/// thread 3 of 5 chunks). Chunk k is entries [wall_chunk_start(k), wall_chunk_start(k + 1)).
constexpr std::size_t kWallChunk = 512;
std::size_t wall_chunk_count(const std::vector<std::uint32_t>& wall_particle) {
  return (wall_particle.size() + kWallChunk - 1) / kWallChunk;
}
std::size_t wall_chunk_start(const std::vector<std::uint32_t>& wall_particle, std::size_t k) {
  const std::size_t nwall = wall_particle.size();
  std::size_t e = std::min(k * kWallChunk, nwall);
  while (e > 0 && e < nwall && wall_particle[e] == wall_particle[e - 1]) ++e;
  return e;
}

/// For each wall chunk, the lowest and highest slab group (slab_group_starts: group_start) that
/// holds one of its particles: the groups whose pairs add into the chunk's particles are those
/// and the group before the lowest (whose last slab's rows add into the next group's first
/// slab). A chunk without particles in any slab (none: every particle is in one) would get
/// every group.
void wall_chunk_groups(const NeighbourList& nl, const std::vector<int>& group_start,
                       std::vector<int>& lo, std::vector<int>& hi) {
  const std::vector<std::uint32_t>& wall_particle = nl.wall_particle;
  const std::size_t nchunk = wall_chunk_count(wall_particle);
  const int ngroup = std::max(0, static_cast<int>(group_start.size()) - 1);
  lo.assign(nchunk, ngroup);
  hi.assign(nchunk, -1);
  // The chunk of entry e: chunk k starts at k * kWallChunk or a few entries after it.
  auto chunk_of = [&](std::size_t e) {
    const std::size_t k = e / kWallChunk;
    return wall_chunk_start(wall_particle, k) > e ? k - 1 : k;
  };
  // Mark the chunks of entries [e0, e1) as holding a particle of group g.
  auto mark = [&](std::size_t e0, std::size_t e1, int g) {
    if (e0 >= e1) return;
    for (std::size_t k = chunk_of(e0), k_end = chunk_of(e1 - 1); k <= k_end; ++k)
      lo[k] = std::min(lo[k], g), hi[k] = std::max(hi[k], g);
  };
  auto entries_from = [&](std::uint32_t i) {
    return static_cast<std::size_t>(
        std::lower_bound(wall_particle.begin(), wall_particle.end(), i) - wall_particle.begin());
  };
  for (int g = 0; g < ngroup; ++g)
    for (int sl = group_start[g]; sl < group_start[g + 1]; ++sl) {
      const std::uint32_t s0 = nl.slab_start[sl], s1 = nl.slab_start[sl + 1];
      if (s0 == s1) continue;
      const std::uint32_t first = nl.slab_particles[s0], final = nl.slab_particles[s1 - 1];
      if (final - first == s1 - 1 - s0) { // consecutive indices (ascending within a slab)
        mark(entries_from(first), entries_from(final + 1), g);
      } else {
        for (std::uint32_t m = s0; m < s1; ++m) {
          const std::uint32_t i = nl.slab_particles[m];
          mark(entries_from(i), entries_from(i + 1), g);
        }
      }
    }
  for (std::size_t k = 0; k < nchunk; ++k)
    if (lo[k] > hi[k]) lo[k] = 0, hi[k] = ngroup - 1;
}

/// Add a slab's or wall chunk's statistics to the total (the deepest overlap: the first one
/// found in the order of the calls).
void add_stats(ContactStats& total, const ContactStats& part) {
  total.n_contacts += part.n_contacts;
  total.elastic_energy += part.elastic_energy;
  total.spring_losses += part.spring_losses;
  total.max_force2 = std::max(total.max_force2, part.max_force2);
  if (part.max_overlap_ratio > total.max_overlap_ratio) {
    total.max_overlap_ratio = part.max_overlap_ratio;
    total.max_overlap_particle = part.max_overlap_particle;
  }
}

/// Whether every species meets every wall face with the same coefficients (bit for bit): the
/// kernel then reads them once for all wall contacts (Uniformity).
bool walls_alike(const ContactTable& table) {
  const PairParams* first = &table.wall(0, 0);
  for (int sp = 0; sp < table.species_count(); ++sp)
    for (int f = 0; f < 6; ++f)
      if (std::memcmp(&table.wall(sp, f), first, sizeof(PairParams)) != 0) return false;
  return true;
}

/// Whether every particle has one radius and mass, into nc.same_particles (NeighbourList::
/// generation() keys the check: the radii and masses change only with the particles, and any
/// change of those rebuilds the list). Fixed particles (1/m = 0) differ from the others.
void find_same_particles(const ParticleStore& p, const NeighbourList& nl, ContactScratch& nc) {
  const std::size_t n = p.size();
  if (nc.same_particles_generation == nl.generation() && nc.same_particles_count == n &&
      !(n > 0 && (p.radius[0] != nc.same_radius || p.inv_mass[0] != nc.same_inv_mass)))
    return;
  nc.same_particles = n > 0;
  for (std::size_t i = 1; i < n && nc.same_particles; ++i)
    nc.same_particles = p.radius[i] == p.radius[0] && p.inv_mass[i] == p.inv_mass[0];
  nc.same_radius = n > 0 ? p.radius[0] : 0.0;
  nc.same_inv_mass = n > 0 ? p.inv_mass[0] : 0.0;
  nc.same_particles_generation = nl.generation();
  nc.same_particles_count = n;
}

/// The particle whose row holds each pair entry of the list (nc.entry_owner), for the flat walk
/// of beds small enough (compute()); released otherwise.
void find_entry_owners(const NeighbourList& nl, std::size_t n, bool flat_walk, ContactScratch& nc) {
  if (!flat_walk) {
    nc.entry_owner = {};
  } else if (nc.entry_owner_generation != nl.generation()) {
    const std::uint32_t* row_offset = nl.offset.data();
    nc.entry_owner.resize(nl.partner.size());
    for (std::size_t i = 0; i < n; ++i)
      std::fill(nc.entry_owner.begin() + row_offset[i], nc.entry_owner.begin() + row_offset[i + 1],
                static_cast<std::uint32_t>(i));
    nc.entry_owner_generation = nl.generation();
  }
}

/// The slabs' and wall chunks' statistics summed in their order into `st`, and (rec given) their
/// samples concatenated in that order: the result does not depend on the thread count.
void join_parts(const std::vector<ContactStats>& slab_stats,
                const std::vector<ContactStats>& wall_stats,
                const std::vector<std::vector<ContactSample>>& slab_samples,
                const std::vector<std::vector<ContactSample>>& chunk_samples,
                std::size_t wall_entries, ContactRecord* rec, ContactStats& st) {
  if (rec) {
    std::size_t total = 0;
    for (const auto& b : slab_samples) total += b.size();
    rec->samples.reserve(total + wall_entries);
    for (const auto& b : slab_samples) rec->samples.insert(rec->samples.end(), b.begin(), b.end());
  }
  for (const auto& ss : slab_stats) add_stats(st, ss);
  for (std::size_t k = 0; k < wall_stats.size(); ++k) {
    add_stats(st, wall_stats[k]);
    if (rec)
      rec->samples.insert(rec->samples.end(), chunk_samples[k].begin(), chunk_samples[k].end());
  }
}

/// The contact loop of one combination of sub-models. A measured hot loop (bench/ab.sh,
/// bench/RESULTS.md): its passes are lambdas over the same locals so that GCC keeps the walk's
/// pointers in registers and inlines the batch kernel; the per-call preparations are the named
/// functions above.
template <class Normal, class Tangential, class Rolling>
ContactStats compute(const ParticleStore& p, NeighbourList& nl, const ContactTable& table,
                     double dt, ContactScratch& nc, ContactRecord* rec, const SlabHook* hook) {
  ContactStats st;
  const bool recording = rec != nullptr && rec->enabled;
  constexpr int hw = kHistoryWidth<Normal, Tangential, Rolling>;
  if (nl.history_width() != hw)
    throw std::logic_error("contact loop: the neighbour list keeps " +
                           std::to_string(nl.history_width()) +
                           " history values per contact, the "
                           "contact model needs " +
                           std::to_string(hw));
  // Whether a contact's history holds anything (a pair that stops touching releases it): the
  // values' bits without their signs, ORed, so that the walk tests one integer (-0.0 counts as
  // empty, as with != 0.0) instead of branching on each value.
  auto loaded = [](const double* hist) {
    std::uint64_t bits = 0;
    for (int k = 0; k < hw; ++k) bits |= std::bit_cast<std::uint64_t>(hist[k]) << 1;
    return bits;
  };
  // A contact that ends takes its spring energy with it: count it as dissipated
  // (contact_kernel::add_released_energy).
  auto release = [&](ContactStats& acc, double* hist, const PairParams& pp, double r_eff) {
    add_released_energy<Normal, Tangential, Rolling>(acc.spring_losses, hist, pp, r_eff);
    std::fill_n(hist, hw, 0.0);
  };
  const std::size_t n = p.size();
  // Particle-particle pairs (half list: each pair once, forces applied to both). The rows of a
  // slab write only to particles of that slab and the next, so all even slabs run in parallel,
  // then all odd slabs; each slab runs its rows in a fixed order and keeps its own statistics,
  // summed in slab order: the result does not depend on the number of threads.
  // Contacts are evaluated in batches (ContactBatch): the list walk keeps the touching entries,
  // their inputs are gathered by field from the packed view, one vectorised loop evaluates the
  // batch's contacts side by side (a contact is a long chain of dependent square roots and
  // divisions; one at a time, the core waits on it), and a last pass adds the forces to the
  // particles in the list's order. A contact's result is the same in any lane and any batch: no
  // FP contraction (-ffp-contract=off for this library), no approximate roots (no -ffast-math).
  const double* view = nc.view.data();
  double* acc_f = nc.acc.data();
  const PairParams* pair_params = &table.pair(0, 0);
  const PairParams* wall_params = &table.wall(0, 0);
  const int n_species = table.species_count();
  using Batch = ContactBatch<hw>;
  constexpr std::false_type kPairs;
  constexpr std::true_type kWalls;
  // Passes 2 and 3 for a full batch: gather the inputs, evaluate, then add the forces to the
  // accumulator, the statistics, the history back into the list, the samples.
  // `wall` is a std::bool_constant: each kind of contact gets its own copy, without a branch
  // per contact on the kind.
  const auto& box = nl.box();
  const double wall_lo[3] = {box.lo[0], box.lo[1], box.lo[2]};
  const double wall_hi[3] = {box.hi[0], box.hi[1], box.hi[2]};
  const std::uint8_t* const wall_face_of = nl.wall_face.data();
  const int* const species_of = p.species.data();
  // One set of parameters for all pairs (one species), or for all wall contacts (every
  // species against every face alike, compared bit for bit): the kernel reads it once.
  const bool pairs_uniform = n_species == 1;
  const bool walls_uniform = walls_alike(table);
  find_same_particles(p, nl, nc);
  // Uniformity::Particles for the pairs, for the walls (it needs their parameters uniform).
  const bool pairs_same = pairs_uniform && nc.same_particles;
  const bool walls_same = walls_uniform && nc.same_particles;
  const double r0 = nc.same_radius, im0 = nc.same_inv_mass;
  auto flush = [&, view, acc_f, pairs_uniform, walls_uniform, pairs_same, walls_same, r0,
                im0](Batch& b, auto wall_kind, ContactStats& acc, std::vector<ContactSample>* buf) {
    constexpr bool wall = decltype(wall_kind)::value;
    // The batch's radius and mass columns are filled unless the kernel does not read them.
    const bool same_particles = wall ? walls_same : pairs_same;
    double* history = wall ? nl.wall_history.data() : nl.history.data();
    for (int k = 0; k < b.n; ++k) {
      // The accumulator lines the last pass will add into, fetched while the batch evaluates.
      const double* target = acc_f + ContactScratch::kAcc * (wall ? b.i[k] : b.j[k]);
      __builtin_prefetch(target, 1);
      __builtin_prefetch(target + 8, 1);
      const double* pi = view + ContactScratch::kView * b.i[k];
      if (!same_particles) b.ri[k] = pi[3], b.inv_mi[k] = pi[7];
      for (int a = 0; a < 3; ++a) b.wi[a][k] = pi[8 + a];
      if constexpr (wall) {
        for (int a = 0; a < 3; ++a) b.dv[a][k] = pi[4 + a];
        if constexpr (Rolling::has_torque) b.inv_inertia_sum[k] = pi[11];
        // The wall's normal, overlap and gap, here for the touching entries only (the walk
        // tests the gap of every entry).
        const int f = wall_face_of[b.e[k]];
        const int a = f / 2;
        const bool lo_face = (f % 2 == 0);
        const double gap = lo_face ? pi[a] - wall_lo[a] : wall_hi[a] - pi[a];
        if (!walls_uniform) b.params[k] = species_of[b.i[k]] * 6 + f;
        for (int c = 0; c < 3; ++c) b.normal[c][k] = 0.0;
        b.normal[a][k] = lo_face ? -1.0 : 1.0; // from the particle towards the wall
        b.overlap[k] = pi[3] - gap;
        b.wall_gap[k] = gap;
      } else {
        const double* pj = view + ContactScratch::kView * b.j[k];
        if (!pairs_uniform) b.params[k] = species_of[b.i[k]] * n_species + species_of[b.j[k]];
        if (!same_particles) b.rj[k] = pj[3], b.inv_mj[k] = pj[7];
        for (int a = 0; a < 3; ++a) {
          b.dv[a][k] = pi[4 + a] - pj[4 + a];
          b.wj[a][k] = pj[8 + a];
        }
        if constexpr (Rolling::has_torque) b.inv_inertia_sum[k] = pi[11] + pj[11];
      }
      const double* hist = history + static_cast<std::size_t>(b.e[k]) * Batch::kHistory;
      for (int m = 0; m < Batch::kHistory; ++m) b.hist[m][k] = hist[m];
    }
    const PairParams* params = wall ? wall_params : pair_params;
    if (!(wall ? walls_uniform : pairs_uniform))
      evaluate_batch<Normal, Tangential, Rolling, wall, Uniformity::PerContact>(b, params, r0, im0,
                                                                                dt);
    else if (!same_particles)
      evaluate_batch<Normal, Tangential, Rolling, wall, Uniformity::Params>(b, params, r0, im0, dt);
    else
      evaluate_batch<Normal, Tangential, Rolling, wall, Uniformity::Particles>(b, params, r0, im0,
                                                                               dt);
    // The sums and the deepest overlap in registers (the accumulator's stores could alias
    // them), in the same order.
    double elastic = acc.elastic_energy, spring_losses = acc.spring_losses;
    double max_ratio = acc.max_overlap_ratio;
    const double max_force2 = largest_force2<Batch::kSize>(b.n, b.force, acc.max_force2);
    std::size_t deepest = n; // the particle of the deepest overlap, when this batch has it
    // The additions into the particles' sums, a quad at a time, before the per-contact loop.
    const AddColumns<Batch::kSize> columns{b.force,          b.torque_unit, b.nc_force,
                                           b.nc_torque_unit, b.torque_roll, b.nc_torque_roll};
    if (same_particles)
      add_to_particles<!wall, Tangential::has_force, Rolling::has_torque, true, Batch::kSize>(
          b.n, b.i, b.j, b.ri, b.rj, r0, columns, acc_f);
    else
      add_to_particles<!wall, Tangential::has_force, Rolling::has_torque, false, Batch::kSize>(
          b.n, b.i, b.j, b.ri, b.rj, r0, columns, acc_f);
    for (int k = 0; k < b.n; ++k) {
      const std::uint32_t i = b.i[k];
      const double ri = same_particles ? r0 : b.ri[k];
      const Vec3 f = b.get(b.force, k);
      Vec3 tr{}; // the rolling torque on i, for the record
      if constexpr (Rolling::has_torque) tr = b.get(b.torque_roll, k);
      double* hist = history + static_cast<std::size_t>(b.e[k]) * Batch::kHistory;
      for (int m = 0; m < Batch::kHistory; ++m) hist[m] = b.hist[m][k];
      elastic += b.elastic[k];
      spring_losses += b.spring_loss[k];
      const double dmin = wall ? 2.0 * ri : 2.0 * std::min(ri, same_particles ? r0 : b.rj[k]);
      if (b.overlap[k] > max_ratio * dmin) [[unlikely]] {
        const double ratio = b.overlap[k] / dmin;
        if (ratio > max_ratio) max_ratio = ratio, deepest = i;
      }
      if (buf) {
        const Vec3 nk = b.get(b.normal, k);
        const Vec3 xi{view[ContactScratch::kView * i], view[ContactScratch::kView * i + 1],
                      view[ContactScratch::kView * i + 2]};
        ContactSample& cs = buf->emplace_back();
        cs.id_i = p.id[i];
        cs.id_j = wall ? -1 - nl.wall_face[b.e[k]] : p.id[b.j[k]];
        cs.i = static_cast<std::int32_t>(i);
        cs.j = wall ? -1 : static_cast<std::int32_t>(b.j[k]);
        cs.overlap = b.overlap[k];
        cs.normal = nk;
        cs.force = f;
        cs.torque_roll = tr;
        // pairs: midway through the overlap; walls: on the wall plane
        cs.contact_point = wall ? xi + nk * b.wall_gap[k] : xi + nk * (ri - 0.5 * b.overlap[k]);
      }
    }
    acc.n_contacts += b.n;
    acc.elastic_energy = elastic;
    acc.spring_losses = spring_losses;
    acc.max_force2 = max_force2;
    if (deepest < n) acc.max_overlap_ratio = max_ratio, acc.max_overlap_particle = p.id[deepest];
    b.n = 0;
  };
  [[maybe_unused]] auto attached_pair = [](bool overlapping, const double* hist,
                                           const PairParams& pp, double ri, double rj, double d2) {
    return contact_kernel::attached_pair<Normal>(overlapping, hist, pp, ri, rj, d2);
  };
  // The end of pass 1 for an entry (pairs and walls alike). A contact that just ended: one
  // integer test, so one rarely taken branch instead of one on touching (unpredictable).
  auto just_ended = [&](const double* hist, bool touching) {
    return (loaded(hist) & (std::uint64_t{touching} - 1)) != 0;
  };
  // The slot is kept when the entry touches; a full batch is evaluated and emptied (the fill
  // `k` lives in the walk's register, stored into the batch only for the flush).
  auto keep = [&](Batch& b, int& k, bool touching, auto kind, ContactStats& acc,
                  std::vector<ContactSample>* buf) {
    k += touching ? 1 : 0;
    if (k == Batch::kSize) {
      b.n = k;
      flush(b, kind, acc, buf);
      k = 0;
    }
  };
  // The walk's arrays as local pointers: the batch's stores could otherwise alias them (the
  // box's periodic flags are chars) and the compiler would reload them for every entry.
  const std::uint32_t* partner = nl.partner.data();
  const std::uint32_t* row_offset = nl.offset.data();
  const int* species = p.species.data();
  double* pair_history = nl.history.data();
  const bool any_periodic = nl.box().periodic[0] || nl.box().periodic[1] || nl.box().periodic[2];
  constexpr std::uint32_t kPrefetch = 16;
  const auto last = static_cast<std::uint32_t>(nl.partner.empty() ? 0 : nl.partner.size() - 1);
  // Pass 1 for a row of the list: every entry is written into the batch's next slot, which is
  // kept only when the pair touches (no branch on contact); a pair that stopped touching
  // releases its history.
  // Prefetch: the partners' lines ahead of the walk, in beds of more than kPrefetchParticles
  // (their packed view, 96 bytes a particle, and the list outgrow the L2 and L3 caches). Below,
  // computing the prefetch address costs more than it saves (bench/RESULTS.md).
  constexpr std::size_t kPrefetchParticles = 32768;
  auto gather_row = [&, view, partner, row_offset, species, pair_history, any_periodic,
                     last]<bool Prefetch>(std::size_t i, Batch& b, ContactStats& acc,
                                          std::vector<ContactSample>* buf) {
    // Locals, not the closure's members: the batch's stores could alias those.
    const double* const v = view;
    const std::uint32_t* const part = partner;
    const int* const spec = species;
    double* const hist_base = pair_history;
    const bool periodic = any_periodic;
    const std::uint32_t end_of_list = last;
    const double* pi = v + ContactScratch::kView * i;
    const double xi = pi[0], yi = pi[1], zi = pi[2], ri = pi[3];
    const int si_row = spec[i] * n_species;
    const std::uint32_t row_end = row_offset[i + 1];
    int k = b.n; // the batch's fill, in a register (stored back before a flush and at the end)
    for (std::uint32_t e = row_offset[i]; e < row_end; ++e) {
      const std::uint32_t j = part[e];
      const double* pj = v + ContactScratch::kView * j;
      // The partner kPrefetch entries ahead: its position for this walk, the rest of its
      // 96 bytes (a second cache line) for the batch's gather.
      if constexpr (Prefetch) {
        const double* ahead =
            v + ContactScratch::kView * part[std::min(e + kPrefetch, end_of_list)];
        __builtin_prefetch(ahead);
        __builtin_prefetch(ahead + 8);
      }
      double dx = pj[0] - xi, dy = pj[1] - yi, dz = pj[2] - zi;
      if (periodic) {
        dx = nl.min_image(dx, 0);
        dy = nl.min_image(dy, 1);
        dz = nl.min_image(dz, 2);
      }
      const double rj = pj[3];
      const double rsum = ri + rj;
      bool touching = dx * dx + dy * dy + dz * dz < rsum * rsum;
      if constexpr (adhesive<Normal>)
        touching =
            attached_pair(touching, hist_base + static_cast<std::size_t>(e) * hw,
                          pair_params[si_row + spec[j]], ri, rj, dx * dx + dy * dy + dz * dz);
      // The pair, its entry and separation (the flush gathers the rest for the touching ones).
      b.i[k] = static_cast<std::uint32_t>(i), b.j[k] = j, b.e[k] = e;
      b.d[0][k] = dx, b.d[1][k] = dy, b.d[2][k] = dz;
      if constexpr (hw > 0) {
        double* hist = hist_base + static_cast<std::size_t>(e) * hw;
        if (just_ended(hist, touching)) [[unlikely]]
          release(acc, hist, pair_params[si_row + spec[j]], ri * rj / rsum);
      }
      keep(b, k, touching, kPairs, acc, buf);
    }
    b.n = k;
  };
  // Beds of up to kFlatWalkParticles (their data in the cache, no prefetch): a slab whose
  // particles have consecutive indices (the spatial sort orders them by slab) has its rows next
  // to each other in the list, and pass 1 walks the slab's entries in one loop, each entry's
  // particle from nc.entry_owner, instead of row by row: the same entries in the same order,
  // without the end of a row, whose length varies, to predict (bench/RESULTS.md). 4 bytes per
  // entry.
  constexpr std::size_t kFlatWalkParticles = kPrefetchParticles;
  const bool flat_walk = n <= kFlatWalkParticles;
  find_entry_owners(nl, n, flat_walk, nc);
  // Pass 1 for the entries [e_begin, e_end), as gather_row for each of their rows in turn.
  auto gather_entries =
      [&, view, partner, species, pair_history, any_periodic,
       owner_of = nc.entry_owner.data()](std::uint32_t e_begin, std::uint32_t e_end, Batch& b,
                                         ContactStats& acc, std::vector<ContactSample>* buf) {
        // Locals, as in gather_row.
        const double* const v = view;
        const std::uint32_t* const part = partner;
        const std::uint32_t* const owner = owner_of;
        const int* const spec = species;
        double* const hist_base = pair_history;
        const bool periodic = any_periodic;
        int k = b.n;
        for (std::uint32_t e = e_begin; e < e_end; ++e) {
          const std::uint32_t i = owner[e], j = part[e];
          const double* pi = v + ContactScratch::kView * i;
          const double* pj = v + ContactScratch::kView * j;
          double dx = pj[0] - pi[0], dy = pj[1] - pi[1], dz = pj[2] - pi[2];
          if (periodic) {
            dx = nl.min_image(dx, 0);
            dy = nl.min_image(dy, 1);
            dz = nl.min_image(dz, 2);
          }
          const double ri = pi[3], rj = pj[3];
          const double rsum = ri + rj;
          bool touching = dx * dx + dy * dy + dz * dz < rsum * rsum;
          if constexpr (adhesive<Normal>)
            touching = attached_pair(touching, hist_base + static_cast<std::size_t>(e) * hw,
                                     pair_params[spec[i] * n_species + spec[j]], ri, rj,
                                     dx * dx + dy * dy + dz * dz);
          b.i[k] = i, b.j[k] = j, b.e[k] = e;
          b.d[0][k] = dx, b.d[1][k] = dy, b.d[2][k] = dz;
          if constexpr (hw > 0) {
            double* hist = hist_base + static_cast<std::size_t>(e) * hw;
            if (just_ended(hist, touching)) [[unlikely]]
              release(acc, hist, pair_params[spec[i] * n_species + spec[j]], ri * rj / rsum);
          }
          k += opaque_flag(touching); // keep(), the fill counted without a branch
          if (k == Batch::kSize) {
            b.n = k;
            flush(b, kPairs, acc, buf);
            k = 0;
          }
        }
        b.n = k;
      };
  // Pass 1 for slab sl's rows.
  auto walk_slab = [&](int sl, Batch& b, ContactStats& acc, std::vector<ContactSample>* buf) {
    const std::uint32_t s0 = nl.slab_start[sl], s1 = nl.slab_start[sl + 1];
    if (s0 == s1) return;
    const std::uint32_t first = nl.slab_particles[s0], final = nl.slab_particles[s1 - 1];
    if (flat_walk && final - first == s1 - 1 - s0) { // (ascending within a slab)
      gather_entries(row_offset[first], row_offset[final + 1], b, acc, buf);
    } else if (n > kPrefetchParticles) {
      for (std::uint32_t k = s0; k < s1; ++k)
        gather_row.template operator()<true>(nl.slab_particles[k], b, acc, buf);
    } else {
      for (std::uint32_t k = s0; k < s1; ++k)
        gather_row.template operator()<false>(nl.slab_particles[k], b, acc, buf);
    }
  };
  // Particle-wall contacts: wall of infinite mass, its own material, in chunks of entries
  // (wall_chunk_start).
  // Pass 1 for the wall entries [e_begin, e_end), as for a row of pairs.
  auto gather_walls = [&](std::size_t e_begin, std::size_t e_end, Batch& b, ContactStats& acc,
                          std::vector<ContactSample>* buf) {
    // Locals, as in the pair walk: the batch's stores could alias the list's and box's members.
    const std::uint32_t* const wall_particle = nl.wall_particle.data();
    const std::uint8_t* const wall_face = nl.wall_face.data();
    const int* const spec = p.species.data();
    double* const hist_base = nl.wall_history.data();
    const double* const v = view;
    const double lo[3] = {wall_lo[0], wall_lo[1], wall_lo[2]};
    const double hi[3] = {wall_hi[0], wall_hi[1], wall_hi[2]};
    int k = b.n;
    for (std::size_t e = e_begin; e < e_end; ++e) {
      const std::uint32_t i = wall_particle[e];
      const int f = wall_face[e];
      const int a = f / 2;
      const bool lo_face = (f % 2 == 0);
      const double* pi = v + ContactScratch::kView * i;
      const double ri = pi[3];
      const double gap = lo_face ? pi[a] - lo[a] : hi[a] - pi[a];
      bool touching = gap < ri;
      if constexpr (adhesive<Normal>)
        if (!touching && hist_base[e * hw] != 0.0)
          touching = gap < ri + Normal::detach_distance(wall_params[spec[i] * 6 + f], ri);
      // The entry and its particle (the flush gathers the rest for the touching ones).
      b.i[k] = i, b.e[k] = static_cast<std::uint32_t>(e);
      if constexpr (hw > 0) {
        double* hist = hist_base + e * hw;
        if (just_ended(hist, touching)) [[unlikely]]
          release(acc, hist, wall_params[spec[i] * 6 + f], ri);
      }
      keep(b, k, touching, kWalls, acc, buf);
    }
    b.n = k;
  };
  const std::size_t nchunk = wall_chunk_count(nl.wall_particle);
  auto chunk_start = [&](std::size_t k) { return wall_chunk_start(nl.wall_particle, k); };
  auto& wall_stats = nc.wall_stats;
  wall_stats.assign(nchunk, ContactStats{});
  std::vector<std::vector<ContactSample>> no_samples;
  auto& chunk_samples = recording ? rec->chunk_parts : no_samples;
  if (recording) {
    chunk_samples.resize(nchunk);
    for (auto& b : chunk_samples) b.clear();
  }
  // Wall chunk k. With threads, each thread of the pairs' region runs the chunks of its own
  // particles after its pairs, in the same region (one fork and join per step fewer), so they
  // are threaded when the pairs are, by particle count, not by wall entries: in a bed one
  // particle deep every particle has two, and the worker thread's writes into the accumulators
  // of a bed whose pairs ran on the main thread would cost more than they share out.
  auto run_wall_chunk = [&](std::size_t k) {
    std::vector<ContactSample>* buf = recording ? &chunk_samples[k] : nullptr;
    const std::size_t end = chunk_start(k + 1);
    ContactStats local; // on the stack, as the slabs' (no false sharing)
    Batch batch;
    gather_walls(chunk_start(k), end, batch, local, buf);
    flush(batch, kWalls, local, buf);
    wall_stats[k] = local;
  };
  const int nslab = nl.slab_count();
  // The slabs run in two phases over fixed groups of consecutive slabs (slab_group_starts(), at
  // least two slabs each): first each group's slabs but its last, in order (their rows write to the
  // group's own slabs only), then each group's last slab (whose rows write to it and to the
  // next group's first slab). Within a phase the groups write to disjoint particles, so they
  // run in parallel; the order of the additions into a particle depends on the slabs alone,
  // not on the thread count. A slab's particles are read by its own rows and the previous
  // slab's, which in the first phase run one after the other: the data are still in the cache
  // (with all even slabs, then all odd ones, every slab would be read twice per step from memory
  // in beds larger than the cache; bench/RESULTS.md).
  slab_group_starts(nl.slab_start, nslab, nc.slab_group_start); // kept: no allocation per step
  const int* const group_start = nc.slab_group_start.data();
  const int ngroup = std::max(0, static_cast<int>(nc.slab_group_start.size()) - 1);
  auto group_begin = [group_start](int g) { return group_start[g]; };
  // The slabs [first, second) of group g in phase 0 or 1.
  auto phase_slabs = [&](int g, int phase) {
    const int last_slab = group_begin(g + 1) - 1;
    return phase == 0 ? std::pair{group_begin(g), last_slab} : std::pair{last_slab, last_slab + 1};
  };
  auto& slab_stats = nc.slab_stats; // kept between steps: no allocation per step
  slab_stats.assign(nslab, ContactStats{});
  // Recording: one buffer per slab (a slab runs on one thread), concatenated in slab order.
  auto& slab_samples = recording ? rec->slab_parts : no_samples;
  if (recording) {
    slab_samples.resize(static_cast<std::size_t>(nslab));
    for (auto& b : slab_samples) b.clear();
  }
  // Below the threading threshold the slabs run on one thread whatever the thread count: then
  // one batch runs through all of them (a slab of a small bed holds a few contacts, too few to
  // fill the vector lanes), its statistics in the first slab's entry. The record keeps the
  // per-slab batches (its samples are ordered by slab).
  const bool threaded = n > kThreadedParticles;
  // The hook (before_slab of compute_contact_forces): in phase 0, for a group's first slab, then
  // for each next slab of the group just before the rows that read it (a group's last slab is
  // read by its own rows in phase 1 and by the slab before it in phase 0; the next group's
  // first slab is prepared by that group's phase 0, which the group's phase 1 waits for).
  const auto prepare = [hook](int slab) {
    if (hook) (*hook)(slab);
  };
  if (!threaded && !recording) {
    ContactStats local;
    Batch batch;
    for (int phase = 0; phase < 2; ++phase)
      for (int g = 0; g < ngroup; ++g) {
        if (phase == 0) prepare(group_begin(g));
        for (auto [sl, sl_end] = phase_slabs(g, phase); sl < sl_end; ++sl) {
          if (phase == 0) prepare(sl + 1);
          walk_slab(sl, batch, local, nullptr);
        }
      }
    flush(batch, kPairs, local, nullptr);
    if (nslab > 0) slab_stats[0] = local;
    for (std::size_t k = 0; k < nchunk; ++k) run_wall_chunk(k);
  } else {
    // Each thread runs a contiguous run of slab groups, and then, in the same region, the wall
    // chunks whose lowest group is one of its own (a chunk writes only to its own particles'
    // sums). The runs hold shares of the particles that LoadShares adjusts step by step toward
    // equal busy times (the cores of a shared machine do not run at the same speed, so the work
    // follows the cores' speed, not the bed's halves); they move little from step to step, so
    // that a thread's particles' view and accumulator lines stay in its core's cache instead of
    // moving between the cores (slabs handed out dynamically did not; bench/RESULTS.md). The
    // threads hand over through the groups' marks (PhaseProgress)
    // instead of barriers: group g's phase 1 waits for group g + 1's phase 0 (the first slab it
    // writes into, and which it reads prepared); a wall chunk waits for phase 1 of its groups and
    // of the group before them (every pair addition into its particles: the walls add after the
    // pairs, as on one thread). When the slabs' axis is periodic the last group's last slab writes
    // into slab 0: group 0 follows the last group. Each thread runs its last group's phase 1, which
    // waits for the next thread, after its other groups', and its wall chunks from the last, whose
    // first one may wait for the previous thread's last group: a thread held up for a moment holds
    // up the others only when their own work runs out (a barrier after each phase made them
    // wait). One thread (or a recording below the threshold):
    // the same slabs in the same order, outside any OpenMP region (core/parallel.hpp).
    if (nc.chunk_groups_generation != nl.generation() || nc.chunk_group_lo.size() != nchunk) {
      wall_chunk_groups(nl, nc.slab_group_start, nc.chunk_group_lo, nc.chunk_group_hi);
      nc.chunk_groups_generation = nl.generation();
    }
    const int* const chunk_lo = nc.chunk_group_lo.data();
    const int* const chunk_hi = nc.chunk_group_hi.data();
    PhaseProgress& progress = nc.group_progress;
    const std::uint64_t step = progress.start(static_cast<std::size_t>(ngroup));
    const bool wrap = nl.slabs_wrap() && ngroup > 1;
    // The group whose first slab group g's last slab writes into (-1: none), and the one that
    // writes into group g's first slab.
    auto next_group = [&](int g) { return g + 1 < ngroup ? g + 1 : (wrap ? 0 : -1); };
    auto previous_group = [&](int g) { return g > 0 ? g - 1 : (wrap ? ngroup - 1 : -1); };
    LoadShares& shares = nc.thread_shares;
    const bool parallel = go_parallel(threaded);
    const double* const bounds = parallel ? shares.prepare(omp_get_max_threads()) : nullptr;
    // The particles before group g's first slab (g = ngroup: all).
    auto particles_before = [&](int g) { return nl.slab_start[group_begin(g)]; };
    auto run_slabs = [&](int nt, int t) {
      const double t0 = omp_get_wtime();
      double waited = 0.0;
      const bool measured = nt > 1 && nt == shares.threads(); // (a smaller team: even shares)
      // The group boundary nearest to a fraction of the particles.
      auto group_at = [&](int thread) {
        if (thread == 0 || thread == nt) return thread == 0 ? 0 : ngroup;
        const double target =
            (measured ? bounds[thread] : static_cast<double>(thread) / nt) * static_cast<double>(n);
        int best = 0;
        for (int g = 1; g <= ngroup; ++g)
          if (std::abs(particles_before(g) - target) < std::abs(particles_before(best) - target))
            best = g;
        return best;
      };
      const int g_begin = group_at(t), g_end = std::max(g_begin, group_at(t + 1));
      const bool handing_over = nt > 1;
      auto run_group = [&](int g, int phase) {
        if (phase == 0) prepare(group_begin(g));
        for (auto [sl, sl_end] = phase_slabs(g, phase); sl < sl_end; ++sl) {
          if (phase == 0) prepare(sl + 1);
          std::vector<ContactSample>* buf = recording ? &slab_samples[sl] : nullptr;
          // Summed on this thread's stack, stored once: the slabs' entries of slab_stats
          // share cache lines, and updating them per contact from two threads made the lines
          // bounce between the cores (false sharing).
          ContactStats local;
          Batch batch;
          walk_slab(sl, batch, local, buf);
          flush(batch, kPairs, local, buf);
          slab_stats[sl] = local;
        }
        if (handing_over) progress.finish(static_cast<std::size_t>(g), phase, step);
      };
      for (int g = g_begin; g < g_end; ++g) run_group(g, 0);
      for (int g = g_begin; g < g_end; ++g) {
        if (handing_over && next_group(g) >= 0)
          waited += progress.wait(static_cast<std::size_t>(next_group(g)), 0, step);
        run_group(g, 1);
      }
      for (std::size_t k = nchunk; k-- > 0;) {
        if (chunk_lo[k] < g_begin || chunk_lo[k] >= g_end) continue;
        if (handing_over) {
          if (previous_group(chunk_lo[k]) >= 0)
            waited += progress.wait(static_cast<std::size_t>(previous_group(chunk_lo[k])), 1, step);
          for (int g = chunk_lo[k]; g <= chunk_hi[k]; ++g)
            waited += progress.wait(static_cast<std::size_t>(g), 1, step);
        }
        run_wall_chunk(k);
      }
      if (measured)
        shares.record(t, static_cast<double>(particles_before(g_end) - particles_before(g_begin)),
                      omp_get_wtime() - t0 - waited);
    };
    if (parallel) {
#pragma omp parallel
      run_slabs(omp_get_num_threads(), omp_get_thread_num());
      shares.update();
    } else {
      run_slabs(1, 0);
    }
  }
  join_parts(slab_stats, wall_stats, slab_samples, chunk_samples, nl.wall_particle.size(),
             recording ? rec : nullptr, st);
  // The contact forces and torques stay in nc.acc: the integrator's kicks read them there (the
  // gas forces and gravity join them in the kick).
  return st;
}

} // namespace

void ContactScratch::reset(const ParticleStore& p) {
  const std::size_t n = p.size();
  resize(n);
  parallel_for(n, threaded_particles(n), [&](std::size_t i) { pack(p, i); });
}

std::size_t ContactScratch::bytes() const {
  return (view.capacity() + acc.capacity()) * sizeof(double) +
         entry_owner.capacity() * sizeof(std::uint32_t) + group_progress.bytes() +
         (chunk_group_lo.capacity() + chunk_group_hi.capacity()) * sizeof(int);
}

ContactStats compute_contact_forces(const ParticleStore& p, NeighbourList& nl,
                                    const ContactTable& t, double dt, ContactScratch& nc,
                                    ContactRecord* rec, ScratchState state, const SlabHook* hook) {
  if (state == ScratchState::Packed) {
    if (nc.view.size() != ContactScratch::kView * p.size() ||
        nc.acc.size() != ContactScratch::kAcc * p.size())
      throw std::logic_error("compute_contact_forces: the packed view is not the particles'");
  } else {
    nc.reset(p);
  }
  if (rec && rec->enabled) rec->samples.clear(); // also for a model that computes nothing
  // The models' combination, chosen once per call; compute<> inlines their kernels. A refused
  // model (declared with a refusal) is never instantiated: the ContactTable refused it.
  using namespace contact_models;
  const Chosen& m = t.models();
  return with_chosen_models<ContactStats>(
      m.normal->index, m.tangential->index, m.rolling->index,
      [&]<class N, class T, class R>() { return compute<N, T, R>(p, nl, t, dt, nc, rec, hook); });
}

} // namespace fluidem
