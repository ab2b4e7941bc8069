// The case a coarse-grained run simulates [Chang08 §2.2.3]: the case file describes the real
// particles and `[coarse_graining] ratio = W`; the run moves parcels of W real particles each.
// simulated_case() turns the one into the other (core/coarse_graining.hpp has the factors,
// docs/coarse-graining.md what each scaling conserves):
//   species diameters and size distributions' diameters x s, s = W^(1/3) [Chang08 eq. 2.27]
//     (mass and volume x W, density kept, eq. 2.24-2.26; the fractions, by number or mass, are
//     the real particles');
//   the contact law by contact_scaling: linear and Walton-Braun `contact.stiffness` (k_t follows
//     through stiffness_ratio), Hertz-Mindlin E and G of every species and wall;
//   the drag closure's diameter by drag_diameter (coupling.drag_diameter_factor).
// A pressure force scales with the volume by itself [Chang08 eq. 2.32]; restitution, friction
// and the hard-sphere collision operator are the real particles' (the operator has no stiffness).
// What has no derived scaling is refused while W > 1 (InputError naming both keys): JKR adhesion,
// the non-contact forces, the Basset, Saffman, Magnus and torque terms of [coupling.forces]
// (virtual mass scales with the volume: allowed), and particles read from a file.
// The resolved case a run writes (and a checkpoint restarts from) is the user's: user_values().
#pragma once
#include <string_view>

#include "core/case_spec.hpp"

namespace fluidem {

/// The case as simulated: `user` itself when coarse_graining.ratio is 1; InputError as above.
CaseSpec simulated_case(const CaseSpec& user);

/// Simulated value / user's value of the case key `key` ("species[0].diameter",
/// "contact.stiffness", "walls.x_lo.youngs_modulus", ...) as simulated_case() scales it: s for a
/// diameter, the contact scaling's factor for the linear stiffness and the Hertz moduli, 1 for
/// every other key and without coarse graining. Messages about simulated values divide by it to
/// speak of what the user wrote.
/// (`spec`: the user's case or the simulated one, which keep the same [coarse_graining].)
double simulated_over_user(const CaseSpec& spec, std::string_view key);

/// `simulated` with the values simulated_case() scaled put back to the user's, so that the
/// resolved case keeps everything the set-up resolved (time step, closure name, ...) in the
/// user's terms: simulated_case(user_values(s, user)) == s field by field.
CaseSpec user_values(const CaseSpec& simulated, const CaseSpec& user);

} // namespace fluidem
