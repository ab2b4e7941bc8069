// Pendular liquid bridge between two spheres, or a sphere and a plane wall [Zhu07 §2.2, Table 2
// "Liquid bridge force"]: the capillary force, its rupture distance, the viscous force of the
// liquid, the work of rupture and the liquid distribution among bridges.
//
// Capillary force: the closed form of Willett, Adams, Johnson & Seville (2000, Langmuir 16:9396,
// "Capillary bridges between two spherical bodies", the more accurate expression of their
// appendix, the one [Zhu07 §2.2] recommends: V* < 0.1, error < 3% against the Laplace-Young
// solution), for total contact angle theta (radians), surface tension gamma and bridge volume V:
//   F = 2 pi R gamma F*,   ln F* = f1 - f2 exp(f3 ln S+ + f4 (ln S+)^2),
//   V* = V / R^3,   S+ = (S/2) / sqrt(V/R)      (S the surface gap: S/2 is Willett's
//                                                half-separation),
//   f_k = sum_m (a_km + b_km theta + c_km theta^2) (ln V*)^m   with (a, b, c) per power m:
//   f1: m=0 (-0.44507,  0.050832,  -1.1466)    m=1 (-0.1119,   -0.000411,  -0.1490)
//       m=2 (-0.012101, -0.0036456, -0.01255)  m=3 (-0.0005,   -0.0003505, -0.00029076)
//   f2: m=0 ( 1.9222,   -0.57473,  -1.2918)    m=1 (-0.0668,   -0.1201,    -0.22574)
//       m=2 (-0.0013375, -0.0068988, -0.01137)
//   f3: m=0 ( 1.268,    -0.01396,  -0.23566)   m=1 ( 0.198,     0.092,     -0.06418)
//       m=2 ( 0.02232,   0.02238,  -0.009853)  m=3 ( 0.0008585, 0.001318,  -0.00053)
//   f4: m=0 (-0.010703,  0.073776, -0.34742)   m=1 ( 0.03345,   0.04543,   -0.09056)
//       m=2 ( 0.0018574, 0.004456, -0.006257)
// (coefficients as implemented, with the same definitions of S+ and V*, in Yade's
// ViscoelasticCapillarPM.cpp, Willett_numeric_f, which cites the appendix of Willett et al.; the
// same expression, definitions, Derjaguin radius and coefficients are in PDPS's pair_lbw.cpp,
// style lb/willet, which states the range theta < 50 degrees, V* < 0.1; the theta = 0
// coefficients are also those of LIGGGHTS-PFM's Willett cohesion model.)
// At contact (S -> 0, f4 < 0) the exponential vanishes and F = 2 pi R gamma exp(f1), the value
// used for S <= 0 (touching or overlapping pairs: the force stays that of contact).
// Unequal spheres: the Derjaguin approximation as Willett et al. use it, the equal-sphere
// expression with the harmonic mean radius R = 2 R_i R_j / (R_i + R_j) (equal spheres: R = R_i;
// a plane wall, R_j = infinity: R = 2 R_i, so that the small-bridge force at contact is the
// sphere-plane 4 pi R_i gamma cos theta). Willett et al. find it relatively accurate for small
// volumes, except at close contact and near rupture [Zhu07 §2.2].
// Validity of the fit: theta < 50 degrees (0.87 rad), 1e-5 <= V* <= 0.1 (its contact force then
// lies within 3% of the toroidal value 2 pi R gamma / (1 + tan(beta/2)) for theta = 0;
// tools/noncontact_reference.py); below V* ~ 1e-6 it grows unphysically, and for V* < ~1e-8 f4
// turns positive and F(0) = 0. The caller keeps V* in range.
//
// Rupture distance (Lian, Thornton & Adams 1993, J. Colloid Interface Sci. 161:138):
//   S_c = (1 + theta/2) V^(1/3)        (theta in radians)
// Beyond S_c the bridge has ruptured: no force. At S_c the force drops from F(S_c) > 0 to 0 (the
// bridge breaks with a finite force); the potential is continuous there.
//
// Potential: U(S) = -int_S^{S_c} |F(s)| ds (minus the work still needed to rupture the bridge),
// by a fixed 32-point Gauss-Legendre rule after the substitution s = S + (S_c - S) t^2
// (t in [0, 1]), which smooths the steep rise of F near contact: relative error < 2e-11 against
// mpmath.quad for 1e-5 <= V* <= 0.1, 0 <= theta <= 0.7 (tools/noncontact_reference.py;
// the tests hold it to 1e-9). For S < 0 the constant contact force continues the potential
// linearly, U(S) = U(0) + |F(0)| S, as van_der_waals.hpp does inside h0.
// Bridge energy E = int_0^{S_c} |F| ds = -U(0): the work to pull a bridge from contact to rupture.
//
// Viscous force of the bridge liquid along the line of centres (Reynolds lubrication between two
// spheres, O. Reynolds 1886; the form 6 pi mu R*^2 v / S used for liquid bridges by Adams &
// Perchard 1985 and Pitois, Moucheront & Chateau 2000, J. Colloid Interface Sci. 231:26, there
// without their finite-bridge correction factor, i.e. the fully flooded gap):
//   F_v = -6 pi mu_l R*^2 v_n / max(S, S_min),   R* = R_i R_j / (R_i + R_j)  (wall: R* = R_i),
// v_n the rate of change of the gap (> 0 separating): F_v < 0 (pulls together) when the pair
// separates, > 0 when it approaches. S_min (a parameter, e.g. the surface roughness) removes the
// 1/S singularity; overlapping pairs use S_min too.
//
// Liquid distribution (Yang, Zou & Yu 2003 [Zhu07 §2.2]: liquid distributed evenly among the
// particles and not transferable; "the liquid assigned to a particle will be evenly distributed
// to its liquid bridges"): a particle of liquid volume V_i with n_i bridges (this one included)
// gives V_i / n_i to each, so
//   V_bridge = V_i / n_i + V_j / n_j
// (not V_i/(2 n_i) + ...: with the full share the bridges of a particle hold exactly its liquid,
// sum over its bridges of V_i/n_i = V_i, which is the literal reading of the rule; a half share
// would leave half of every wetted particle's liquid in no bridge). A wall brings no liquid:
// V_j = 0 (its n_j is then ignored).
#pragma once
#include <array>
#include <cmath>
#include <numbers>

