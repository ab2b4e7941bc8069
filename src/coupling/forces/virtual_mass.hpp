// The virtual (added) mass force [Zhu07 Table 3; Maxey & Riley 1983, Phys. Fluids 26:883;
// Odar & Hamilton 1964, J. Fluid Mech. 18:302; Odar 1966, J. Fluid Mech. 25:591]:
//
//   F_vm = C_vm rho_f V (Du/Dt - dv/dt),   V = pi d^3/6,   m_a = C_vm rho_f V (added mass)
//
// Du/Dt the fluid's acceleration at the particle (material derivative, Maxey & Riley; Zhu07
// writes u-dot), dv/dt the particle's. C_vm = 1/2 for a sphere in an inviscid fluid (potential
// flow, any Re; exact for Re_p -> 0 as well, Maxey & Riley).
// [Zhu07 Table 3] writes F = C_vm rho_f V (u. - v.)/2 with Odar's C_vm = 2.1 - 0.132/(0.12 +
// A_c^2); the original [Odar & Hamilton 1964, eq. for Delta_A] writes the added-mass term as
// Delta_A rho_f V du/dt with
//   Delta_A = 1.05 - 0.066/(A_c^2 + 0.12),   A_c = |w|^2/(d |dw/dt|)   (acceleration number)
// (and the history term as Delta_H a^2 sqrt(pi rho_f mu) int ..., Delta_H = 2.88 + 3.12/(A_c +
// 1)^3, = 6 (Basset) at A_c = 0): the same coefficient on rho_f V, Zhu07's C_vm/2 = Delta_A.
// Limits: A_c -> 0 (large acceleration, small slip) Delta_A -> 1.05 - 0.55 = 0.5 (the inviscid
// 1/2); A_c -> infinity Delta_A -> 1.05.
// Validity: Odar & Hamilton fitted a sphere oscillating in a liquid, Re_p = |w| d/nu < 62 (as
// quoted by Clift, Grace & Weber 1978 ch. 11; the original was not at hand); Odar (1966) tested
// the equation on further accelerating-sphere data. Outside that range use C_vm = 1/2.
// w = 0 with dw/dt != 0: A_c = 0, Delta_A = 1/2. dw/dt = 0: A_c is infinite, Delta_A = 1.05
// (the force C_vm rho_f V (Du/Dt - dv/dt) is then whatever the accelerations give); no 0/0.
#pragma once
#include <cmath>
#include <numbers>

#include "core/vec3.hpp"

namespace fluidem::coupling::forces {

/// The inviscid sphere's added-mass coefficient (on rho_f V).
inline constexpr double c_vm_sphere = 0.5;

/// V = pi d^3/6, m^3.
inline double sphere_volume(double d) {
  return std::numbers::pi * d * d * d / 6.0;
}

/// m_a = C_vm rho_f V, kg.
inline double added_mass(double c_vm, double rho_f, double d) {
  return c_vm * rho_f * sphere_volume(d);
}

/// F_vm = C_vm rho_f V (Du/Dt - dv/dt), N.
inline Vec3 virtual_mass_force(double c_vm, double rho_f, double d, const Vec3& fluid_accel,
                               const Vec3& particle_accel) {
  return added_mass(c_vm, rho_f, d) * (fluid_accel - particle_accel);
}

/// A_c = |w|^2/(d |dw/dt|) [Odar & Hamilton 1964]; +infinity when dw/dt = 0.
inline double acceleration_number(const Vec3& w, const Vec3& dw_dt, double d) {
  const double a = norm(dw_dt);
  if (a == 0.0) return INFINITY;
  return norm2(w) / (d * a);
}

/// Delta_A(A_c) = 1.05 - 0.066/(A_c^2 + 0.12) [Odar & Hamilton 1964] (= Zhu07's C_vm/2), the
/// coefficient on rho_f V. A_c = +infinity gives 1.05.
inline double odar_hamilton_added_mass_coefficient(double a_c) {
  if (std::isinf(a_c)) return 1.05;
  return 1.05 - 0.066 / (a_c * a_c + 0.12);
}

/// Delta_A from the slip and its rate, without forming A_c: 1.05 - 0.066 (d a)^2/(0.12 (d a)^2 +
/// |w|^4), a = |dw/dt| (finite for w = 0: 1/2; for dw/dt = 0: 1.05).
inline double odar_hamilton_added_mass_coefficient(const Vec3& w, const Vec3& dw_dt, double d) {
  const double da = d * norm(dw_dt);
  if (da == 0.0) return 1.05;
  const double w2 = norm2(w);
  return 1.05 - 0.066 * da * da / (0.12 * da * da + w2 * w2);
}

/// Delta_H/6 = (2.88 + 3.12/(A_c + 1)^3)/6 [Odar & Hamilton 1964]: the factor on the Basset
/// prefactor C_B (basset_history.hpp) of the same fit; 1 at A_c = 0, 0.48 at A_c = infinity.
inline double odar_hamilton_history_factor(double a_c) {
  if (std::isinf(a_c)) return 0.48;
  const double p = a_c + 1.0;
  return (2.88 + 3.12 / (p * p * p)) / 6.0;
}

} // namespace fluidem::coupling::forces
