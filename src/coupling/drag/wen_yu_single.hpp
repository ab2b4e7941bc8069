// Single-particle Wen-Yu drag of the POGO code [Hoomans96 eq. 35-39]:
//
//   F_d  = pi/8 d^2 C_d' rho |v| v,   v = eps (u - v_p)   (relative SUPERFICIAL velocity, eq. 36)
//   C_d' = C_d eps^-4.7                                   (Wen & Yu 1966, eq. 37)
//   C_d  = 24/Re_p (1 + 0.15 Re_p^0.687) (Re_p < 1000), 0.44 (Re_p >= 1000)   (eq. 38)
//   Re_p = eps rho |u - v_p| d / mu                                           (eq. 39)
//
// so F_d = pi/8 d^2 C_d rho eps^-2.7 |u - v_p| (u - v_p). The extraction garbles eq. 35-37
// ("Fd = la rcd~ C~pg Ivlv", "C~ = Cde -4'7"); the form above is Wen & Yu's
// C_d' = C_d eps^-4.7 on the superficial velocity, as Hoomans et al. state in words.
//
// In this folder's convention (F_p = V_p K (u - v)):
//   K    = 3/4 C_d rho |u - v| eps^-2.7 / d = 3/4 (C_d Re_p) mu eps^-3.7 / d^2
//   beta = (1 - eps) K
//   F    = (C_d Re_p / 24) eps^-4.7
//
// NOTE: Hoomans96 eq. 34 has no pressure-gradient force (buoyancy neglected for gas-solid), so
// F_d is the TOTAL gas force on the particle; it is larger than the Model-A drag of eq. 46 by
// eps^-1.05 (4.7 = 3.65 + 1.05). Use it WITHOUT a separate -V_p grad p term, as in POGO
// (coupling.particle_force = "total").
//
// Validity: any eps in (0, 1], any Re_p (Wen & Yu's data: 0.4 < eps < 1). Single-particle limit:
// eps = 1 is the isolated sphere (Schiller-Naumann), F -> 1 as Re_p -> 0.
#pragma once
#include <cmath>
#include <string_view>

#include "coupling/drag/drag_common.hpp"

namespace fluidem::coupling::drag {

struct WenYuSingle {
  static constexpr const char* name = "wen_yu_single";
  static constexpr bool needs_mean_diameter = false;
  /// The TOTAL gas force on the particle (drag and the flow's pressure force together): valid
  /// only in the particle-force form coupling.particle_force = "total" [Hoomans96 eq. 34], which
  /// adds no pressure-gradient force (exchange.hpp); refused with the other forms, which would
  /// count the pressure force twice (about 1/eps times the right force).
  static constexpr bool total_force = true;
  static void validate(const DragInput& in) { validate_drag_input(in, name); }

  /// K = |F_d| / (V_p |u - v|), kg m^-3 s^-1.
  static double k(const DragInput& in) {
    return 0.75 * cd_re_schiller_naumann(reynolds(in)) * in.mu * std::pow(in.eps, -3.7) /
           (in.d * in.d);
  }
  static double beta(const DragInput& in) { return beta_from_k(k(in), in.eps); }
};

} // namespace fluidem::coupling::drag
