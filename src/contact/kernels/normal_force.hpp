// Normal contact force kernels: stateless, inlined into the pair loop, tested one by one.
//
// Linear spring-dashpot [Deen07 eq. 24-26]:
//   F_n = max(0, k_n delta + eta_n v_n) (repulsive, along -n on particle i),  eta_n = f sqrt(m*
//   k_n)
// Hertz with Tsuji's damping [Zhu07 Table 1; Chang08 eq. 2.15, 2.22]:
//   F_n = max(0, K delta^{3/2} + alpha sqrt(m* K) delta^{1/4} v_n),   K = 4/3 E* sqrt(R*)
// The force never pulls (floored_normal_force): the dashpot would make it tensile at the end of a
// damped contact, and friction, bounded by the compressive force, would then not match the
// normal impulse [Schwager & Poeschel 2008]. f(e) and alpha(e) are calibrated for this floor once
// per run (contact/kernels/normal_damping.hpp), so that a head-on impact rebounds with exactly the
// requested e, independent of the impact velocity.
// The Hertz spring is written with the contact radius a = sqrt(R* delta) (delta = a^2 / R*):
//   K delta^{3/2} = k_n a delta, sqrt(m* K) delta^{1/4} = sqrt(m* k_n a), dF/d(delta) = 3/2 k_n a
//   (k_n = 4/3 E*): two square roots per contact instead of four (sqrt R*, sqrt delta, its root,
//   sqrt(m* K)); the contact loop is bound by the divider (square roots and divisions) on wide
//   vectors.
#pragma once
#include <cmath>
#include <numbers>

