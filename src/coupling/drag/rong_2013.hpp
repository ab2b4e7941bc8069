// Rong, Dong & Yu (2013) voidage function from lattice-Boltzmann simulations of packed beds
// [Rong, Dong & Yu, Chem. Eng. Sci. 99 (2013) 44-58, their drag correlation (equation number not
// checked: the paper's text was not available here); the form below is restated identically by
// PhasicFlowPlus drag/Rong.hpp and by other codes listed in docs/drag.md]:
//
//   F_d  = C_d rho pi d^2 / 8 * eps^2 |u - v| (u - v) * eps^-beta_R
//          (Di Felice's form: the single-sphere drag at the SUPERFICIAL slip eps (u - v) times
//           eps^-beta_R; eps^(2 - beta_R) on the interstitial slip)
//   beta_R = 2.65 (eps + 1) - (5.3 - 3.5 eps) eps^2 exp(-(1.5 - log10 Re_p)^2 / 2)
//   C_d  = (0.63 + 4.8 / sqrt(Re_p))^2                 (Dalla Valle, as Di Felice and Rong fit)
//   Re_p = eps rho |u - v| d / mu
//
// The exponent replaces Di Felice's chi = 3.7 - 0.65 exp(...) by an eps-dependent one fitted to
// LB data over a wide porosity range; the drag is without the pressure-gradient force (Model A),
// like di_felice.hpp. Unlike di_felice (which follows [Zhu07 Table 3] with Schiller-Naumann), C_d
// here is Dalla Valle's, as published: so the single sphere has F -> 0.96 at Re -> 0.
//
// In this folder's convention (C_d Re_p = cd_re_dallavalle(Re_p)):
//   K = 3/4 C_d rho |u - v| eps^(2 - beta_R) / d = 3/4 (C_d Re_p) mu eps^(1 - beta_R) / d^2
//   beta = (1 - eps) K,   F = (C_d Re_p / 24) eps^-beta_R
// Re_p = 0: the exponential is 0 (log10 Re_p -> -inf), beta_R = 2.65 (eps + 1); C_d Re_p = 23.04.
//
// Validity: LB data on packed beds of uniform spheres over a wide porosity range and moderate
// Re_p (the exact ranges are in the paper, not checked here). Single-particle limit: eps = 1
// gives F = C_d Re_p / 24 of Dalla Valle, F -> 0.96 as Re_p -> 0.
#pragma once
#include <cmath>

#include "coupling/drag/dallavalle.hpp"
#include "coupling/drag/drag_common.hpp"

namespace fluidem::coupling::drag {

struct Rong2013 {
  static constexpr const char* name = "rong_2013";
  static constexpr bool needs_mean_diameter = false;
  static void validate(const DragInput& in) { validate_drag_input(in, name); }

  /// Rong's exponent beta_R(eps, Re_p).
  static double exponent(double eps, double re) {
    const double base = 2.65 * (eps + 1.0);
    if (!(re > 0.0)) return base;
    const double x = 1.5 - std::log10(re);
    return base - (5.3 - 3.5 * eps) * eps * eps * std::exp(-0.5 * x * x);
  }
  static double k(const DragInput& in) {
    const double re = reynolds(in);
    return 0.75 * cd_re_dallavalle(re) * in.mu * std::pow(in.eps, 1.0 - exponent(in.eps, re)) /
           (in.d * in.d);
  }
  static double beta(const DragInput& in) { return beta_from_k(k(in), in.eps); }
};

} // namespace fluidem::coupling::drag
