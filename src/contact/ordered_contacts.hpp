// Rank-independent soft-sphere contact forces (docs/parallel.md): each own particle's contact
// force is the sum of its contacts in ascending partner id (walls after them, by face), each
// pair evaluated from its lower id's side (the same operations in the rows of both particles,
// whichever rank holds them) with the kernel of the batched loop (contact_evaluate.hpp). A
// particle's sums therefore do not depend on the store's order, on the other particles a rank
// holds, on the number of threads or on the number of ranks. A pair is evaluated twice (in both
// rows), where the half list of contact_forces.hpp evaluates it once: the price of that.
#pragma once
#include <cstdint>
#include <vector>

#include "contact/contact_table.hpp"
#include "neighbour/ordered_rows.hpp"
#include "particles/contact_record.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// The contact sums of the own particles, from the last compute_ordered_contact_forces.
struct OrderedContactSums {
  static constexpr std::size_t kAcc = 12; ///< f | t | f_nc | t_nc
  std::vector<double> acc;
  /// Per own particle: the elastic energy of its contacts and the spring energy released by
  /// those that ended, J; a pair's counts at its lower id (so that a sum over all particles
  /// counts it once).
  std::vector<double> elastic, released;
};

/// What a rank saw of its contacts this step: order-free (a sum of integers, maxima).
struct OrderedContactStats {
  std::int64_t contacts = 0;      ///< touching pairs (counted at the lower id) and walls
  double max_overlap_ratio = 0.0; ///< overlap / smaller diameter (wall: / diameter)
  std::int64_t deepest_id = -1;   ///< the lower id of the deepest contact (ties: the lowest)
  double max_force2 = 0.0;        ///< N^2, the largest |F|^2 of one contact
};

/// Contact forces and torques on the first rows.owned() particles of p (its own), from their
/// rows (built on p), updating the rows' histories. `record` (null: none): replaced by the
/// touching contacts that this rank's rows see from their lower id's side (each pair in exactly
/// one row over all ranks) and the own particles' wall contacts, keyed by ids, in no particular
/// order.
OrderedContactStats compute_ordered_contact_forces(const ParticleStore& p, OrderedRows& rows,
                                                   const ContactTable& table, double dt,
                                                   OrderedContactSums& sums,
                                                   std::vector<KeyedContact>* record = nullptr);

} // namespace fluidem
