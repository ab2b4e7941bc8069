// The classic Ergun / Wen-Yu switch [Hoomans96 eq. 45-46; Deen07 eq. 3-4, first model of §4]:
//
//   beta = beta_Ergun (eps < 0.8),  beta_WenYu (eps >= 0.8)
//
// Hoomans96: "For porosities eps < 0.80 ... Ergun equation", "for porosities eps >= 0.80 ...
// Wen and Yu". The drag jumps at eps = 0.8 when Re_p is not small [Deen07 below eq. 4]; that
// jump is the reason for ergun_wen_yu_min and chang_joint. Single-particle limit: that of
// Wen-Yu (F -> 1 as Re_p -> 0 at eps = 1).
#pragma once
#include "coupling/drag/ergun.hpp"
#include "coupling/drag/wen_yu.hpp"

namespace fluidem::coupling::drag {

struct ErgunWenYuSwitch {
  static constexpr const char* name = "ergun_wen_yu";
  /// A case without coupling.drag gets this closure, the gas-phase closure of [Hoomans96].
  static constexpr bool is_default = true;
  static constexpr bool needs_mean_diameter = false;
  static constexpr double eps_switch = 0.8; ///< [Hoomans96 §3.2.2]
  static void validate(const DragInput& in) { validate_drag_input(in, name); }

  static double k(const DragInput& in) { return in.eps < eps_switch ? Ergun::k(in) : WenYu::k(in); }
  static double beta(const DragInput& in) { return beta_from_k(k(in), in.eps); }
};

} // namespace fluidem::coupling::drag
