// Tangential spring-dashpot with history and a Coulomb limit [Deen07 eq. 28-31].
//   delta_t <- H delta_t + v_t dt                     (history rotated, then integrated)
//   F_t = -k_t delta_t - eta_t v_t                    if |F_t| <= mu |F_n|   (sticking)
//   F_t = mu |F_n| F_t/|F_t|                          otherwise              (sliding)
//   eta_t = -2 ln(beta0) sqrt(2/7 m* k_t) / sqrt(pi^2 + ln^2 beta0)        [Deen07 eq. 30]
// While sliding, the spring alone is kept within the Coulomb limit (|k_t delta_t| <= mu |F_n|,
// delta_t rescaled along itself). [Deen07 eq. 31] sets delta_t = -F_t/k_t, and LAMMPS sets
// delta_t = -(F_t + eta_t v_t)/k_t; both load the spring with the dashpot's share of the force
// at the onset of a contact (where the dashpot dominates) and release it later as spurious
// energy, which our energy balance showed (+20% in an oblique pair impact).
// Energy bookkeeping: while sticking the force splits into the spring -k_t delta_t and the
// dashpot, whose work the integrator evaluates with full-step velocities; while sliding the
// whole force is non-conservative and the spring's change of energy is returned as spring_loss.
#pragma once
#include <cmath>

#include "core/vec3.hpp"

namespace fluidem::kernels {

struct TangentialResult {
  Vec3 force;           ///< on particle i, N
  Vec3 nonconservative; ///< the part of `force` that is not the spring's, N
  double spring_loss;   ///< energy removed from the spring by the Coulomb limit, J
  double energy;        ///< elastic energy stored in the spring after the step, J
  bool sliding;
};

/// `delta_t` is the history, already rotated into the current tangent plane; it is updated.
inline TangentialResult tangential_spring(Vec3& delta_t, const Vec3& v_t, double k_t, double eta_t,
                                          double mu, double fn_abs, double dt) {
  const double e_old = 0.5 * k_t * norm2(delta_t);
  delta_t += v_t * dt;
  const Vec3 f_spring = -k_t * delta_t;
  Vec3 f = f_spring - eta_t * v_t;
  const double f2 = norm2(f);
  // mu = inf (never sliding): no limit under load, none without (not inf * 0 = NaN).
  const double fmax = fn_abs > 0.0 ? mu * fn_abs : 0.0;
  if (f2 <= fmax * fmax) {
    return {f, -eta_t * v_t, 0.0, 0.5 * k_t * norm2(delta_t), false};
  }
  // fmax / |f| and fmax / |f_spring| from one division (the contact loop is bound by the
  // divider); |f_spring| only counts when the spring alone exceeds the limit (so > 0 then).
  const double fs2 = norm2(f_spring);
  const bool spring_over = fs2 > fmax * fmax;
  const double root_f = std::sqrt(f2), root_s = std::sqrt(spring_over ? fs2 : 1.0);
  const double inv = fmax / (root_f * root_s);
  f *= root_s * inv;
  if (spring_over) delta_t *= root_f * inv;
  const double e_new = 0.5 * k_t * norm2(delta_t);
  // While sliding the whole force is non-conservative (its work is taken with the full-step
  // velocities by the integrator) and the spring's change of stored energy is booked against the
  // dissipation, so the balance holds to round-off even while mu |F_n| changes.
  return {f, f, e_old - e_new, e_new, true};
}

/// The simplified Hertz-Mindlin-Deresiewicz tangential force of Langston et al. (1994)
/// [Zhu07 Table 1], without its dashpot (C_t = 0):
///   delta_t <- H delta_t + v_t dt, clipped to |delta_t| <= delta_t,max (full sliding there),
///   F_t = -mu |F_n| (1 - (1 - |delta_t|/delta_t,max)^{3/2}) delta_t/|delta_t|,
///   delta_t,max = mu delta_n (2 - nu)/(2 (1 - nu))            (`delta_t_max`, > 0)
/// Its initial stiffness 3/2 mu |F_n|/delta_t,max is Mindlin's 8 G* sqrt(R* delta_n) for a
/// Hertz normal force. The whole force is non-conservative (its work goes into the dissipation
/// with the full-step velocities; nothing is stored, no spring_loss): see
/// contact/models/tangential_mindlin_deresiewicz.hpp. `sliding`: |delta_t| reached delta_t,max.
inline TangentialResult mindlin_deresiewicz(Vec3& delta_t, const Vec3& v_t, double mu,
                                            double fn_abs, double delta_t_max, double dt) {
  delta_t += v_t * dt;
  const double d2 = norm2(delta_t);
  const double d = std::sqrt(d2);
  const bool sliding = d >= delta_t_max;
  const Vec3 dir = delta_t * (d > 0.0 ? 1.0 / d : 0.0); // delta_t/|delta_t| (0 for 0)
  if (sliding) delta_t = dir * delta_t_max;             // clipped along itself
  const double s = sliding ? 0.0 : 1.0 - d / delta_t_max;
  const double g = 1.0 - s * std::sqrt(s);
  const Vec3 f = dir * (-mu * fn_abs * g);
  return {f, f, 0.0, 0.0, sliding};
}

} // namespace fluidem::kernels