namespace fluidem::kernels {

/// Magnitudes of the normal contact response for a given overlap and approach speed.
struct NormalResponse {
  double elastic;       ///< spring force magnitude, N (repulsive, along -n on particle i)
  double damping_coeff; ///< eta_n, kg/s: damping force = -eta_n v_n
  double stiffness;     ///< tangent stiffness dF/d(delta), N/m (for tangential/rolling springs)
  double energy;        ///< elastic energy stored, J
  /// sqrt(m* K) delta^{1/4} (Hertz) or sqrt(m* k_n) (linear): the dashpots scale with it, the
  /// tangential one as eta_t = factor sqrt(2 k_t / (7 k_n)) damping_scale [Deen07 eq. 30].
  double damping_scale;
  /// Hertz contact radius sqrt(R* delta), m (Mindlin's k_t scales with it; 0 for the linear
  /// spring, which does not need it).
  double contact_radius;
};

/// Damping factor -2 ln e / sqrt(pi^2 + ln^2 e) (2 for e = 0) [Deen07 eq. 27, 30]: the
/// tangential dashpot's (from beta0) and the rolling dashpot's (from e). (The normal dashpot,
/// whose force is floored at zero, takes contact/kernels/normal_damping.hpp's calibration instead.)
inline double restitution_damping_factor(double e) {
  if (e <= 0.0) return 2.0;
  const double l = std::log(e);
  return -2.0 * l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

/// Linear spring [Deen07 eq. 24, 26]. `damping_factor` f from linear_damping_factor(e).
inline NormalResponse linear_normal(double k, double damping_factor, double m_eff, double delta) {
  const double scale = std::sqrt(m_eff * k);
  return {k * delta, damping_factor * scale, k, 0.5 * k * delta * delta, scale, 0.0};
}

/// Hertz spring with Tsuji damping [Chang08 eq. 2.15, 2.22]. `k_n` = 4/3 E* (K = k_n sqrt(R*)),
/// `r_eff` = R*.
inline NormalResponse hertz_normal(double k_n, double r_eff, double alpha, double m_eff,
                                   double delta) {
  const double a = std::sqrt(r_eff * delta);       // contact radius
  const double elastic = k_n * a * delta;          // K delta^{3/2}
  const double scale = std::sqrt(m_eff * k_n * a); // sqrt(m* K) delta^{1/4}
  return {elastic, alpha * scale, 1.5 * k_n * a, 0.4 * elastic * delta, scale, a};
}

/// Walton & Braun's hysteretic spring [Zhu07 Table 1; Walton & Braun 1986, J. Rheol. 30:949]
/// for one step: loading k1 while the overlap is at its largest so far, unloading and reloading
/// on k2 = k1/ratio along F = k2 (delta - delta0), delta0 = delta_max (1 - k1/k2), floored at 0.
struct WaltonBraunResult {
  double force;       ///< N, >= 0
  double stiffness;   ///< dF/d(delta), N/m (0 while the force is floored)
  double energy;      ///< the recoverable energy 1/2 k2 (delta - delta0)^2, J
  double spring_loss; ///< the work of loading that the unloading line does not give back, J
  double delta_max;   ///< the history after the step, m
  double delta0;      ///< the unloading line's zero, m
};

/// `ratio` = k1/k2 in (0, 1] (= e^2), `delta_max` the history before the step. While loading
/// from delta_max to delta the force k1 delta does the work 1/2 k1 (delta^2 - delta_max^2), of
/// which the recoverable energy 1/2 (k1^2/k2) delta^2 takes the share k1/k2: the rest,
/// 1/2 k1 (1 - k1/k2) (delta^2 - delta_max^2), is spring_loss (also for a step that reloads on
/// k2 up to delta_max and loads on k1 beyond it: the recoverable energy at delta_max is the same).
inline WaltonBraunResult walton_braun_normal(double k1, double ratio, double delta_max,
                                             double delta) {
  if (delta >= delta_max) {
    const double loss = 0.5 * k1 * (1.0 - ratio) * (delta * delta - delta_max * delta_max);
    return {k1 * delta, k1, 0.5 * ratio * k1 * delta * delta, loss, delta, delta * (1.0 - ratio)};
  }
  const double k2 = k1 / ratio;
  const double delta0 = delta_max * (1.0 - ratio);
  const double s = delta - delta0;
  if (s > 0.0) return {k2 * s, k2, 0.5 * k2 * s * s, 0.0, delta_max, delta0};
  return {0.0, 0.0, 0.0, 0.0, delta_max, delta0};
}

/// Johnson, Kendall & Roberts (1971) adhesive elastic contact [Zhu07 §2.2; Johnson, Contact
/// Mechanics 1985, §5.5] on its attached branch: the contact radius a at the overlap delta from
///   delta = a^2/R* - sqrt(2 pi w a / E*)   (c = sqrt(2 pi w / E*) = `root`)
/// i.e. with x = sqrt(a) the quartic x^4 - p x - q = 0, p = R* c, q = R* delta, solved in closed
/// form (Ferrari's resolvent cubic y^3 + q y - p^2/8 = 0, of which Cardano's root is written as
/// y = r/(u^2 + q/3 + (q/(3u))^2), u = cbrt(r/2 + sqrt(r^2/4 + q^3/27)), r = p^2/8, free of
/// cancellation for any sign of q; then x = (s + sqrt(2p/s - 2y))/2, s = sqrt(2y), the largest
/// root: the stable branch, a >= a_c). No iteration. Relative error against mpmath <= 1e-13
/// down to delta = -0.9999 delta_c (tools/jkr_reference.py); at -delta_c the two roots meet
/// (r^2/4 + q^3/27 = 0) and a is ill-conditioned, as the physics.
///   F_n = 4 E* a^3/(3 R*) - sqrt(8 pi w E* a^3)     (> 0 repulsive; down to -3/2 pi w R*)
/// Energy, the potential of the attached branch referenced to its formation state (delta = 0,
/// a_f^3 = 2 pi w R*^2/E*): U(delta) = integral_0^delta F_n = G(a) - G(a_f) with
///   G(a) = 8 E* a^5/(15 R*^2) - 4/(3 R*) sqrt(2 pi w E*) a^{7/2} + pi w a^2,
///   G(a_f) = -3/5 pi w a_f^2,  a_f^2 = p^{4/3}.
/// `k_n` = 4/3 E* (as for Hertz), `root` = c (so that pi w = E* c^2/2).
inline NormalResponse jkr_normal(double k_n, double root, double r_eff, double m_eff,
                                 double delta) {
  const double p = r_eff * root, q = r_eff * delta, r = 0.125 * p * p;
  const double disc = 0.25 * r * r + q * q * q / 27.0;
  const double u = std::cbrt(0.5 * r + std::sqrt(disc > 0.0 ? disc : 0.0));
  const double v = q / (3.0 * u);
  const double y = r / (u * u + q / 3.0 + v * v);
  const double s = std::sqrt(2.0 * y);
  const double t = 2.0 * p / s - 2.0 * y;
  const double x = 0.5 * (s + std::sqrt(t > 0.0 ? t : 0.0)); // sqrt(a)
  const double a = x * x;
  const double e_star = 0.75 * k_n;
  const double hertz = k_n / r_eff * a * a * a;        // 4 E* a^3 / (3 R*)
  const double adhesive = 2.0 * e_star * root * a * x; // sqrt(8 pi w E* a^3)
  const double pw = 0.5 * e_star * root * root;        // pi w
  const double a2 = a * a;
  const double g = 8.0 * e_star / (15.0 * r_eff * r_eff) * a2 * a2 * a -
                   4.0 / (3.0 * r_eff) * e_star * root * a2 * a * x + pw * a2;
  const double energy = g + 0.6 * pw * p * std::cbrt(p);
  const double scale = std::sqrt(m_eff * k_n * a);
  // The tangent stiffness the tangential and rolling springs scale with: Hertz's 2 E* a at the
  // JKR contact radius (the exact dF/d(delta) diverges at -delta_c).
  return {hertz - adhesive, 0.0, 1.5 * k_n * a, energy, scale, a};
}

/// The JKR potential at the break, U(-delta_c) = G(a_c) - G(a_f) = pi w a_f^2 (3/5 + 2/5
/// 16^{-2/3}) (a_c^3 = a_f^3/16: the radius where d(delta)/da = 0), J: the energy an attached
/// contact takes with it when it breaks (spring_loss). The contact radius there is a_c.
/// `k_n` = 4/3 E*, `root` = sqrt(2 pi w/E*) (pi w = 3/8 k_n root^2).
inline double jkr_break_energy(double k_n, double root, double r_eff) {
  const double p = r_eff * root;
  return 0.375 * k_n * root * root * p * std::cbrt(p) * (0.6 + 0.4 / std::cbrt(256.0));
}

/// The normal force of a response at the approach speed v_n (> 0 approaching): its magnitude
/// pushing the pair apart, never negative, and the part of it that is not the spring's.
struct NormalForce {
  double magnitude;       ///< max(0, elastic + damping_coeff v_n), N
  double nonconservative; ///< magnitude - elastic, N: the dashpot's, or -elastic when floored
};

/// [Schwager & Poeschel 2008]: a contact never pulls; once the dashpot outweighs the spring the
/// force is zero, and the spring's energy leaves through the non-conservative part.
inline NormalForce floored_normal_force(const NormalResponse& r, double v_n) {
  const double dashpot = r.damping_coeff * v_n;
  const double f = r.elastic + dashpot;
  return f > 0.0 ? NormalForce{f, dashpot} : NormalForce{0.0, -r.elastic};
}

} // namespace fluidem::kernels
