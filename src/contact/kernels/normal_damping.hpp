// Calibration of the normal dashpots to a coefficient of restitution e (docs/contact.md):
// stateless, evaluated once per material pair by the ContactTable.
//
// The normal force never pulls: F_n = max(0, spring + dashpot), and a contact ends when it
// vanishes [Schwager & Poeschel 2008, Granular Matter 10]. The head-on impact of the linear
// spring-dashpot m x'' + eta x' + k x = 0 (zeta = eta / (2 sqrt(m k))) then rebounds with
//   e(zeta) = exp(-2 zeta g(zeta)),   g = arccos(zeta)/sqrt(1 - zeta^2)   (zeta < 1),
//                                     g = arccosh(zeta)/sqrt(zeta^2 - 1) (zeta > 1), g(1) = 1,
// after the force pulse t_c = 2 g(zeta) sqrt(m/k) [Schwager & Poeschel 2008]. e falls to 0 only
// as zeta grows without bound (e ~ 1/(4 zeta^2)): e = 0 cannot be calibrated.
// Hertz with Tsuji's damping [Chang08 eq. 2.22], scaled (below) to X'' + alpha X^{1/4} X' +
// X^{3/2} = 0: the change of variable X = (5/4)^{2/5} Y^{4/5} maps its phase portrait V(X)
// exactly onto that of the linear Y'' + 2 zeta Y' + Y = 0 with zeta = alpha / sqrt(5), and its
// force onto the linear one times dX/dY > 0 (Antypov & Elliott 2011, EPL 94:50004, for the impact
// that ends at X = 0; Feng 2026, arXiv:2603.27764, for any power law; docs/contact.md), so
// alpha(e) = sqrt(5) zeta(e) with the same zeta(e). This replaces the ODE solve that inverted
// e(alpha) at start-up; scaled_hertz_impact() still integrates the Hertz impact for the
// contact duration (which has no closed form), and the tests invert it to check alpha(e).
#pragma once
#include <cmath>
#include <stdexcept>
#include <string>

