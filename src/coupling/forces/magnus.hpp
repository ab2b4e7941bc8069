// The Magnus (spin) lift on a sphere rotating relative to the fluid [Zhu07 Table 3]:
//
//   Rubinow & Keller (1961, J. Fluid Mech. 11:447), Re_p << 1:
//     F_M = pi/8 d^3 rho_f (Omega_rel x w),   Omega_rel = Omega/2 - omega_p
//   (Omega = curl u, Omega/2 the local fluid rotation, omega_p the particle's spin, w = u - v);
//   zero when the particle turns with the fluid.
//   Finite Re [Crowe, Sommerfeld & Tsuji 1998 §4.6; Oesterle & Bui Dinh 1998, Exp. Fluids
//   25:16]:
//     F_M = 1/2 rho_f (pi d^2/4) C_L |w| (Omega_rel x w)/|Omega_rel|
//     C_L = 0.45 + (Re_r/Re_p - 0.45) exp(-0.05684 Re_r^0.4 Re_p^0.3)
//     Re_p = rho_f |w| d/mu,  Re_r = rho_f d^2 |Omega_rel|/mu
//   Low Re: C_L -> Re_r/Re_p = d |Omega_rel|/|w|, and F_M -> pi/8 d^3 rho_f (Omega_rel x w),
//   Rubinow & Keller exactly (tested). Validity of C_L: Oesterle & Bui Dinh's experiments,
//   10 < Re_p < 140; at Re_p -> 0 it joins Rubinow & Keller. (C_L's constants as quoted by
//   Crowe, Sommerfeld & Tsuji; the original paper was not at hand to check them.)
// Implemented with C_L |w|/|Omega_rel| = 0.45 |w|/|Omega_rel| + (d - 0.45 |w|/|Omega_rel|) e
// (e the exponential): no 0/0 at w = 0 or Omega_rel = 0, where F_M = 0 (returned first).
#pragma once
#include <cmath>
#include <numbers>

#include "core/vec3.hpp"

namespace fluidem::coupling::forces {

/// Omega_rel = Omega/2 - omega_p, s^-1.
inline Vec3 relative_spin(const Vec3& vorticity, const Vec3& omega_p) {
  return 0.5 * vorticity - omega_p;
}

/// Rubinow & Keller: pi/8 d^3 rho_f (Omega_rel x w), N.
inline Vec3 magnus_rubinow_keller(const Vec3& w, const Vec3& vorticity, const Vec3& omega_p,
                                  double d, double rho_f) {
  return (std::numbers::pi / 8.0 * d * d * d * rho_f) * cross(relative_spin(vorticity, omega_p), w);
}

/// Oesterle & Bui Dinh's C_L(Re_p, Re_r), Re_p > 0.
inline double magnus_lift_coefficient(double re_p, double re_r) {
  return 0.45 +
         (re_r / re_p - 0.45) * std::exp(-0.05684 * std::pow(re_r, 0.4) * std::pow(re_p, 0.3));
}

/// 1/2 rho_f (pi d^2/4) C_L |w| (Omega_rel x w)/|Omega_rel|, N.
inline Vec3 magnus_oesterle(const Vec3& w, const Vec3& vorticity, const Vec3& omega_p, double d,
                            double rho_f, double mu) {
  const Vec3 om = relative_spin(vorticity, omega_p);
  const double om_mag = norm(om);
  const double slip = norm(w);
  if (om_mag == 0.0 || slip == 0.0) return {};
  const double re_p = rho_f * slip * d / mu;
  const double re_r = rho_f * d * d * om_mag / mu;
  const double e = std::exp(-0.05684 * std::pow(re_r, 0.4) * std::pow(re_p, 0.3));
  const double ratio = slip / om_mag;                            // |w|/|Omega_rel|
  const double cl_ratio = 0.45 * ratio + (d - 0.45 * ratio) * e; // C_L |w|/|Omega_rel|
  return (0.125 * std::numbers::pi * rho_f * d * d * cl_ratio) * cross(om, w);
}

} // namespace fluidem::coupling::forces
