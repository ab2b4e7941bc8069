// The geometry of a liquid bridge (noncontact/liquid_bridges.hpp and
// noncontact/ordered_liquid_bridges.hpp): the surface gap of two particles or of a particle and a
// wall, the unit normal and the rate at which the gap opens.
#pragma once
#include <cmath>

#include "core/vec3.hpp"
#include "noncontact/pair_rows.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

struct BridgeSeparation {
  double gap;  ///< m, < 0 overlapping
  Vec3 n;      ///< unit normal from the first body towards the second
  double rate; ///< d gap / dt, m/s, > 0 separating
};

/// From particle a to particle b, with the minimum image of `rows` (a NeighbourList or
/// OrderedRows: min_image(d, axis)).
template <class Rows>
BridgeSeparation bridge_separation(const Rows& rows, const ParticleStore& p, std::size_t a,
                                   std::size_t b) {
  const Vec3 d{rows.min_image(p.x[b] - p.x[a], 0), rows.min_image(p.y[b] - p.y[a], 1),
               rows.min_image(p.z[b] - p.z[a], 2)};
  const double r = std::sqrt(norm2(d));
  const Vec3 n = d * (1.0 / r);
  return {r - p.radius[a] - p.radius[b], n, dot(p.velocity(b) - p.velocity(a), n)};
}

/// Particle i and the wall of face f: the normal towards the wall; the rate is minus the
/// velocity towards it.
inline BridgeSeparation wall_bridge_separation(const BoxGeometry& box, const ParticleStore& p,
                                               std::size_t i, int f) {
  const WallDistance w = wall_distance(box, p, i, f);
  return {w.centre - p.radius[i], w.normal, -dot(p.velocity(i), w.normal)};
}

} // namespace fluidem
