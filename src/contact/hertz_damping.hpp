// Calibration of Tsuji's Hertzian damping [Chang08 eq. 2.22, Fig. 2.7].
// The head-on impact  m x'' + alpha sqrt(m K) x^{1/4} x' + K x^{3/2} = 0  scales to
//   X'' + alpha X^{1/4} X' + X^{3/2} = 0,  X(0) = 0, X'(0) = 1
// with x = v tau_s X, t = tau_s T, tau_s = (K/m)^{-2/5} v^{-1/5}, so the restitution depends on
// alpha only. We integrate that equation (RK4, fine step) and invert e(alpha) by bisection,
// replacing the digitised curve of Tsuji et al. (1992) with its exact counterpart.
#pragma once

namespace fluidem {

struct HertzImpact {
  double restitution; ///< -X'(end)/X'(0)
  double duration;    ///< scaled contact duration T_c
  double max_overlap; ///< scaled maximum overlap X_max
};

/// Solve the scaled damped Hertz impact for a given alpha >= 0.
HertzImpact scaled_hertz_impact(double alpha);

/// alpha such that the scaled impact rebounds with restitution e in (0, 1]; alpha(1) = 0.
/// Results are cached per e. e = 0 is rejected by the caller (Hertz needs e > 0).
double hertz_damping_alpha(double e);

/// Duration of a (damped) Hertz impact, s: T_c(alpha) (m/K)^{2/5} v^{-1/5}.
double hertz_contact_duration(double m_eff, double k_hertz, double alpha, double speed);

/// Maximum overlap of a (damped) Hertz impact, m: v X_max(alpha) (m/K)^{2/5} v^{-1/5}.
double hertz_max_overlap(double m_eff, double k_hertz, double alpha, double speed);

} // namespace fluidem
