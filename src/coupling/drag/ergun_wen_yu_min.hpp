// The least of Ergun and Wen-Yu [Deen07 below eq. 4 and §4: "F = min(F_Ergun, F_Wen and Yu)"]:
//
//   beta = min(beta_Ergun, beta_WenYu)   for every eps (no switch porosity)
//
// Removes the jump of the switch at eps = 0.8. Both closures share the factor (1 - eps), so the
// minimum is taken on K = beta / (1 - eps), which is the same choice and stays defined at eps = 1.
//
// Single-particle limit: NONE at low Re_p. As eps -> 1, K_Ergun -> 1.75 rho |u - v| / d while
// K_WenYu -> 18 mu / d^2 (1 + 0.15 Re^0.687), so Ergun is the smaller one whenever
// 1.75 Re_p < 18 (1 + 0.15 Re_p^0.687), i.e. for Re_p below about 24 (23.97): there min -> Ergun
// and F -> 1.75 Re_p / 18 -> 0, not 1. It is a closure for beds, not for isolated particles.
#pragma once
#include <algorithm>

#include "coupling/drag/ergun.hpp"
#include "coupling/drag/wen_yu.hpp"

namespace fluidem::coupling::drag {

struct ErgunWenYuMin {
  static constexpr const char* name = "ergun_wen_yu_min";
  static constexpr bool needs_mean_diameter = false;
  static void validate(const DragInput& in) { validate_drag_input(in, name); }

  static double k(const DragInput& in) { return std::min(Ergun::k(in), WenYu::k(in)); }
  static double beta(const DragInput& in) { return beta_from_k(k(in), in.eps); }
};

} // namespace fluidem::coupling::drag
