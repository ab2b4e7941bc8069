// Ergun (1952) packed-bed drag as an interphase momentum exchange coefficient
// [Hoomans96 eq. 45; Deen07 eq. 3; Zhu07 Table 3; Gidaspow 1994]:
//
//   beta = 150 (1 - eps)^2 mu / (eps d^2) + 1.75 (1 - eps) rho |u - v| / d
//   K    = beta / (1 - eps) = 150 (1 - eps) mu / (eps d^2) + 1.75 rho |u - v| / d
//
// This is Ergun's pressure drop dp/L = 150 mu U (1-eps)^2/(eps^3 d^2) + 1.75 rho U^2 (1-eps)/
// (eps^3 d) (U = eps |u - v| superficial) put into the gas momentum balance
// 0 = -eps grad p - beta (u - v) of a fixed bed: beta = eps^2 (dp/L) / U.
//
// Reconstruction note: [Deen07 eq. 3] prints beta d^2/mu = 150 eps_s^2/eps + 1.75 eps_s Re with
// Re = eps rho |u - v| d / mu; with that Re the inertial term would be eps times the
// [Hoomans96 eq. 45] / Ergun value. We use the Ergun / Hoomans96 form above, i.e.
// beta d^2 / mu = 150 eps_s^2 / eps + 1.75 eps_s Re / eps.
//
// Validity: dense beds, eps < 0.8 [Hoomans96 §3.2.2]. Single-particle limit: NONE — as
// eps -> 1 the viscous term vanishes (K -> 1.75 rho |u - v| / d, F -> 1.75 Re / 18 -> 0 as
// Re -> 0), so Ergun does not tend to Stokes drag; it is meant to be used below eps = 0.8.
#pragma once
#include "coupling/drag/drag_common.hpp"

namespace fluidem::coupling::drag {

struct Ergun {
  static constexpr const char* name = "ergun";
  static constexpr bool needs_mean_diameter = false;
  static void validate(const DragInput& in) { validate_drag_input(in, name); }

  /// K = beta / (1 - eps), kg m^-3 s^-1.
  static double k(const DragInput& in) {
    return 150.0 * (1.0 - in.eps) * in.mu / (in.eps * in.d * in.d) + 1.75 * in.rho * in.slip / in.d;
  }
  /// beta, kg m^-3 s^-1 [Hoomans96 eq. 45].
  static double beta(const DragInput& in) { return beta_from_k(k(in), in.eps); }
};

} // namespace fluidem::coupling::drag
