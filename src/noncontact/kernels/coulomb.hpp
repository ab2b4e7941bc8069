// Coulomb force between two point charges (charged spheres: the charge acts from the centre
// [Zhu07 §2.2, Table 2 "Coulomb force"]), in a medium of relative permittivity eps_r:
//   F(r) = q_i q_j / (4 pi eps0 eps_r r^2)     (r the distance of the centres; > 0 repels)
// truncated at the cut-off r_c with the shifted force (Levitt et al. 1995; Fennell & Gezelter
// 2006, "shifted force" without damping), which makes both the force and the potential vanish
// continuously at r_c, so that a pair crossing the cut-off neither jumps in force nor in energy:
//   F_sf(r) = k (1/r^2 - 1/r_c^2),   U_sf(r) = k (1/r - 1/r_c + (r - r_c)/r_c^2),   k = q_i q_j /
//   (4 pi eps0 eps_r),   r < r_c.
// Why a cut-off, not an Ewald/PPPM sum: see docs/noncontact.md (the error of the cut-off is
// measured there for bipolar and for net-charged beds).
// A charge q at distance z from a grounded conducting plane is attracted by its image -q at
// distance 2 z (Jackson, Classical Electrodynamics §2.1); the image of another charge q_j acts on
// q_i as the charge -q_j at the mirror point. The energy of the system is half the interaction
// of the real charges with the images: U_self = -k q^2 / (2 (2 z)) (k = 1/(4 pi eps0 eps_r)) and,
// for a pair, U_ij = -k q_i q_j / |x_i - x_j'| once.
#pragma once
#include <numbers>

#include "noncontact/kernels/pair_force.hpp"

namespace fluidem::kernels {

/// Vacuum permittivity, F/m (CODATA 2018).
inline constexpr double kVacuumPermittivity = 8.8541878128e-12;

/// q_i q_j / (4 pi eps0 eps_r), N m^2.
inline double coulomb_constant(double qi, double qj, double eps_r) {
  return qi * qj / (4.0 * std::numbers::pi * kVacuumPermittivity * eps_r);
}

/// The shifted Coulomb force at centre distance r (< r_c) for k = coulomb_constant(), with its
/// shifted potential. `force` > 0 repels.
inline PairForce coulomb_shifted(double k, double r, double r_c) {
  if (r >= r_c) return {};
  const double inv_r = 1.0 / r, inv_rc = 1.0 / r_c;
  const double f = k * (inv_r * inv_r - inv_rc * inv_rc);
  const double u = k * (inv_r - inv_rc + (r - r_c) * inv_rc * inv_rc);
  const double stiffness = 2.0 * (k < 0.0 ? -k : k) * inv_r * inv_r * inv_r;
  return {f, u, stiffness};
}

} // namespace fluidem::kernels
