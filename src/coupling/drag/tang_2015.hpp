// Tang, Peters, Kuipers, Kriebitzsch & van der Hoef (2015) drag from immersed-boundary simulations
// of flow past static random arrays of monodisperse spheres [Tang et al., AIChE J. 61 (2015)
// 688-698, eq. 21 (the equation number as cited by MFiX model/drag_gs.f, subroutine DRAG_TPKKV:
// "Eq. (21) of Tang, et al. AIChEJ 61(2) 2015"; the paper's text was not available here)]:
//
//   F(phi, Re) = 10 phi / (1 - phi)^2 + (1 - phi)^2 (1 + 1.5 sqrt(phi))
//              + [ 0.11 phi (1 + phi) - 0.00456 / (1 - phi)^4
//                  + (0.169 (1 - phi) + 0.0644 / (1 - phi)^4) Re^-0.343 ] Re
//   Re = (1 - phi) rho |u - v| d / mu                     (superficial: this folder's Re_p)
//   beta = 18 mu eps phi F / d^2                          (MFiX: F_STOKES = 18 mu eps / d^2,
//                                                          "like BVK"; F_gs = DgA eps_s, Model A)
// The Stokes part is Beetstra's (van der Hoef 2005); F is normalised like Beetstra's F, i.e.
// drag without the pressure-gradient force over 3 pi mu d eps |u - v|: this folder's F exactly.
// MFiX writes the Re^-0.343 term as (0.169 eps + 0.0644/eps^4) Re^0.657: the same expression.
//
// In this folder's convention: K = beta/(1 - eps) = 18 mu eps F / d^2. Re = 0 is finite (the
// Re^0.657 term is evaluated as such, no Re^-0.343 overflow).
//
// Validity: the IBM data of the paper (moderate phi and Re up to about 1000; ranges not checked
// against the paper's text). Outside it the -0.00456 Re/(1-phi)^4 term takes over: at Re_p of a
// few thousand and eps below ~0.5 beta falls as the solids fraction rises (monotonicity is tested
// only up to Re_p = 1000), and at phi = 0 F = 1 + 0.2334 Re^0.657 - 0.00456 Re turns negative
// near Re = 1e5. Single-particle
// limit: phi = 0 gives F = 1 + 0.2334 Re^0.657 - 0.00456 Re -> 1 (Stokes) as Re -> 0 (not
// Schiller-Naumann at finite Re).
#pragma once
#include <cmath>

#include "coupling/drag/drag_common.hpp"

namespace fluidem::coupling::drag {

struct Tang2015 {
  static constexpr const char* name = "tang_2015";
  static constexpr bool needs_mean_diameter = false;
  static void validate(const DragInput& in) { validate_drag_input(in, name); }

  /// Tang's F(phi, Re) on the superficial Re (this folder's F).
  static double f(double eps, double re) {
    const double phi = 1.0 - eps;
    const double e2 = eps * eps;
    const double inv_e4 = 1.0 / (e2 * e2);
    return 10.0 * phi / e2 + e2 * (1.0 + 1.5 * std::sqrt(phi)) +
           (0.11 * phi * (1.0 + phi) - 0.00456 * inv_e4) * re +
           (0.169 * eps + 0.0644 * inv_e4) * std::pow(re, 1.0 - 0.343);
  }
  static double k(const DragInput& in) {
    return 18.0 * in.mu * in.eps * f(in.eps, reynolds(in)) / (in.d * in.d);
  }
  static double beta(const DragInput& in) { return beta_from_k(k(in), in.eps); }
};

} // namespace fluidem::coupling::drag
