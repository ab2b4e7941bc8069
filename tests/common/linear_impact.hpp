// The head-on impact of the linear spring-dashpot whose force never pulls, from its explicit
// solution (independent of contact/kernels/normal_damping.hpp's closed form): with
// w0 = sqrt(k/m*), damping ratio zeta < 1, wd = w0 sqrt(1 - zeta^2) and impact speed v,
//   x(t) = v/wd exp(-zeta w0 t) sin(wd t),  x'(t) = v exp(-zeta w0 t) (cos wd t - zeta w0/wd sin wd
//   t),
// the force k x + 2 zeta sqrt(m* k) x' starts positive and the contact ends where it first
// vanishes [Schwager & Poeschel 2008, Granular Matter 10:465]; the rebound is e = -x'(t_c)/v.
// Both found by bisection here (the force on its first half period; zeta from e(zeta), which
// falls monotonically).
#pragma once
#include <cmath>
#include <numbers>

namespace fluidem::test {

struct LinearImpact {
  double duration;    ///< of the force pulse, s
  double restitution; ///< -x'(t_c)/v
};

/// The impact with damping ratio zeta in [0, 1/sqrt(2)) (e > 0.044: the force then vanishes in
/// the first half period).
inline LinearImpact linear_impact(double m_eff, double k, double zeta) {
  const double w0 = std::sqrt(k / m_eff), wd = w0 * std::sqrt(1.0 - zeta * zeta);
  auto x = [&](double t) { return std::exp(-zeta * w0 * t) * std::sin(wd * t) / wd; };
  auto v = [&](double t) {
    return std::exp(-zeta * w0 * t) * (std::cos(wd * t) - zeta * w0 / wd * std::sin(wd * t));
  };
  auto force = [&](double t) { return k * x(t) + 2.0 * zeta * std::sqrt(m_eff * k) * v(t); };
  double lo = 0.5 * std::numbers::pi / wd, hi = std::numbers::pi / wd; // F(lo) > 0 >= F(hi)
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (force(mid) > 0.0 ? lo : hi) = mid;
  }
  return {hi, -v(hi)};
}

/// The impact whose rebound is e (e in [0.05, 1]).
inline LinearImpact linear_impact_for_restitution(double m_eff, double k, double e) {
  double lo = 0.0, hi = 0.69;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (linear_impact(m_eff, k, mid).restitution > e ? lo : hi) = mid;
  }
  return linear_impact(m_eff, k, lo);
}

} // namespace fluidem::test
