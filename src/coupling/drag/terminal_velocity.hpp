// Terminal velocity of one sphere falling in still fluid, with the Schiller-Naumann drag
// coefficient [Deen07 eq. 4; Hoomans96 eq. 38; Zhu07 Table 3]:
//
//   C_d = 24/Re (1 + 0.15 Re^0.687)  (Re < 1000),   0.44  (Re >= 1000),   Re = rho v d / mu
//   force balance: (rho_p - rho) g pi d^3 / 6 = C_d rho v^2 / 2 * pi d^2 / 4
//              <=> 3 pi mu d v (C_d Re / 24) = (rho_p - rho) g pi d^3 / 6
//
// Solved by bisection on v in [0, v_Stokes]: the residual 3 pi mu d v (C_d Re)/24 - weight is
// < 0 at v = 0 and >= 0 at v_Stokes = (rho_p - rho) g d^2 / (18 mu) (C_d Re / 24 >= 1), and it
// increases with v (also across Re = 1000, where C_d Re jumps up from 438.4 to 440), so the
// bracket always holds the root. Bisection halves until the bracket is one ulp wide (< 1100
// steps, ~60 in practice). If the balance falls inside the small jump at Re = 1000 there is no
// exact root and the result is the velocity at Re = 1000 (residual not zero; `converged`
// reports whether |residual| <= 1e-12 weight).
//
// Closed forms used by the tests: Stokes v = (rho_p - rho) g d^2 / (18 mu) (Re -> 0); Newton
// v = sqrt(4 (rho_p - rho) g d / (3 * 0.44 rho)) (Re >= 1000).
#pragma once
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "coupling/drag/drag_common.hpp"

namespace fluidem::coupling::drag {

struct TerminalVelocityInput {
  double d = 0.0;     ///< particle diameter, m
  double rho_p = 0.0; ///< particle density, kg/m3
  double rho = 0.0;   ///< fluid density, kg/m3 (must be < rho_p: the particle sinks)
  double mu = 0.0;    ///< fluid viscosity, Pa s
  double g = 9.81;    ///< magnitude of gravity, m/s2
};

struct TerminalVelocity {
  double velocity = 0.0; ///< settling speed, m/s
  double reynolds = 0.0; ///< rho v d / mu
  double cd = 0.0;       ///< Schiller-Naumann C_d at that Re
  double residual = 0.0; ///< drag - (weight - buoyancy), N
  double weight = 0.0;   ///< (rho_p - rho) g V, N
  bool converged = false;
};

/// InputError naming the quantity if d, mu, g <= 0, rho < 0 or rho_p <= rho.
inline void validate(const TerminalVelocityInput& in) {
  auto fail = [](const std::string& what) { throw InputError("terminal velocity: " + what); };
  if (!std::isfinite(in.d) || !(in.d > 0.0)) fail("particle diameter d must be > 0");
  if (!std::isfinite(in.mu) || !(in.mu > 0.0)) fail("fluid viscosity mu must be > 0");
  if (!std::isfinite(in.rho) || !(in.rho >= 0.0)) fail("fluid density rho must be >= 0");
  if (!std::isfinite(in.g) || !(in.g > 0.0)) fail("gravity g must be > 0");
  if (!std::isfinite(in.rho_p) || !(in.rho_p > in.rho))
    fail("particle density rho_p must exceed the fluid density rho (the particle must sink)");
}

/// Net weight (rho_p - rho) g pi d^3 / 6, N.
inline double net_weight(const TerminalVelocityInput& in) {
  constexpr double pi = 3.14159265358979323846;
  return (in.rho_p - in.rho) * in.g * pi * in.d * in.d * in.d / 6.0;
}

/// Schiller-Naumann drag on the sphere at speed v, N.
inline double schiller_naumann_drag(const TerminalVelocityInput& in, double v) {
  constexpr double pi = 3.14159265358979323846;
  const double re = in.rho * v * in.d / in.mu;
  return 3.0 * pi * in.mu * in.d * v * cd_re_schiller_naumann(re) / 24.0;
}

/// Solves the force balance (validates first).
inline TerminalVelocity terminal_velocity(const TerminalVelocityInput& in) {
  validate(in);
  const double w = net_weight(in);
  double lo = 0.0;
  double hi = (in.rho_p - in.rho) * in.g * in.d * in.d / (18.0 * in.mu); // Stokes: drag >= w
  for (int it = 0; it < 1100; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break; // bracket is one ulp wide
    if (schiller_naumann_drag(in, mid) < w)
      lo = mid;
    else
      hi = mid;
  }
  // The end whose residual is smaller.
  const double r_lo = schiller_naumann_drag(in, lo) - w;
  const double r_hi = schiller_naumann_drag(in, hi) - w;
  TerminalVelocity out;
  out.velocity = std::abs(r_lo) < std::abs(r_hi) ? lo : hi;
  out.residual = std::abs(r_lo) < std::abs(r_hi) ? r_lo : r_hi;
  out.weight = w;
  out.reynolds = in.rho * out.velocity * in.d / in.mu;
  out.cd = out.reynolds > 0.0 ? cd_re_schiller_naumann(out.reynolds) / out.reynolds : 0.0;
  out.converged = std::abs(out.residual) <= 1e-12 * w;
  return out;
}

} // namespace fluidem::coupling::drag
