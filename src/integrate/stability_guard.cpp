#include "integrate/stability_guard.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fluidem {

void check_stability(const ParticleStore& p, const ContactStats& contacts,
                     const StabilityLimits& limits, double time, long step, std::size_t count) {
  const auto where = fmt::format("at t = {:.6g} s (step {})", time, step);
  const BoxGeometry& box = limits.box;
  for (std::size_t i = 0; i < count; ++i) {
    const double q[9] = {p.x[i],  p.y[i],  p.z[i],  p.vx[i], p.vy[i],
                         p.vz[i], p.wx[i], p.wy[i], p.wz[i]};
    for (double v : q) {
      if (!std::isfinite(v)) {
        throw InstabilityError(fmt::format("run unstable {}: particle {} has a non-finite "
                                           "position or velocity",
                                           where, p.id[i]));
      }
    }
    for (int a = 0; a < 3; ++a) {
      if (box.periodic[a] || (limits.dimension == 2 && a == 1)) continue;
      if (q[a] < box.lo[a] - p.radius[i] || q[a] > box.hi[a] + p.radius[i]) {
        throw InstabilityError(fmt::format("run unstable {}: particle {} left the closed domain "
                                           "along {} ({} = {:.6g} m, domain [{}, {}])",
                                           where, p.id[i], "xyz"[a], "xyz"[a], q[a], box.lo[a],
                                           box.hi[a]));
      }
    }
  }
  // After the per-particle checks: a particle that went through a wall is reported as having
  // left the domain rather than as overlapping the wall.
  if (contacts.max_overlap_ratio > limits.max_overlap) {
    throw InstabilityError(fmt::format(
        "run unstable {}: particle {} overlaps a neighbour or wall by {:.3g} of its diameter "
        "(limit contact.max_overlap = {}); reduce simulation.time_step",
        where, contacts.max_overlap_particle, contacts.max_overlap_ratio, limits.max_overlap));
  }
}

} // namespace fluidem
