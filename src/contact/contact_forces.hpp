// Soft-sphere contact forces over the neighbour list: particle-particle pairs and particle-wall
// contacts, composed from the sub-models named in the case (normal x tangential x rolling).
// The model choice is resolved once into a template instantiation: no virtual call per contact.
#pragma once
#include <array>
#include <functional>

#include "contact/contact_table.hpp"
#include "core/load_shares.hpp"
#include "core/parallel.hpp"
#include "core/phase_progress.hpp"
#include "neighbour/neighbour_list.hpp"
#include "particles/contact_record.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

struct ContactStats {
  long n_contacts = 0;            ///< touching pairs + wall contacts
  double max_overlap_ratio = 0.0; ///< overlap / smaller diameter (wall: / particle diameter)
  long max_overlap_particle = -1; ///< id of a particle in the deepest contact
  double elastic_energy = 0.0;    ///< J stored in all springs (normal, tangential, rolling)
  double spring_losses = 0.0;     ///< J removed from springs this step (Coulomb limit, release)
  /// The largest |F|^2 of one contact (normal and tangential force on a particle), N^2: with the
  /// list's most entries per particle it bounds every particle's contact force (the folded step
  /// of Simulation::step).
  double max_force2 = 0.0;
};

/// Working arrays of the contact loop, kept between steps (nothing is allocated per step).
/// `view` packs what the pair loop reads of each particle (position, radius, velocity, inverse
/// mass, angular velocity, inverse inertia: kView doubles, one base pointer instead of twelve;
/// the inverses are 0 for a fixed particle, ParticleStore::fix);
/// `acc` packs what it adds: contact force, torque, and their non-conservative parts (dashpots,
/// sliding friction, rolling resistance). The work of the non-conservative parts, evaluated by
/// the integrator with the full-step velocities, is the energy the contacts dissipate: with
/// velocity Verlet this is exactly the kinetic energy they remove, so the energy balance
/// measures only the integration error. After compute_contact_forces `acc` holds the step's
/// contact forces and torques (force(i), torque(i)), which the integrator's kicks read: they are
/// kept nowhere else. Between a run's steps the view is also where the particles' positions and
/// velocities live (Simulation::sync_particles copies them into the particle store when read).
struct ContactScratch {
  static constexpr std::size_t kView = 12; ///< x y z r | vx vy vz 1/m | wx wy wz 1/I
  static constexpr std::size_t kAcc = 12;  ///< f | t | f_nc | t_nc
  std::vector<double> view, acc;
  std::vector<ContactStats> slab_stats, wall_stats; ///< per slab / wall chunk, summed in order
  std::vector<int> slab_group_start;                ///< the contact loop's groups of slabs
  std::vector<double> chunk_sums;                   ///< dissipation_sum(): per chunk of particles
  std::vector<unsigned char> chunk_flags;           ///< dissipation_sum(): per chunk
  /// The particle whose row holds each pair entry of the neighbour list (beds small enough for
  /// the contact loop to walk a slab's entries in one loop), for the list of generation
  /// entry_owner_generation (NeighbourList::generation()).
  std::vector<std::uint32_t> entry_owner;
  std::uint64_t entry_owner_generation = ~std::uint64_t{0};
  /// The threads' hand-off in the contact loop: per group of slabs, the step whose phases it
  /// has finished.
  PhaseProgress group_progress;
  /// How the contact loop's threads share the slab groups (measured step by step).
  LoadShares thread_shares;
  /// Per wall chunk, the lowest and highest slab group holding one of its particles, for the
  /// list of generation chunk_groups_generation.
  std::vector<int> chunk_group_lo, chunk_group_hi;
  std::uint64_t chunk_groups_generation = ~std::uint64_t{0};
  /// Whether every particle has the radius same_radius and the inverse mass same_inv_mass,
  /// found for the list of generation same_particles_generation and that many particles.
  bool same_particles = false;
  double same_radius = 0.0, same_inv_mass = 0.0;
  std::uint64_t same_particles_generation = ~std::uint64_t{0};
  std::size_t same_particles_count = 0;
  /// Pack the view from p and zero the sums.
  void reset(const ParticleStore& p);
  /// reset() for particle i alone (the view and sums must be sized for p): the integrator packs
  /// each particle right after its drift, while its data are in the cache, instead of in a
  /// second pass over all of them.
  void pack(const ParticleStore& p, std::size_t i) {
    pack(i, {p.x[i], p.y[i], p.z[i], p.radius[i], p.vx[i], p.vy[i], p.vz[i], p.inv_mass[i], p.wx[i],
             p.wy[i], p.wz[i], p.inv_inertia[i]});
  }
  /// pack() with particle i's values given (x y z r | vx vy vz 1/m | wx wy wz 1/I), as the
  /// integrator has them in registers after its kick and drift.
  [[gnu::always_inline]] void pack(std::size_t i, const std::array<double, kView>& v) {
    double* vi = view.data() + kView * i;
    for (std::size_t k = 0; k < kView; ++k) vi[k] = v[k];
    zero_sums(i);
  }
  /// pack() of the positions and velocities alone (x y z | vx vy vz | wx wy wz), radius, 1/m
  /// and 1/I being in the view already.
  [[gnu::always_inline]] void pack_state(std::size_t i, const std::array<double, 9>& s) {
    double* vi = view.data() + kView * i;
    vi[0] = s[0], vi[1] = s[1], vi[2] = s[2];
    vi[4] = s[3], vi[5] = s[4], vi[6] = s[5];
    vi[8] = s[6], vi[9] = s[7], vi[10] = s[8];
    zero_sums(i);
  }
  /// Zero particle i's sums in acc.
  [[gnu::always_inline]] void zero_sums(std::size_t i) {
    double* ai = acc.data() + kAcc * i;
    // Twelve stores of a double, not a loop: GCC turns a zeroing loop into memset, which may
    // alias anything, and the integrator's loop then reloads every array pointer per particle.
    ai[0] = 0.0, ai[1] = 0.0, ai[2] = 0.0, ai[3] = 0.0, ai[4] = 0.0, ai[5] = 0.0;
    ai[6] = 0.0, ai[7] = 0.0, ai[8] = 0.0, ai[9] = 0.0, ai[10] = 0.0, ai[11] = 0.0;
    static_assert(kAcc == 12);
  }
  /// Size the view and the sums for n particles (keeps what they hold where the sizes agree).
  void resize(std::size_t n) {
    view.resize(kView * n);
    acc.resize(kAcc * n);
  }
  /// Contact force (N) and torque (N m) on particle i from the last compute_contact_forces.
  Vec3 force(std::size_t i) const {
    const double* a = acc.data() + kAcc * i;
    return {a[0], a[1], a[2]};
  }
  Vec3 torque(std::size_t i) const {
    const double* a = acc.data() + kAcc * i;
    return {a[3], a[4], a[5]};
  }
  /// before(i) for every particle i (the integrator's last half kick, returning the particle's
  /// new velocity and angular velocity), each followed by its term of -sum (F_nc.v + T_nc.w) dt
  /// with those velocities: the energy the contacts dissipated over a step of length dt, J, in
  /// one pass over the particles.
  template <class Before>
  double dissipated_after(const ParticleStore& p, double dt, Before&& before) {
    bool any = false;
    return dissipation_sum(
        p.size(), dt,
        [&](std::size_t i) __attribute__((always_inline)) {
          const std::array<double, 6> v = before(i); // vx vy vz wx wy wz
          const std::array<double, 2> t = dissipation_terms(i, v);
          return DissipationTerms{t[0], t[1], false};
        },
        any);
  }
  /// F_nc.v and T_nc.w of particle i with velocities v (vx vy vz wx wy wz).
  [[gnu::always_inline]] std::array<double, 2>
  dissipation_terms(std::size_t i, const std::array<double, 6>& v) const {
    const double* nci = acc.data() + kAcc * i + 6;
    return {nci[0] * v[0] + nci[1] * v[1] + nci[2] * v[2],
            nci[3] * v[3] + nci[4] * v[4] + nci[5] * v[5]};
  }
  /// A particle's two dissipation terms, and a flag (dissipation_sum).
  struct DissipationTerms {
    double force, torque;
    bool flag;
  };
  /// -dt sum over the particles i < n of term(i).force + term(i).torque: term(i) may do more
  /// for particle i in the same pass (the integrator's kicks and drift) and report a flag, ORed
  /// into `any`. Fixed chunks of particles, each summed in particle order, the chunks in chunk
  /// order: the same sum with any number of threads; small enough to share out evenly between
  /// the threads.
  template <class Term>
  double dissipation_sum(std::size_t n, double dt, Term&& term, bool& any) {
    constexpr std::size_t kChunk = 512;
    const std::size_t nchunk = (n + kChunk - 1) / kChunk;
    chunk_sums.resize(nchunk); // kept between steps
    chunk_flags.resize(nchunk);
    double* sums = chunk_sums.data();
    unsigned char* flags = chunk_flags.data();
    parallel_for(nchunk, threaded_particles(n), [&](std::size_t c) {
      double w = 0.0;
      bool flag = false;
      const std::size_t end = std::min(n, (c + 1) * kChunk);
      for (std::size_t i = c * kChunk; i < end; ++i) {
        const DissipationTerms t = term(i);
        w += t.force;
        w += t.torque;
        flag = t.flag || flag;
      }
      sums[c] = w;
      flags[c] = flag;
    });
    double w = 0.0;
    for (std::size_t c = 0; c < nchunk; ++c) w += sums[c];
    for (std::size_t c = 0; c < nchunk; ++c) any = any || flags[c] != 0;
    return -w * dt;
  }
  std::size_t bytes() const;
};

