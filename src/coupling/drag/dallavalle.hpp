// Dalla Valle's (1948) single-sphere drag coefficient, as used by Syamlal & O'Brien (MFiX) and by
// Rong, Dong & Yu (2013) [MFiX model/drag_gs.f, function C_DSXRE_DV; Di Felice 1994]:
//
//   C_d = (0.63 + 4.8 / sqrt(Re))^2
//
// computed as C_d Re = (0.63 sqrt(Re) + 4.8)^2 so that Re = 0 is finite (= 23.04). Its Stokes
// limit is C_d Re / 24 = 0.96, not 1: a closure built on it gives F -> 0.96 for one sphere at
// Re -> 0 (4% below Stokes), and F = 0.96 + 0.252 sqrt(Re) + ... near Re = 0.
#pragma once
#include <cmath>

namespace fluidem::coupling::drag {

/// C_d Re of Dalla Valle: (0.63 sqrt(Re) + 4.8)^2 (Re >= 0).
inline double cd_re_dallavalle(double re) {
  const double s = 0.63 * std::sqrt(re) + 4.8;
  return s * s;
}

} // namespace fluidem::coupling::drag
