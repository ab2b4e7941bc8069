// Syamlal & O'Brien drag, as MFiX implements it (its default closure) [MFiX model/drag_gs.f,
// subroutine DRAG_SYAM_OBRIEN (MFiX 21.3.2), citing Syamlal & O'Brien, Int. J. Multiphase Flow 14
// (1988) 473; MFiX Theory Guide, Syamlal, Rogers & O'Brien 1993, DOE/METC-94/1004; terminal-
// velocity ratio of Garside & Al-Dibouni 1977]:
//
//   Re   = rho |u - v| d / mu          (INTERSTITIAL slip, gas density WITHOUT eps: MFiX's RE =
//                                       DPM*VREL*ROg/Mug, unlike Re_p of this folder)
//   A    = eps^4.14
//   B    = c1 eps^1.28   (eps <= 0.85),   eps^d1   (eps > 0.85),   c1 = 0.8, d1 = 2.65
//                                      (MFiX's defaults DRAG_C1, DRAG_D1)
//   V_r  = 1/2 (A - 0.06 Re + sqrt((0.06 Re)^2 + 0.12 Re (2B - A) + A^2))
//   C_d  = (0.63 + 4.8 sqrt(V_r / Re))^2            (Dalla Valle at Re / V_r)
//   beta = 3/4 eps_s eps rho C_d |u - v| / (V_r^2 d)
//          (MFiX: DgA = 0.75 mu eps C_DSXRE_DV(Re/V_r)/(V_r d^2), F_gs = DgA eps_s in Model A)
//
// In this folder's convention, with C_d (Re/V_r) = cd_re_dallavalle(Re/V_r) and
// rho |u - v| = Re mu / d:
//   K = beta/(1 - eps) = 3/4 eps mu cd_re_dallavalle(Re/V_r) / (V_r d^2)
//   F = K d^2/(18 mu eps) = cd_re_dallavalle(Re/V_r) / (24 V_r)
// Re = 0: V_r = A, C_d Re = 23.04; finite everywhere on eps in (0, 1].
// V_r is evaluated as 2 x B / (sqrt(S) + x - A) (x = 0.06 Re, S the radicand) when x > A: the
// same number (S - (x - A)^2 = 4 x B) without the cancellation of the printed form at large Re.
//
// Validity: MFiX uses it for all eps; B (and so the drag) has a small jump at eps = 0.85
// (0.8 0.85^1.28 = 0.64974 vs 0.85^2.65 = 0.65010; c1, d1 are usually recalibrated to a
// measured minimum fluidisation velocity, which this closure does not do). Single-particle limit:
// eps = 1 gives A = B = 1 and V_r = 1 exactly at every Re, so F = C_d Re / 24 of Dalla Valle:
// F -> 0.96 (not 1) as Re -> 0.
#pragma once
#include <cmath>

#include "coupling/drag/dallavalle.hpp"
#include "coupling/drag/drag_common.hpp"

namespace fluidem::coupling::drag {

struct SyamlalOBrien {
  static constexpr const char* name = "syamlal_obrien";
  static constexpr bool needs_mean_diameter = false;
  static void validate(const DragInput& in) { validate_drag_input(in, name); }

  /// Garside & Al-Dibouni's terminal-velocity ratio V_r(eps, Re), Re on the interstitial slip.
  static double velocity_ratio(double eps, double re) {
    const double a = std::pow(eps, 4.14);
    const double b = eps <= 0.85 ? 0.8 * std::pow(eps, 1.28) : std::pow(eps, 2.65);
    const double x = 0.06 * re;
    const double root = std::sqrt(x * x + 2.0 * x * (2.0 * b - a) + a * a);
    if (x > a) return 2.0 * x * b / (root + x - a);
    return 0.5 * (a - x + root);
  }
  static double k(const DragInput& in) {
    const double re = in.rho * in.slip * in.d / in.mu; // interstitial, as MFiX
    const double vr = velocity_ratio(in.eps, re);
    return 0.75 * in.eps * in.mu * cd_re_dallavalle(re / vr) / (vr * in.d * in.d);
  }
  static double beta(const DragInput& in) { return beta_from_k(k(in), in.eps); }
};

} // namespace fluidem::coupling::drag
