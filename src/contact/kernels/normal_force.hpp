// Normal contact force kernels: stateless, inlined into the pair loop, tested one by one.
//
// Linear spring-dashpot [Deen07 eq. 24-27]:
//   F_n = -k_n delta n - eta_n v_n,   eta_n = -2 ln(e) sqrt(m* k_n) / sqrt(pi^2 + ln^2 e)
// Hertz with Tsuji's damping [Zhu07 Table 1; Chang08 eq. 2.15, 2.22]:
//   F_n = -K delta^{3/2} n - alpha sqrt(m* K) delta^{1/4} v_n,   K = 4/3 E* sqrt(R*)
//   where alpha(e) is calibrated once per run (contact/hertz_damping.hpp) so that a head-on
//   impact rebounds with exactly the requested e, independent of the impact velocity.
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
  double sqrt_overlap; ///< delta^{1/2} (Hertz; 0 for the linear spring, which does not need it)
};

/// Damping factor -2 ln e / sqrt(pi^2 + ln^2 e) (2 for e = 0) [Deen07 eq. 27, 30].
inline double restitution_damping_factor(double e) {
  if (e <= 0.0) return 2.0;
  const double l = std::log(e);
  return -2.0 * l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

/// Linear spring [Deen07 eq. 24, 27]. `damping_factor` from restitution_damping_factor().
inline NormalResponse linear_normal(double k, double damping_factor, double m_eff, double delta) {
  const double scale = std::sqrt(m_eff * k);
  return {k * delta, damping_factor * scale, k, 0.5 * k * delta * delta, scale, 0.0};
}

/// Hertz spring with Tsuji damping [Chang08 eq. 2.15, 2.22]. `k_hertz` = 4/3 E* sqrt(R*).
inline NormalResponse hertz_normal(double k_hertz, double alpha, double m_eff, double delta) {
  const double sd = std::sqrt(delta);
  const double qd = std::sqrt(sd); // delta^{1/4}
  const double elastic = k_hertz * delta * sd;
  const double scale = std::sqrt(m_eff * k_hertz) * qd;
  return {elastic, alpha * scale, 1.5 * k_hertz * sd, 0.4 * elastic * delta, scale, sd};
}

} // namespace fluidem::kernels
