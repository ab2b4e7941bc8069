// Coarse-grained "virtual" particles [Chang08 §2.2.3, eq. 2.24-2.40]: each simulated particle
// (a parcel, subscript 2) stands for W real ones (subscript 1) of the same density, so that
// mass and volume balance (eq. 2.24-2.26) and
//   d2 = W^(1/3) d1                                               [Chang08 eq. 2.27].
// The case gives the real particles (species diameters, materials, contact coefficients) and W;
// the set-up simulates the parcels (integrate/coarse_graining.hpp). Plain data and the scaling
// factors as pure functions; what each scaling conserves is derived in docs/coarse-graining.md.
#pragma once
#include <cmath>
#include <string_view>

namespace fluidem {

/// How the contact law of two parcels follows from that of two real particles (s = W^(1/3)).
enum class ContactScaling {
  /// [Chang08 eq. 2.38, 2.40] as printed: linear k_n2 = s k_n1, k_t2 = s k_t1; Hertz
  /// E2 = W^(1/6) E1 (the eq. 2.35-2.36 balance applied to the Hertz coefficient, with eq.
  /// 2.15's sqrt(R*) growing as well: docs/coarse-graining.md).
  chang08,
  /// The material unchanged (Bierwisch et al. 2009, J. Mech. Phys. Solids 57:10; Radl et al.
  /// 2011, 8th CFD Oil & Gas): linear k ~ E d, so k2 = s k1; Hertz E2 = E1. Overlap / diameter
  /// and restitution kept; contact duration x s.
  scale_invariant,
  /// The real contact duration kept: linear k2 = W k1 (k/m kept), Hertz E2 = s^(5/2) E1
  /// (m*^2 / (E*^2 R*) kept). Restitution and the absolute overlap kept; overlap/diameter / s.
  collision_time,
};

/// Which diameter the drag closure sees.
enum class DragDiameter {
  /// The real particles' d1 = d2 / s: a parcel gets W times the drag of one real particle, the
  /// cell's drag is the real system's (the represented surface area of [Chang08 eq. 2.31]), and
  /// the relaxation time (Stokes number) of the real particles is kept.
  real,
  /// The parcel's own d2: Stokes-regime drag per unit mass / s^2 (relaxation time x s^2).
  parcel,
};

struct CoarseGrainingSpec {
  double ratio = 1.0; ///< `coarse_graining.ratio`: W, real particles per parcel, >= 1
  ContactScaling contact_scaling = ContactScaling::chang08;
  DragDiameter drag_diameter = DragDiameter::real;
  bool active() const { return ratio != 1.0; }
};

namespace coarse_graining {

/// s = W^(1/3): d2 / d1 [Chang08 eq. 2.27].
inline double diameter_factor(double w) {
  return std::cbrt(w);
}

/// k2 / k1 for a linear (or Walton-Braun) spring, both k_n and k_t.
inline double linear_stiffness_factor(ContactScaling c, double w) {
  switch (c) {
  case ContactScaling::chang08:         // [Chang08 eq. 2.38]
  case ContactScaling::scale_invariant: // k ~ E d (Bierwisch et al. 2009)
    return std::cbrt(w);
  case ContactScaling::collision_time: // sqrt(m/k) kept
    return w;
  }
  return 1.0;
}

/// E2 / E1 (and G2 / G1) for Hertz-Mindlin.
inline double youngs_modulus_factor(ContactScaling c, double w) {
  switch (c) {
  case ContactScaling::chang08: // [Chang08 eq. 2.40]
    return std::pow(w, 1.0 / 6.0);
  case ContactScaling::scale_invariant:
    return 1.0;
  case ContactScaling::collision_time: // (m*^2 / (E*^2 R*))^(1/5) kept: E ~ s^(5/2)
    return std::pow(w, 5.0 / 6.0);
  }
  return 1.0;
}

/// The factor from a parcel's diameter to the diameter the drag closure sees.
inline double drag_diameter_factor(DragDiameter d, double w) {
  return d == DragDiameter::real ? 1.0 / std::cbrt(w) : 1.0;
}

} // namespace coarse_graining

inline std::string_view to_string(ContactScaling c) {
  switch (c) {
  case ContactScaling::chang08:
    return "chang08";
  case ContactScaling::scale_invariant:
    return "scale_invariant";
  case ContactScaling::collision_time:
    return "collision_time";
  }
  return "?";
}
inline std::string_view to_string(DragDiameter d) {
  return d == DragDiameter::real ? "real" : "parcel";
}

} // namespace fluidem
