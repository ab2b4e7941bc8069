// Soft-sphere contact forces over the neighbour list: particle-particle pairs and particle-wall
// contacts, composed from the sub-models named in the case (normal x tangential x rolling).
// The model choice is resolved once into a template instantiation: no virtual call per contact.
#pragma once
#include "contact/contact_record.hpp"
#include "contact/contact_table.hpp"
#include "neighbour/neighbour_list.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

struct ContactStats {
  long n_contacts = 0;            ///< touching pairs + wall contacts
  double max_overlap_ratio = 0.0; ///< overlap / smaller diameter (wall: / particle diameter)
  long max_overlap_particle = -1; ///< id of a particle in the deepest contact
  double elastic_energy = 0.0;    ///< J stored in all springs (normal, tangential, rolling)
  double spring_losses = 0.0;     ///< J removed from springs this step (Coulomb limit, release)
};

/// Working arrays of the contact loop, kept between steps (nothing is allocated per step).
/// `view` packs what the pair loop reads of each particle (position, radius, velocity, mass,
/// angular velocity, inverse inertia: kView doubles, one base pointer instead of twelve);
/// `acc` packs what it adds: contact force, torque, and their non-conservative parts (dashpots,
/// sliding friction, rolling resistance). The work of the non-conservative parts, evaluated by
/// the integrator with the full-step velocities, is the energy the contacts dissipate: with
/// velocity Verlet this is exactly the kinetic energy they remove, so the energy balance
/// measures only the integration error. After compute_contact_forces `acc` holds the step's
/// contact forces and torques (force(i), torque(i)), which the integrator's kicks read: they are
/// kept nowhere else.
struct ContactScratch {
  static constexpr std::size_t kView = 12; ///< x y z r | vx vy vz m | wx wy wz 1/I
  static constexpr std::size_t kAcc = 12;  ///< f | t | f_nc | t_nc
  std::vector<double> view, acc;
  std::vector<ContactStats> slab_stats, wall_stats; ///< per slab / wall chunk, summed in order
  std::vector<double> chunk_sums;                   ///< dissipated(): per chunk of particles
  /// Pack the view from p and zero the sums.
  void reset(const ParticleStore& p);
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
  /// -sum (F_nc.v + T_nc.w) dt: energy dissipated over a step of length dt, J.
  double dissipated(const ParticleStore& p, double dt);
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
ContactStats compute_contact_forces(const ParticleStore& p, NeighbourList& nl,
                                    const ContactTable& table, double dt, ContactScratch& nc,
                                    ContactRecord* record = nullptr);

} // namespace fluidem