/// History doubles per contact needed by the chosen sub-models.
int contact_history_width(const ContactTable& table);

/// The contact forces and torques on the particles, into nc (ContactScratch::force, torque:
/// overwritten, not added). Velocities are the
/// ones at which the forces are evaluated (half-step velocities in velocity Verlet); `dt` is the
/// step over which the tangential displacement and the dissipation are integrated.
/// When `record` is given and enabled, its samples are replaced by this call's touching contacts:
/// the pairs slab by slab in slab order (rows in the slab's order, partners in list order), then
/// the wall contacts in wall-list order, so the record does not depend on the thread count.
/// Without a record (or disabled) nothing is recorded and nothing is allocated.
/// `state`: Packed when nc's view already holds p's current positions and velocities and its
/// sums are zero (ContactScratch::pack of every particle since they last changed); Stale (the
/// default) packs them here.
/// `before_slab`, when given, is called once for every slab s of the list, before any row reads
/// or adds into a particle of slab s (only s's own rows and the previous slab's do). Calls for
/// different slabs may run at once on different threads, beside rows that touch none of s's
/// particles. The integrator moves and packs slab s's particles there (the view entries and
/// zeroed sums of nl.slab_particles[slab_start[s] .. slab_start[s+1])), while the contact loop
/// is about to read them, instead of in a pass of its own over all particles before the loop.
enum class ScratchState { Stale, Packed };
using SlabHook = std::function<void(int slab)>;
ContactStats compute_contact_forces(const ParticleStore& p, NeighbourList& nl,
                                    const ContactTable& table, double dt, ContactScratch& nc,
                                    ContactRecord* record = nullptr,
                                    ScratchState state = ScratchState::Stale,
                                    const SlabHook* before_slab = nullptr);

} // namespace fluidem