namespace fluidem::kernels {

struct HertzImpact {
  double restitution; ///< -X'(end)/X'(0)
  double duration;    ///< scaled duration T_c of the force pulse
  double max_overlap; ///< scaled maximum overlap X_max
};

/// g(zeta) above: the force pulse of the linear impact lasts 2 g(zeta) sqrt(m/k).
inline double half_pulse_factor(double zeta) {
  // With s = sqrt(|1 - zeta| / 2): arccos(zeta) = 2 asin(s), arccosh(zeta) = 2 asinh(s) and
  // sqrt(|1 - zeta^2|) = s sqrt(2 (1 + zeta)), so g = (asin(s)/s or asinh(s)/s) sqrt(2/(1 + zeta)):
  // no cancellation near zeta = 1, where 1 - zeta is exact.
  const double d = 1.0 - zeta;
  const double s = std::sqrt(0.5 * std::abs(d));
  const double ratio = s > 0.0 ? (d > 0.0 ? std::asin(s) : std::asinh(s)) / s : 1.0;
  return ratio * std::sqrt(2.0 / (1.0 + zeta));
}

/// Restitution e(zeta) of a head-on impact of the linear spring-dashpot with damping ratio
/// zeta >= 0 whose force never pulls.
inline double floored_restitution(double zeta) {
  return std::exp(-2.0 * zeta * half_pulse_factor(zeta));
}

/// The damping ratio zeta for which floored_restitution(zeta) = e, e in (0, 1]; zeta(1) = 0.
/// Throws std::invalid_argument for e outside (0, 1] (the ContactTable refuses e = 0 first).
inline double floored_damping_ratio(double e) {
  if (!(e > 0.0 && e <= 1.0))
    throw std::invalid_argument("floored_damping_ratio: e = " + std::to_string(e) +
                                " is outside (0, 1]");
  if (e == 1.0) return 0.0;
  // -ln e = 2 zeta g(zeta), which grows monotonically from 0 (zeta = 0) without bound: bracket,
  // then bisect to the last bit (the result does not depend on the platform's rounding of a
  // Newton step; ~60-1100 evaluations, once per material pair at start-up).
  const double target = -std::log(e);
  auto h = [](double z) { return 2.0 * z * half_pulse_factor(z); };
  double lo = 0.0, hi = 1.0;
  while (h(hi) < target) lo = hi, hi *= 2.0;
  for (int it = 0; it < 2000; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (h(mid) < target ? lo : hi) = mid;
  }
  return hi;
}

/// Linear spring-dashpot: the factor f = eta_n / sqrt(m* k_n) = 2 zeta(e).
inline double linear_damping_factor(double e) {
  return 2.0 * floored_damping_ratio(e);
}

/// Tsuji's alpha = sqrt(5) zeta(e) for the Hertz spring; alpha(1) = 0.
inline double hertz_damping_alpha(double e) {
  return std::sqrt(5.0) * floored_damping_ratio(e);
}

/// Duration of the force pulse of a linear impact with damping factor f = 2 zeta, s.
inline double linear_contact_duration(double m_eff, double k, double damping_factor) {
  return 2.0 * half_pulse_factor(0.5 * damping_factor) * std::sqrt(m_eff / k);
}

/// The scaled damped Hertz impact  X'' + alpha X^{1/4} X' + X^{3/2} = 0, X(0) = 0, X'(0) = 1
/// (x = v tau X, t = tau T, tau = (K/m)^{-2/5} v^{-1/5}), integrated until its force
/// X^{3/2} + alpha X^{1/4} X' vanishes (undamped: until X returns to 0). RK4 with steps of
/// 1.5e-4 (T_c ~ 2-3.2), graded as 1.5e-4 T^{3/4} below T = 1: the solution goes as
/// T^{5/4} there (X^{1/4}), whose derivatives would otherwise make the first steps' error
/// dominate (1e-6 in e with even steps, 1e-9 graded); the end is found inside its step by
/// bisecting the length of one RK4 step. ~4e4 steps, once per material pair at start-up.
inline HertzImpact scaled_hertz_impact(double alpha) {
  const double h = 1.5e-4;
  // X^{1/4} and X^{3/2} use max(X, 0) so that the right-hand side stays defined past the end.
  auto force = [alpha](double x, double v) {
    const double xp = x > 0.0 ? x : 0.0;
    return alpha * std::sqrt(std::sqrt(xp)) * v + xp * std::sqrt(xp);
  };
  struct State {
    double x, v;
  };
  auto step = [&force](State y, double s) {
    const double k1x = y.v, k1v = -force(y.x, y.v);
    const double k2x = y.v + 0.5 * s * k1v, k2v = -force(y.x + 0.5 * s * k1x, y.v + 0.5 * s * k1v);
    const double k3x = y.v + 0.5 * s * k2v, k3v = -force(y.x + 0.5 * s * k2x, y.v + 0.5 * s * k2v);
    const double k4x = y.v + s * k3v, k4v = -force(y.x + s * k3x, y.v + s * k3v);
    return State{y.x + s / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x),
                 y.v + s / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v)};
  };
  // Positive while the contact lasts.
  auto lasting = [&](State y) { return alpha > 0.0 ? force(y.x, y.v) > 0.0 : y.x > 0.0; };
  State y{0.0, 1.0};
  double t = 0.0, xmax = 0.0;
  for (int k = 0; k < 10000000; ++k) {
    const double s = t < 1.0 ? std::max(h * std::pow(t, 0.75), 1e-12) : h;
    const State next = step(y, s);
    if (!lasting(next)) {
      double lo = 0.0, hi = s; // the end lies in (lo, hi] of this step
      for (int it = 0; it < 64; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        (lasting(step(y, mid)) ? lo : hi) = mid;
      }
      return {-step(y, hi).v, t + hi, xmax};
    }
    y = next, t += s;
    if (y.x > xmax) xmax = y.x;
  }
  return {0.0, t, xmax}; // not reached: every impact ends within T ~ 4
}

namespace detail {
inline double time_scale(double m_eff, double k_hertz, double speed) {
  return std::pow(m_eff / k_hertz, 0.4) * std::pow(speed, -0.2);
}
} // namespace detail

/// Duration of the force pulse of a (damped) Hertz impact, s: T_c(alpha) (m/K)^{2/5} v^{-1/5}.
inline double hertz_contact_duration(double m_eff, double k_hertz, double alpha, double speed) {
  return scaled_hertz_impact(alpha).duration * detail::time_scale(m_eff, k_hertz, speed);
}

/// Maximum overlap of a (damped) Hertz impact, m: v X_max(alpha) (m/K)^{2/5} v^{-1/5}.
inline double hertz_max_overlap(double m_eff, double k_hertz, double alpha, double speed) {
  return speed * scaled_hertz_impact(alpha).max_overlap * detail::time_scale(m_eff, k_hertz, speed);
}

} // namespace fluidem::kernels
