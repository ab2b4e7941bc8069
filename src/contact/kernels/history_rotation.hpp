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

/// The same rotation with the previous normal given unnormalised, n0 = a/|a| (the separation one
/// step earlier): R v = [(a.n) v + (a x n) x v] / L + ((a x n).v) (a x n) / (L (L + a.n)),
/// L = |a|; one square root and one division per call.
inline Vec3 rotate_with_separation(const Vec3& v, const Vec3& a, const Vec3& n) {
  const double l = norm(a);
  const double an = dot(a, n);
  const double s = l + an;
  if (s <= 1e-12 * l) return -v; // normal flipped: cannot happen within one step
  const Vec3 w = cross(a, n);
  const double inv = 1.0 / (l * s);
  return (an * v + cross(w, v)) * (s * inv) + (dot(w, v) * inv) * w;
}

} // namespace fluidem::kernels
