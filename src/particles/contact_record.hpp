// One step's contacts, recorded on request by the contact loop for the analyses that need the
// individual contacts: collision statistics (overlap extents, contact births and ends) and the
// discrete-to-continuum contact and couple stresses [Zhu07 Tables 5-6].
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"

namespace fluidem {

/// One touching contact at the end of a step's force evaluation.
struct ContactSample {
  std::int64_t id_i = 0;  ///< particle id (ParticleStore::id) of i
  std::int64_t id_j = -1; ///< particle id of the partner; for a wall: -1 - face (face 0..5)
  std::int32_t i = 0;     ///< index of i in the ParticleStore at this step
  std::int32_t j = -1;    ///< index of the partner particle; -1 for a wall
  double overlap = 0.0;   ///< m, > 0
  Vec3 normal;            ///< unit normal from i towards the partner
  Vec3 force;             ///< total contact force on i from the partner, N (partner: -force)
  Vec3 torque_roll;       ///< rolling torque on i, N m (partner particle: -torque_roll)
  Vec3 contact_point;     ///< m: x_i + (r_i - overlap/2) n for pairs, on the wall for walls
};

/// One touching contact keyed by particle ids, independent of any store's indices (what the
/// rank-independent contact loop records for the collision statistics, gathered over the
/// ranks): a pair seen from its lower id's side, a wall contact from its particle.
struct KeyedContact {
  std::int64_t a = 0;    ///< the pair's lower id; a wall contact's particle
  std::int64_t b = -1;   ///< the pair's higher id; for a wall: -1 - face (face 0..5)
  double overlap = 0.0;  ///< m, > 0
  double diameter = 0.0; ///< m: the smaller of the pair's (a wall contact: its particle's)
  Vec3 contact_point;    ///< m: x_a + (r_a - overlap/2) n (n from a to b), on the wall for walls
  Vec3 normal;           ///< unit normal from a towards b (the wall)
  Vec3 force;            ///< total contact force on a, N (b: -force)
  Vec3 torque_roll;      ///< rolling torque on a, N m (b: -torque_roll)
};

/// The record the contact loop fills when `enabled`; cleared by the loop at each call.
struct ContactRecord {
  bool enabled = false;
  /// Pair contacts in the contact loop's slab order, then wall contacts (contact_forces.hpp): the
  /// order does not depend on the number of threads.
  std::vector<ContactSample> samples;
  /// The contact loop's buffers per slab and per wall chunk, concatenated into `samples`; kept
  /// between steps so that a step allocates nothing.
  std::vector<std::vector<ContactSample>> slab_parts, chunk_parts;
};

} // namespace fluidem