#include "noncontact/kernels/pair_force.hpp"

namespace fluidem::kernels {

/// The Derjaguin radius of Willett et al. (2000): 2 R_i R_j / (R_i + R_j); R_j = infinity (a
/// plane wall) gives 2 R_i.
inline double willett_radius(double r_i, double r_j) {
  if (std::isinf(r_j)) return 2.0 * r_i;
  return 2.0 * r_i * r_j / (r_i + r_j);
}

/// Effective radius of the lubrication force, R_i R_j / (R_i + R_j); a wall (R_j = infinity): R_i.
inline double lubrication_radius(double r_i, double r_j) {
  if (std::isinf(r_j)) return r_i;
  return r_i * r_j / (r_i + r_j);
}

/// Rupture distance S_c = (1 + theta/2) V^(1/3) (Lian et al. 1993), m; theta in radians.
inline double liquid_bridge_rupture_distance(double volume, double theta) {
  return (1.0 + 0.5 * theta) * std::cbrt(volume);
}

struct WillettCoefficients {
  double f1 = 0.0, f2 = 0.0, f3 = 0.0, f4 = 0.0;
};

/// f1..f4 of Willett et al. (2000) at contact angle theta (radians) and ln V*.
inline WillettCoefficients willett_coefficients(double theta, double ln_v) {
  const double t = theta, t2 = theta * theta;
  const double l = ln_v, l2 = ln_v * ln_v, l3 = l2 * ln_v;
  WillettCoefficients c;
  c.f1 = (-0.44507 + 0.050832 * t - 1.1466 * t2) + (-0.1119 - 0.000411 * t - 0.1490 * t2) * l +
         (-0.012101 - 0.0036456 * t - 0.01255 * t2) * l2 +
         (-0.0005 - 0.0003505 * t - 0.00029076 * t2) * l3;
  c.f2 = (1.9222 - 0.57473 * t - 1.2918 * t2) + (-0.0668 - 0.1201 * t - 0.22574 * t2) * l +
         (-0.0013375 - 0.0068988 * t - 0.01137 * t2) * l2;
  c.f3 = (1.268 - 0.01396 * t - 0.23566 * t2) + (0.198 + 0.092 * t - 0.06418 * t2) * l +
         (0.02232 + 0.02238 * t - 0.009853 * t2) * l2 +
         (0.0008585 + 0.001318 * t - 0.00053 * t2) * l3;
  c.f4 = (-0.010703 + 0.073776 * t - 0.34742 * t2) + (0.03345 + 0.04543 * t - 0.09056 * t2) * l +
         (0.0018574 + 0.004456 * t - 0.006257 * t2) * l2;
  return c;
}

namespace detail {

/// |F| and |dF/dS| of Willett's force at gap > 0 for the radius r = willett_radius().
struct CapillaryMagnitude {
  double force = 0.0;
  double slope = 0.0;
};

inline CapillaryMagnitude willett_magnitude(const WillettCoefficients& c, double scale,
                                            double half_gap_unit, double gap) {
  // scale = 2 pi R gamma; half_gap_unit = 2 sqrt(V/R): S+ = gap / half_gap_unit
  if (gap <= 0.0) {
    // the limit S+ -> 0: exp(f3 ln S+ + f4 ln^2 S+) -> 0 for f4 < 0 (or f4 = 0, f3 > 0)
    const bool vanishes = c.f4 < 0.0 || (c.f4 == 0.0 && c.f3 > 0.0);
    return {vanishes ? scale * std::exp(c.f1) : 0.0, 0.0};
  }
  const double ls = std::log(gap / half_gap_unit);
  const double e = std::exp(c.f3 * ls + c.f4 * ls * ls);
  const double f = scale * std::exp(c.f1 - c.f2 * e);
  // dF/dS = F * (-f2 e (f3 + 2 f4 ln S+) / S+) * dS+/dS = F * (-f2 e (f3 + 2 f4 ln S+)) / S
  const double slope = f * c.f2 * e * (c.f3 + 2.0 * c.f4 * ls) / gap;
  return {f, std::fabs(slope)};
}

/// Nodes (positive half) and weights of the 32-point Gauss-Legendre rule on [-1, 1].
inline constexpr std::array<std::array<double, 2>, 16> kGauss32 = {{
    {0.048307665687738316235, 0.096540088514727800567},
    {0.14447196158279649349, 0.095638720079274859419},
    {0.23928736225213707454, 0.093844399080804565639},
    {0.33186860228212764978, 0.091173878695763884713},
    {0.42135127613063534536, 0.087652093004403811143},
    {0.50689990893222939002, 0.083311924226946755222},
    {0.58771575724076232904, 0.078193895787070306472},
    {0.66304426693021520098, 0.072345794108848506225},
    {0.73218211874028968039, 0.065822222776361846838},
    {0.79448379596794240696, 0.058684093478535547145},
    {0.84936761373256997013, 0.050998059262376176196},
    {0.89632115576605212397, 0.042835898022226680657},
    {0.93490607593773968917, 0.034273862913021433103},
    {0.96476225558750643077, 0.025392065309262059456},
    {0.9856115115452683354, 0.016274394730905670605},
    {0.99726386184948156354, 0.0070186100094700966004},
}};

/// int_a^b |F(s)| ds, s = a + (b - a) t^2, t = (x + 1)/2, by the 32-point rule.
inline double willett_work(const WillettCoefficients& c, double scale, double half_gap_unit,
                           double a, double b) {
  const double len = b - a;
  double sum = 0.0;
  for (const auto& [x, w] : kGauss32) {
    for (const double xs : {-x, x}) {
      const double t = 0.5 * (xs + 1.0);
      const double s = a + len * t * t;
      // ds = 2 len t dt, dt = dx/2
      sum += w * len * t * willett_magnitude(c, scale, half_gap_unit, s).force;
    }
  }
  return sum;
}

} // namespace detail

/// Capillary force of a pendular bridge of volume `volume` (m^3) between spheres of radii r_i,
/// r_j (m; r_j = infinity: a plane wall) at surface gap `gap` (m; <= 0: the force at contact),
/// contact angle theta (radians), surface tension gamma (N/m). Zero at gap >= S_c (ruptured).
/// `force` < 0 (attractive); `potential` = -int_gap^{S_c} |F| ds; `stiffness` = |dF/dgap|.
inline PairForce liquid_bridge_capillary(double r_i, double r_j, double volume, double theta,
                                         double gamma, double gap) {
  const double s_c = liquid_bridge_rupture_distance(volume, theta);
  if (gap >= s_c) return {};
  const double r = willett_radius(r_i, r_j);
  const WillettCoefficients c = willett_coefficients(theta, std::log(volume / (r * r * r)));
  const double scale = 2.0 * std::numbers::pi * r * gamma;
  const double unit = 2.0 * std::sqrt(volume / r);
  const detail::CapillaryMagnitude m = detail::willett_magnitude(c, scale, unit, gap);
  double u = -detail::willett_work(c, scale, unit, gap > 0.0 ? gap : 0.0, s_c);
  if (gap < 0.0) u += m.force * gap;
  return {-m.force, u, m.slope};
}

/// liquid_bridge_capillary's force alone (N, < 0: attractive), without the quadrature of its
/// potential: what a run evaluates every step.
inline double liquid_bridge_capillary_force(double r_i, double r_j, double volume, double theta,
                                            double gamma, double gap) {
  if (gap >= liquid_bridge_rupture_distance(volume, theta)) return 0.0;
  const double r = willett_radius(r_i, r_j);
  const WillettCoefficients c = willett_coefficients(theta, std::log(volume / (r * r * r)));
  return -detail::willett_magnitude(c, 2.0 * std::numbers::pi * r * gamma,
                                    2.0 * std::sqrt(volume / r), gap)
              .force;
}

/// The work to pull a bridge from contact (S = 0) to rupture (S_c), J: -potential at contact.
inline double liquid_bridge_energy(double r_i, double r_j, double volume, double theta,
                                   double gamma) {
  const double s_c = liquid_bridge_rupture_distance(volume, theta);
  const double r = willett_radius(r_i, r_j);
  const WillettCoefficients c = willett_coefficients(theta, std::log(volume / (r * r * r)));
  return detail::willett_work(c, 2.0 * std::numbers::pi * r * gamma, 2.0 * std::sqrt(volume / r),
                              0.0, s_c);
}

/// Viscous (lubrication) force of the bridge liquid, N, along the line of centres:
/// -6 pi mu_l R*^2 v_n / max(gap, s_min), mu_l the liquid viscosity (Pa s), v_n the rate of the
/// gap (m/s, > 0 separating), s_min > 0 the minimum gap (m). < 0 pulls together.
inline double liquid_bridge_viscous(double mu_l, double r_i, double r_j, double v_n, double gap,
                                    double s_min) {
  const double r = lubrication_radius(r_i, r_j);
  const double h = gap > s_min ? gap : s_min;
  return -6.0 * std::numbers::pi * mu_l * r * r * v_n / h;
}

/// Volume of the bridge between particles i and j (Yang et al. 2003 [Zhu07 §2.2]): each particle
/// shares its liquid v_i evenly among its n_i bridges (this one included, n_i >= 1), so
/// V = v_i / n_i + v_j / n_j; a wall (v_j = 0) brings none (n_j is then not used).
inline double liquid_bridge_volume(double v_i, int n_i, double v_j, int n_j) {
  const double from_i = v_i > 0.0 ? v_i / n_i : 0.0;
  const double from_j = v_j > 0.0 ? v_j / n_j : 0.0;
  return from_i + from_j;
}

} // namespace fluidem::kernels
