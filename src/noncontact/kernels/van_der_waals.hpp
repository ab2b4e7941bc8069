// van der Waals attraction between two spheres, or a sphere and a plane wall, in the Hamaker
// form of [Zhu07 Table 2] (Hamaker 1937; Israelachvili 1991), written for unequal spheres with
// the effective radius R* = R_i R_j / (R_i + R_j) (equal spheres R* = d/4: A d / (24 h^2) as in
// the table; a plane wall R* = R_i):
//   F(h) = A R* / (6 h^2)                 (attractive), h = max(gap, h0),
// h0 the minimum separation ("cut-off" distance, 0.165-1 nm [Zhu07 §2.2]) that removes the
// singularity at contact: at gap <= h0, overlapping pairs included, the force stays A R*/(6 h0^2).
// With a Hertz contact this is the DMT model [Zhu07 §2.2; Derjaguin, Muller & Toporov 1975]: the
// Hertz force plus a constant adhesion whose pull-off force A R*/(6 h0^2) = 2 pi w R* is DMT's
// with the work of adhesion w = A / (12 pi h0^2).
// Beyond the interaction range h_c (a case key) the force is zero. The potential is shifted so
// that it is continuous there (U(h_c) = 0), which keeps the energy balance exact up to the
// integration error:
//   U(h) = -A R*/6 (1/h - 1/h_c)                      h0 <= h < h_c
//   U(h) = U(h0) - F(h0) (h0 - h)                     h < h0 (the constant force's potential)
// Valid for h << R* (the Derjaguin limit the table's expression rests on) and without
// retardation (h below a few nm [Zhu07 §2.2]); beyond, the force is overestimated.
#pragma once
#include <algorithm>

#include "noncontact/kernels/pair_force.hpp"

namespace fluidem::kernels {

/// van der Waals attraction at surface gap `gap` (m, negative when overlapping) for Hamaker
/// constant `hamaker` (J), effective radius `r_eff` (m), minimum separation `h0` (m) and range
/// `h_c` (m, > h0).
inline PairForce van_der_waals(double hamaker, double r_eff, double h0, double h_c, double gap) {
  if (gap >= h_c) return {};
  const double c = hamaker * r_eff / 6.0;
  const double h = std::max(gap, h0);
  const double f = c / (h * h);
  double u = -c * (1.0 / h - 1.0 / h_c);
  if (gap < h0) u -= f * (h0 - gap);
  // dF/dgap of the attraction: -2 F / h outside h0, 0 inside
  const double stiffness = gap > h0 ? 2.0 * f / h : 0.0;
  return {-f, u, stiffness};
}

/// The largest |dF/dgap| of the van der Waals attraction, N/m (at h0): the time-step rule's
/// stiffness of this force.
inline double van_der_waals_stiffness(double hamaker, double r_eff, double h0) {
  return hamaker * r_eff / (3.0 * h0 * h0 * h0);
}

} // namespace fluidem::kernels
