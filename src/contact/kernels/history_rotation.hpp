// Rotation of a tangential (or rolling) history vector with the contact [Deen07 eq. 31-32].
// The matrix H of [Deen07 eq. 32] rotates about h = n x n0 by the angle between n0 and n; here
// it is applied in the equivalent Rodrigues form without trigonometric calls:
//   R v = c v + w x v + (w . v) w / (1 + c),   c = n0 . n,  w = n0 x n.
#pragma once
#include "core/vec3.hpp"

namespace fluidem::kernels {

/// Rotate v by the rotation taking unit vector n0 onto unit vector n.
inline Vec3 rotate_with_contact(const Vec3& v, const Vec3& n0, const Vec3& n) {
  const double c = dot(n0, n);
  const Vec3 w = cross(n0, n);
  if (c <= -1.0 + 1e-12) return -v; // normal flipped: cannot happen within one step
  return c * v + cross(w, v) + (dot(w, v) / (1.0 + c)) * w;
}

} // namespace fluidem::kernels
