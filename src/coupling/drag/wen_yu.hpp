// Wen & Yu (1966) dilute-bed drag as an interphase momentum exchange coefficient
// [Hoomans96 eq. 46-47; Deen07 eq. 4; Gidaspow 1994]:
//
//   beta = 3/4 C_d eps (1 - eps) rho |u - v| / d * eps^-2.65
//   C_d  = 24/Re_p (1 + 0.15 Re_p^0.687) (Re_p < 1000), 0.44 (Re_p >= 1000)   [Hoomans96 eq. 38]
//   Re_p = eps rho |u - v| d / mu                                               [Hoomans96 eq. 47]
//
// Written with C_d Re_p (finite at Re_p = 0) using rho |u - v| = Re_p mu / (eps d):
//   K = beta / (1 - eps) = 3/4 (C_d Re_p) mu eps^-2.65 / d^2
//   F = K d^2 / (18 mu eps) = (C_d Re_p / 24) eps^-3.65
// [Deen07 eq. 4] (beta d^2/mu = 3/4 C_d Re eps_s eps^-2.65) is the same expression.
//
// Validity: eps >= 0.8 [Hoomans96 §3.2.2], any Re_p. Single-particle limit: eps = 1 gives the
// isolated sphere with Schiller-Naumann C_d; F -> 1 (Stokes) as Re_p -> 0.
#pragma once
#include <cmath>

#include "coupling/drag/drag_common.hpp"

namespace fluidem::coupling::drag {

struct WenYu {
  static constexpr const char* name = "wen_yu";
  static constexpr bool needs_mean_diameter = false;
  static void validate(const DragInput& in) { validate_drag_input(in, name); }

  /// K = beta / (1 - eps), kg m^-3 s^-1.
  static double k(const DragInput& in) {
    return 0.75 * cd_re_schiller_naumann(reynolds(in)) * in.mu * std::pow(in.eps, -2.65) /
           (in.d * in.d);
  }
  /// beta, kg m^-3 s^-1 [Hoomans96 eq. 46].
  static double beta(const DragInput& in) { return beta_from_k(k(in), in.eps); }
};

} // namespace fluidem::coupling::drag
