// What stops a run that went unstable (InstabilityError, exit 3): a non-finite position or
// velocity, a particle outside a closed side of the domain, an overlap beyond
// contact.max_overlap. The run keeps its last good state: the guard runs before any output row,
// frame or checkpoint is written (Simulation::run).
#pragma once
#include "contact/contact_forces.hpp"
#include "neighbour/box_geometry.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

struct StabilityLimits {
  BoxGeometry box;          ///< the domain (closed sides: not periodic)
  int dimension = 3;        ///< 2: the y axis is not checked (discs in the x-z plane)
  double max_overlap = 0.0; ///< contact.max_overlap, fraction of a diameter
};

/// Throws InstabilityError naming the particle, what went wrong and the time and step, for the
/// first `count` particles of p (full-step state; all of them when count is p.size()) and the
/// last contacts.
void check_stability(const ParticleStore& p, const ContactStats& contacts,
                     const StabilityLimits& limits, double time, long step, std::size_t count);
inline void check_stability(const ParticleStore& p, const ContactStats& contacts,
                            const StabilityLimits& limits, double time, long step) {
  check_stability(p, contacts, limits, time, step, p.size());
}

} // namespace fluidem
