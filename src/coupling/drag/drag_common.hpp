// Shared pieces of the drag closures: the input struct, the Reynolds numbers, the single-sphere
// drag coefficient of Schiller-Naumann [Deen07 eq. 4; Hoomans96 eq. 38; Zhu07 Table 3], the
// set-up checks, and the conversions between the three ways of stating the same drag.
//
// Convention (one for every closure in this folder) [Deen07 eq. 1-2; Hoomans96 eq. 43]:
//   * beta, kg m^-3 s^-1: force per unit volume of MIXTURE exerted by the gas on the particles
//     = beta (u - v); it appears as -beta (u - v) in the gas momentum equation next to
//     -eps grad p (Model A, pressure-gradient force kept separate).
//   * force on one particle (the drag part only; the pressure-gradient force -V_p grad p is added
//     separately by the coupling) [Deen07 eq. 1]:
//         F_p = V_p beta / (1 - eps) (u - v) = V_p K (u - v),   K = beta / (1 - eps).
//     Every closure computes K (finite at eps = 1) and beta = (1 - eps) K, so the single-particle
//     limit needs no 0/0.
//   * dimensionless drag, normalised by the Stokes drag of one sphere at the SUPERFICIAL slip
//     velocity eps |u - v| (van der Hoef et al. 2005, Beetstra et al. 2007):
//         F = |F_p| / (3 pi mu d eps |u - v|) = K d^2 / (18 mu eps)
//           = beta d^2 / (18 mu eps (1 - eps)).
//     A single sphere in Stokes flow has F = 1. Beetstra's F is exactly this F; the F of
//     Koch-Hill / Hill-Koch-Ladd (beta = 18 mu eps^2 (1-eps) F_KH / d^2) is F = eps F_KH.
//   * Re_p = eps rho |u - v| d / mu, the particle Reynolds number on the superficial slip
//     velocity [Deen07 below eq. 4; Hoomans96 eq. 39, 47].
//
// Inputs are SI: eps (-), d (m), mu (Pa s), rho (kg/m3), slip = |u - v| interstitial (m/s).
// Validation (`validate_drag_input`) belongs to set-up, never to the per-particle loop: the
// closures themselves do not check, they are pure arithmetic.
#pragma once
#include <cmath>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace fluidem::coupling::drag {

/// What a closure needs to know about one particle and the gas around it.
struct DragInput {
  double eps = 1.0;    ///< gas volume fraction (porosity) at the particle, in (0, 1]
  double d = 0.0;      ///< particle diameter, m
  double mu = 0.0;     ///< gas dynamic viscosity, Pa s
  double rho = 0.0;    ///< gas density, kg/m3
  double slip = 0.0;   ///< |u - v|, interstitial gas velocity minus particle velocity, m/s
  double d_mean = 0.0; ///< polydisperse closures only: Sauter mean diameter of the mixture, m
};

/// Re_p = eps rho |u - v| d / mu (superficial slip velocity).
inline double reynolds(const DragInput& in) {
  return in.eps * in.rho * in.slip * in.d / in.mu;
}

/// Schiller-Naumann, written as C_d Re so that Re -> 0 is finite (= 24):
///   C_d = 24/Re (1 + 0.15 Re^0.687) for Re < 1000, 0.44 for Re >= 1000
/// [Deen07 eq. 4; Hoomans96 eq. 38 (Rowe-Henwood); Zhu07 Table 3].
inline double cd_re_schiller_naumann(double re) {
  return re < 1000.0 ? 24.0 * (1.0 + 0.15 * std::pow(re, 0.687)) : 0.44 * re;
}

/// beta from K = beta / (1 - eps).
inline double beta_from_k(double k, double eps) {
  return (1.0 - eps) * k;
}

/// Magnitude of the drag force on one particle, N: V_p K |u - v| (d = the particle's diameter).
inline double particle_force_from_k(double k, const DragInput& in) {
  constexpr double pi = 3.14159265358979323846;
  return pi * in.d * in.d * in.d / 6.0 * k * in.slip;
}

/// F = F_p / (3 pi mu d eps |u - v|) = K d^2 / (18 mu eps).
inline double normalised_from_k(double k, const DragInput& in) {
  return k * in.d * in.d / (18.0 * in.mu * in.eps);
}

/// K = beta/(1 - eps) from F: the inverse of normalised_from_k.
inline double k_from_normalised(double f, const DragInput& in) {
  return 18.0 * in.mu * in.eps * f / (in.d * in.d);
}

/// Set-up check shared by all closures: throws InputError naming the bad quantity and the
/// closure. eps must be in (0, 1]; d, mu > 0; rho, slip >= 0; all finite.
inline void validate_drag_input(const DragInput& in, const std::string& closure,
                                bool needs_mean_diameter = false) {
  auto fail = [&](const std::string& what) {
    throw InputError("drag closure '" + closure + "': " + what);
  };
  auto num = [](double x) {
    std::ostringstream os;
    os << x; // %g-like, 6 significant digits
    return os.str();
  };
  if (!std::isfinite(in.eps) || !(in.eps > 0.0) || in.eps > 1.0)
    fail("gas volume fraction eps = " + num(in.eps) + " must be in (0, 1]");
  if (!std::isfinite(in.d) || !(in.d > 0.0))
    fail("particle diameter d = " + num(in.d) + " m must be > 0");
  if (!std::isfinite(in.mu) || !(in.mu > 0.0))
    fail("gas viscosity mu = " + num(in.mu) + " Pa s must be > 0");
  if (!std::isfinite(in.rho) || !(in.rho >= 0.0))
    fail("gas density rho = " + num(in.rho) + " kg/m3 must be >= 0");
  if (!std::isfinite(in.slip) || !(in.slip >= 0.0))
    fail("slip speed |u - v| = " + num(in.slip) + " m/s must be >= 0");
  if (needs_mean_diameter && (!std::isfinite(in.d_mean) || !(in.d_mean > 0.0)))
    fail("Sauter mean diameter d_mean = " + num(in.d_mean) + " m must be > 0");
}

} // namespace fluidem::coupling::drag
