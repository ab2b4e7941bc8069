// What the contact loop hands a model's kernel for one contact, and what it takes back: the
// interface between the pair loop (contact_forces.cpp) and the sub-models (contact/models/).
#pragma once
#include "contact/kernels/history_rotation.hpp"
#include "contact/kernels/normal_force.hpp"
#include "core/vec3.hpp"

namespace fluidem::contact_models {

/// One contact between particle i and partner b (a particle or a wall of infinite mass).
struct ContactInput {
  Vec3 n;                    ///< unit normal from i towards the partner
  Vec3 d_prev;               ///< separation one step earlier, unnormalised (rotates the history)
  bool fixed_normal = false; ///< wall contact: the normal never turns
  double overlap;            ///< m, > 0
  Vec3 v_rel; ///< contact-point velocity of i relative to the partner [Deen07 eq. 12]
  Vec3 w_rel; ///< w_i - w_partner
  double r_eff, m_eff, inv_inertia_sum;

  /// A history vector turned with the contact normal (from the separation one step earlier)
  /// [Deen07 eq. 31-32]; a wall's normal never turns.
  [[gnu::always_inline]] Vec3 turned(const Vec3& v) const {
    return fixed_normal ? v : kernels::rotate_with_separation(v, d_prev, n);
  }
};

struct ContactOutput {
  Vec3 force;       ///< on i
  Vec3 torque_unit; ///< n x F_t: torque on i is r_i * this, on a partner particle r_j * this
  Vec3 torque_roll; ///< rolling torque on i (partner gets the opposite)
  Vec3 nc_force, nc_torque_unit, nc_torque_roll; ///< the non-conservative parts of the above
  double fn_abs = 0.0;
  double elastic = 0.0, spring_loss = 0.0;
};

} // namespace fluidem::contact_models
