// Koch & Hill (2001) drag from lattice-Boltzmann simulations of random arrays
// [Zhu07 Table 3; Koch & Hill, Annu. Rev. Fluid Mech. 33 (2001) 619; Koch & Sangani 1999]:
//
//   F_KH = F0(phi) + F1(phi) Re^2     (Re < 20)
//   F_KH = F0(phi) + F3(phi) Re       (Re >= 20)
//   F0 = (1 + 3 sqrt(phi/2) + 135/64 phi ln phi + 16.14 phi)
//        / (1 + 0.681 phi - 8.48 phi^2 + 8.16 phi^3)        (phi < 0.4)
//   F0 = 10 phi / (1 - phi)^3                                 (phi >= 0.4)
//   F1 = 0.110 + 5.10e-4 exp(11.6 phi)
//   F3 = 0.0673 + 0.212 phi + 0.0232 / (1 - phi)^5
//   beta = 18 mu eps^2 phi F_KH / d^2   (Benyahia et al. 2006; MFiX "KOCH_HILL")
//
// Reconstruction notes. (1) [Zhu07 Table 3]'s extraction prints "F3 Re^2" in the second branch
// and "(1-phi)5" without the division; the Koch-Hill form is F3 Re and 0.0232/(1-phi)^5 (the
// same F3 as Hill-Koch-Ladd, see [Deen07 eq. 5] where B = 9 eps^2 F3). (2) Koch & Hill and
// Hill-Koch-Ladd use the Reynolds number on the particle RADIUS:
//   Re = eps rho |u - v| d / (2 mu) = Re_p / 2.
// Zhu07 writes Re_p, but only the radius-based Re is consistent with Deen07's B coefficient of
// the same F3 (9 = 18/2), so we use Re = Re_p/2; the switch Re = 20 is then Re_p = 40, which is
// where Deen07 says the F3 branch applies ("for Re > 40"). (3) Zhu07 uses F0 in both branches
// (the original has a separate F2 in the second); we follow Zhu07, so the drag jumps at Re = 20.
//
// In this folder's convention: K = beta/(1 - eps) = 18 mu eps^2 F_KH / d^2, F = eps F_KH;
// phi ln phi is taken as 0 at phi = 0, so F0(0) = 1 and F -> 1 (Stokes) as eps -> 1, Re -> 0.
// Validity: LB data phi <= 0.6, Re up to a few hundred.
#pragma once
#include <cmath>

#include "coupling/drag/drag_common.hpp"

namespace fluidem::coupling::drag {

struct KochHill {
  static constexpr const char* name = "koch_hill";
  static constexpr bool needs_mean_diameter = false;
  static void validate(const DragInput& in) { validate_drag_input(in, name); }

  static double f0(double phi) {
    if (phi >= 0.4) {
      const double e = 1.0 - phi;
      return 10.0 * phi / (e * e * e);
    }
    const double phi_ln_phi = phi > 0.0 ? phi * std::log(phi) : 0.0;
    return (1.0 + 3.0 * std::sqrt(0.5 * phi) + 135.0 / 64.0 * phi_ln_phi + 16.14 * phi) /
           (1.0 + 0.681 * phi - 8.48 * phi * phi + 8.16 * phi * phi * phi);
  }
  static double f1(double phi) { return 0.110 + 5.10e-4 * std::exp(11.6 * phi); }
  static double f3(double phi) {
    const double e = 1.0 - phi;
    return 0.0673 + 0.212 * phi + 0.0232 / (e * e * e * e * e);
  }
  /// Koch & Hill's F (normalised with eps^2 as in beta = 18 mu eps^2 phi F / d^2).
  static double f_kh(double eps, double re_radius) {
    const double phi = 1.0 - eps;
    return re_radius < 20.0 ? f0(phi) + f1(phi) * re_radius * re_radius
                            : f0(phi) + f3(phi) * re_radius;
  }
  static double k(const DragInput& in) {
    return 18.0 * in.mu * in.eps * in.eps * f_kh(in.eps, 0.5 * reynolds(in)) / (in.d * in.d);
  }
  static double beta(const DragInput& in) { return beta_from_k(k(in), in.eps); }
};

} // namespace fluidem::coupling::drag
