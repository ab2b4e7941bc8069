// One contact of a combination of sub-models (normal x tangential x rolling): the kernel every
// contact loop calls, the batched one (contact_forces.cpp) and the rank-independent one
// (ordered_contacts.cpp), so that both give a contact the same bits.
#pragma once
#include "contact/kernels/normal_force.hpp"
#include "contact/models/contact_point.hpp"
#include "contact/pair_params.hpp"

namespace fluidem::contact_kernel {

using contact_models::ContactInput;
using contact_models::ContactOutput;

/// Whether a normal model holds its contacts in tension (JKR): its entries touch while attached
/// down to an overlap of -Normal::detach_distance, and its force is not floored.
template <class Normal>
constexpr bool adhesive = requires {
  Normal::detaches_in_tension;
};

/// One contact of the models Normal x Tangential x Rolling (contact/models/): the normal model's
/// response (with its own history when it has one), floored, then the tangential and rolling
/// models, each on its own part of the history (normal | tangential | rolling).
template <class Normal, class Tangential, class Rolling>
[[gnu::always_inline]] inline ContactOutput evaluate(const ContactInput& c, const PairParams& pp,
                                                     double* hist, double dt) {
  ContactOutput out;
  // Declared, then assigned (not initialised from the call): so GCC splits it into scalars and
  // the batch loop stays vectorised (a struct initialised from a call may stay in memory).
  kernels::NormalResponse nr;
  // A normal model with history (history_width > 0) reads and updates its own part of it and
  // books the energy its hysteresis moves out of the spring; the others are called as before
  // (the same code: no history loads for them).
  [[maybe_unused]] double normal_loss = 0.0;
  if constexpr (Normal::history_width > 0)
    nr = Normal::respond(pp, c.r_eff, c.m_eff, c.overlap, hist, normal_loss);
  else
    nr = Normal::respond(pp, c.r_eff, c.m_eff, c.overlap);
  const double k_t = Normal::tangential_stiffness(pp, nr);
  const double k_rolling = Normal::rolling_stiffness(pp, nr);
  const double vn = dot(c.v_rel, c.n); // > 0 when approaching
  // The normal force never pulls [Schwager & Poeschel 2008]: the Coulomb and rolling limits
  // ([Deen07 eq. 28] |F_n|) scale with the same force whose impulse the normal direction gets,
  // so gross sliding gives J_t = mu J_n (with a tensile tail counted in J_n but not in the
  // limit, J_t/J_n was 1.034 mu at e = 0.5).
  if constexpr (adhesive<Normal>) {
    // An adhesive model's force is tensile by design: not floored, no dashpot; its Coulomb and
    // rolling limits take the model's load (JKR: F_n + 2 F_c).
    out.force = c.n * (-nr.elastic);
    out.fn_abs = Normal::friction_load(pp, c.r_eff, nr.elastic);
    out.elastic = nr.energy;
    out.nc_force = Vec3{};
  } else {
    const kernels::NormalForce fn = kernels::floored_normal_force(nr, vn);
    out.force = c.n * (-fn.magnitude);
    out.fn_abs = fn.magnitude;
    out.elastic = nr.energy;
    out.nc_force = c.n * (-fn.nonconservative);
  }
  if constexpr (Normal::history_width > 0) out.spring_loss = normal_loss;
  double* own = hist + Normal::history_width;
  Tangential::add(out, c, pp, nr, k_t, vn, own, dt);
  Rolling::add(out, c, pp, k_rolling, own + Tangential::history_width, dt);
  return out;
}

template <class Normal, class Tangential, class Rolling>
constexpr int kHistoryWidth =
    Normal::history_width + Tangential::history_width + Rolling::history_width;

/// A contact that ends takes the energy of its springs with it: added to `losses` (J), term by
/// term, as dissipated. (Hertz springs have k_t -> 0 as the overlap closes, so only the linear
/// springs hold energy at separation.) The caller then zeroes the history.
template <class Normal, class Tangential, class Rolling>
[[gnu::always_inline]] inline void add_released_energy(double& losses, const double* hist,
                                                       const PairParams& pp, double r_eff) {
  if constexpr (Normal::springs_hold_energy_at_separation) {
    kernels::NormalResponse separated{}; // the stiffnesses as the overlap closes
    if constexpr (adhesive<Normal>) {
      // An adhesive contact breaks at -delta_c: its potential there is dissipated, and the
      // springs scale with its contact radius there.
      separated = Normal::at_break(pp, r_eff);
      losses += separated.energy;
    }
    const double* own = hist + Normal::history_width;
    if constexpr (Tangential::history_width > 0)
      losses += Tangential::stored_energy(own, Normal::tangential_stiffness(pp, separated));
    if constexpr (Rolling::history_width > 0)
      losses += Rolling::stored_energy(own + Tangential::history_width, pp,
                                       Normal::rolling_stiffness(pp, separated), r_eff);
  }
}

/// Whether a pair touches: it overlaps, or (an adhesive model, whose entry history `hist` is
/// loaded: attached) its overlap is above -delta_c; d2 the squared separation of the centres.
template <class Normal>
[[gnu::always_inline]] inline bool attached_pair(bool overlapping, const double* hist,
                                                 const PairParams& pp, double ri, double rj,
                                                 double d2) {
  if constexpr (adhesive<Normal>) {
    if (overlapping || hist[0] == 0.0) return overlapping;
    const double reach = ri + rj + Normal::detach_distance(pp, ri * rj / (ri + rj));
    return d2 < reach * reach;
  } else {
    return overlapping;
  }
}

} // namespace fluidem::contact_kernel
