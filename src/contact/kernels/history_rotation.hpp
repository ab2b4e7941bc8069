// Rotation of a tangential (or rolling) history vector with the contact [Deen07 eq. 31-32].
// The matrix H of [Deen07 eq. 32] rotates about h = n x n0 by the angle between n0 and n; here
// it is applied without trigonometric calls, in the Rodrigues form
//   R v = c v + w x v + (w . v) w / (1 + c),   c = n0 . n,  w = n0 x n,
// or (the contact loop) as the equal product of two reflections.
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

/// The same rotation with the previous normal given unnormalised, n0 = a/L, L = |a| (the
/// separation one step earlier), written as two reflections: across the plane normal to
/// u = n0 + n (which takes n0 to -n), then across the plane normal to n (-n to n). With
/// u = a + L n, |u|^2 = 2 L (L + a.n):
///   R v = w - 2 (w.n) n,   w = v - (v.u) u / (L (L + a.n)).
/// One square root and one division per call, and 20 multiplications where the Rodrigues form
/// with a takes 30 (its cross products become dot products).
inline Vec3 rotate_with_separation(const Vec3& v, const Vec3& a, const Vec3& n) {
  const double l = norm(a);
  const double s = l + dot(a, n);
  if (s <= 1e-12 * l) return -v; // normal flipped: cannot happen within one step
  const Vec3 u = a + n * l;
  const Vec3 w = v - u * (dot(v, u) / (l * s));
  return w - n * (2.0 * dot(w, n));
}

} // namespace fluidem::kernels
