// The three-parameter hard-sphere collision operator [Deen07 eq. 11-21; Hoomans96 eq. 1-29]:
// normal restitution e_n, Coulomb friction mu, tangential restitution beta_0, sticking and
// sliding collisions, unequal sizes and masses; a wall is a partner of infinite mass.
//
// With n the unit normal from b to a and the contact-point relative velocity
//   v_ab = (v_a - v_b) - (R_a w_a + R_b w_b) x n                       [Deen07 eq. 11]
// the impulse J on a (-J on b) changes
//   v_a += J/m_a, v_b -= J/m_b, w_a -= R_a/I_a n x J, w_b -= R_b/I_b n x J   [eq. 13-14]
// (both spins turn the same way: the force -J acts on b at +R_b n). Then
//   J_n = -(1 + e_n) m_n (v_ab,0 . n),                1/m_n = 1/m_a + 1/m_b          [eq. 20]
//   J_t = -(1 + beta_0) m_t (v_ab,0 . t)  (sticking), 1/m_t = 1/m_n + R_a^2/I_a + R_b^2/I_b
//   J_t = -mu J_n                          (sliding, if mu J_n < (1 + beta_0) m_t |v_t|) [eq. 21]
// For solid spheres m_t = 2/7 m_ab, which is [Deen07 eq. 21] as printed. mu = inf (friction =
// inf in the case) is the sticking limit: mu J_n = inf for every approaching pair (J_n > 0).
#pragma once
#include <cmath>

#include "core/vec3.hpp"

namespace fluidem::hardsphere {

struct Body {
  Vec3 v, w;          ///< velocity, angular velocity
  double r = 0.0;     ///< radius
  double inv_m = 0.0; ///< 1/m (0 for a wall)
  double inv_i = 0.0; ///< 1/I (0 for a wall)
};

struct CollisionLaw {
  double e_n = 1.0, mu = 0.0, beta0 = 0.0;
};

struct CollisionResult {
  Vec3 impulse; ///< J on a
  bool sliding = false;
  bool approaching = false; ///< false: the bodies were separating, nothing was done
};

/// Contact-point velocity of a relative to b [Deen07 eq. 11]; n from b to a.
inline Vec3 contact_velocity(const Body& a, const Body& b, const Vec3& n) {
  return (a.v - b.v) - cross(a.w * a.r + b.w * b.r, n);
}

/// Apply one binary collision in place. n: unit normal from b to a.
inline CollisionResult collide(Body& a, Body& b, const Vec3& n, const CollisionLaw& law) {
  CollisionResult res;
  const Vec3 v0 = contact_velocity(a, b, n);
  // The spins add nothing to the normal component ((w x n) . n = 0); taking it from the linear
  // velocities alone keeps round-off in the spin term from flipping the sign of a grazing
  // approach, so the event scheduler and the operator always agree on it.
  const double vn = dot(a.v - b.v, n);
  if (vn >= 0.0) return res; // separating
  res.approaching = true;
  const double inv_mn = a.inv_m + b.inv_m;
  const double inv_mt = inv_mn + a.r * a.r * a.inv_i + b.r * b.r * b.inv_i;
  const double jn = -(1.0 + law.e_n) * vn / inv_mn;
  const Vec3 vt = v0 - n * vn;
  const double vt_abs = norm(vt);
  Vec3 j = n * jn;
  if (vt_abs > 0.0) {
    const Vec3 t = vt / vt_abs;
    const double jt_stick = (1.0 + law.beta0) * vt_abs / inv_mt; // magnitude
    double jt = jt_stick;
    if (law.mu * jn < jt_stick) {
      jt = law.mu * jn;
      res.sliding = true;
    }
    j -= t * jt;
  }
  const Vec3 nxj = cross(n, j);
  a.v += j * a.inv_m;
  b.v -= j * b.inv_m;
  a.w -= nxj * (a.r * a.inv_i);
  b.w -= nxj * (b.r * b.inv_i);
  res.impulse = j;
  return res;
}

} // namespace fluidem::hardsphere
