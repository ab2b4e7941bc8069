// Rolling friction torques, the two methods of [Zhu07 Table 1].
// Method 2, constant torque (Zhou et al. 1999): M_r = -mu_r R* |F_n| w_rel/|w_rel|, capped so
//   that it cannot reverse the relative rolling velocity within one step.
// Method 1, spring-dashpot (Iwashita & Oda 1998; k_r, C_r as in Ai et al. 2011):
//   M_r = -k_r theta_r - C_r dtheta_r/dt, |M_r| <= mu_r R* |F_n|,
//   k_r = 2.25 k_n mu_r^2 R*^2,  C_r = damping_factor(e) sqrt(I_r k_r).
#pragma once
#include <cmath>

#include "core/vec3.hpp"

namespace fluidem::kernels {

struct RollingResult {
  Vec3 torque;          ///< on particle i, N m (particle j receives the opposite)
  Vec3 nonconservative; ///< the part of `torque` that is not the spring's, N m
  double spring_loss;   ///< energy removed from the spring by the limit, J
  double energy;        ///< elastic energy in the rolling spring, J
};

/// `w_roll`: relative angular velocity w_i - w_j projected on the tangent plane.
/// `inv_inertia_sum` = 1/I_i + 1/I_j (1/I_i for a wall).
inline RollingResult rolling_constant_torque(const Vec3& w_roll, double mu_r, double r_eff,
                                             double fn_abs, double inv_inertia_sum, double dt) {
  const double w = norm(w_roll);
  if (w <= 0.0 || mu_r <= 0.0) return {};
  double m = mu_r * r_eff * fn_abs;
  const double m_stop = w / (inv_inertia_sum * dt); // torque that stops w_rel in one step
  if (m > m_stop) m = m_stop;
  const Vec3 torque = w_roll * (-m / w);
  return {torque, torque, 0.0, 0.0};
}

/// `theta` is the rolling history (rotated into the current tangent plane); it is updated.
/// Always inlined: with more model combinations in the contact loop GCC's inliner, bounded by the
/// growth of the whole unit, stopped inlining it into most batch kernels, which then lost their
/// vectorisation (it was already called, not inlined, in some pair kernels before).
[[gnu::always_inline]] inline RollingResult rolling_spring_dashpot(Vec3& theta, const Vec3& w_roll,
                                                                   double k_r, double c_r,
                                                                   double mu_r, double r_eff,
                                                                   double fn_abs, double dt) {
  if (k_r <= 0.0) return {};
  const double e_old = 0.5 * k_r * norm2(theta);
  theta += w_roll * dt;
  const Vec3 m_spring = -k_r * theta;
  Vec3 m = m_spring - c_r * w_roll;
  const double mmax = mu_r * r_eff * fn_abs;
  const double m2 = norm2(m);
  if (m2 <= mmax * mmax) return {m, -c_r * w_roll, 0.0, 0.5 * k_r * norm2(theta)};
  // Limited as the tangential spring (tangential_force.hpp): the spring alone stays in the limit.
  m *= mmax / std::sqrt(m2);
  const double ms2 = norm2(m_spring);
  if (ms2 > mmax * mmax) theta *= mmax / std::sqrt(ms2);
  const double e_new = 0.5 * k_r * norm2(theta);
  return {m, m, e_old - e_new, e_new}; // booked as the sliding tangential spring
}

} // namespace fluidem::kernels
