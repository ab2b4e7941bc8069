// Normal model "jkr": the adhesive elastic contact of Johnson, Kendall & Roberts (1971)
// [Zhu07 §2.2; Johnson, Contact Mechanics 1985, §5.5], as used in DEM by Thornton & Yin (1991,
// Powder Technol. 65:153) (contact/kernels/normal_force.hpp: jkr_normal), with E* and R* as for
// Hertz and the work of adhesion w (`adhesion_energy`):
//   delta = a^2/R* - sqrt(2 pi w a / E*),   F_n = 4 E* a^3/(3 R*) - sqrt(8 pi w E* a^3)
// (F_n > 0 repulsive; never floored: it is tensile by design, down to the pull-off force
// F_c = 3/2 pi w R*). History (1 double, "attached"): a contact forms when the pair touches
// (delta > 0: a jumps to a_f = (2 pi w R*^2/E*)^{1/3}, the force to -8/9 F_c) and holds in
// tension until delta < -delta_c, delta_c = 3/4 (pi^2 w^2 R*/E*^2)^{1/3} = 3 a_c^2/R*,
// a_c = (pi w R*^2/(8 E*))^{1/3} (where d(delta)/da = 0; the force there is -5/6 F_c).
// No dashpot: the only dissipation is the break, which takes the branch's potential
// U(-delta_c) (kernels::jkr_break_energy) with it (spring_loss); the materials' restitution is
// not used by the normal force. The tangential and rolling models' Coulomb limits take
// F_n + 2 F_c (Thornton & Yin 1991's convention: the load measured from the pull-off state),
// >= F_c > 0, so that an attached contact resists sliding also in tension.
// Mindlin's k_t = 8 G* a with the JKR contact radius a [Thornton & Yin 1991].
#pragma once
#include <array>
#include <cmath>
#include <numbers>

#include "contact/kernels/normal_damping.hpp"
#include "contact/kernels/normal_force.hpp"
#include "contact/models/contact_point.hpp"
#include "contact/models/declaration.hpp"
#include "contact/models/material_pair.hpp"
#include "contact/pair_params.hpp"

namespace fluidem::contact_models {

struct JkrNormal {
  static constexpr Kind kind = Kind::Normal;
  static constexpr std::string_view name = "jkr";
  static constexpr std::string_view summary =
      "JKR adhesive elastic contact, pull-off force 3/2 pi w R* [Zhu07 2.2; Johnson, Kendall & "
      "Roberts 1971; Thornton & Yin 1991]";
  static constexpr std::array<Coefficient, 2> coefficients{{
      {.key = "adhesion_energy",
       .unit = "J/m^2",
       .range = Interval::positive(),
       .given = Given::Required,
       .meaning = "the work of adhesion w of JKR (twice the surface energy of like surfaces); "
                  "pull-off force 3/2 pi w R*, contact breaks at delta = -3/4 (pi^2 w^2 R*/"
                  "E*^2)^{1/3}"},
      {.key = "stiffness_ratio",
       .unit = "",
       .range = Interval::positive(),
       .given = Given::AutoOnly,
       .meaning = "Mindlin's k_t = 8 G* a with the JKR contact radius a follows from the "
                  "materials; set poisson_ratio or shear_modulus per species and wall"},
  }};
  static constexpr int history_width = 1; ///< "attached": 1 from the first touch to the break
  static constexpr bool takes_elastic_constants = true;
  static constexpr bool uses_impact_speed = true;
  static constexpr std::string_view foreign_key_note = "JKR's stiffness follows from the material";
  static constexpr std::string_view mixing =
      "1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b, 1/G* = (2 - nu_a)/G_a + (2 - nu_b)/G_b "
      "[Zhu07 Table 1]; a rigid wall adds no compliance; w the same for every pair and wall";
  /// At the break the contact radius is a_c > 0: the tangential spring still holds energy.
  static constexpr bool springs_hold_energy_at_separation = true;
  /// The contact holds in tension (contact_forces.cpp: the walk's touching test takes
  /// attached entries with overlap > -detach_distance; the force is not floored).
  static constexpr bool detaches_in_tension = true;

  /// kn: 4/3 E*; kt: c_t = 8 G*; normal_damping: c = sqrt(2 pi w/E*) (no dashpot), from which
  /// w = 3 kn c^2/(8 pi) and delta_c = 3/4 (pi^2 w^2 R*/E*^2)^{1/3} = 3/4 (c^4 R*/4)^{1/3}
  /// follow (no field of its own: PairParams keeps its size, the other models' code its layout).
  static void mix(PairParams& p, const MaterialPair& m, const Coefficients& c) {
    const double w = c.at("adhesion_energy");
    p.kn = 4.0 / 3.0 * p.e_star;
    p.normal_damping = std::sqrt(2.0 * std::numbers::pi * w / p.e_star);
    p.kt = 8.0 / (inv_g_part(m.a) + inv_g_part(m.b));
  }

  /// delta_c = 3/4 (pi^2 w^2 R*/E*^2)^{1/3} = 3/4 (c^4 R*/4)^{1/3}, m: an attached contact
  /// breaks when its overlap falls below -delta_c.
  [[gnu::always_inline]] static double detach_distance(const PairParams& pp, double r_eff) {
    const double c2 = pp.normal_damping * pp.normal_damping;
    return 0.75 * std::cbrt(0.25 * c2 * c2 * r_eff);
  }

  /// The force pulse of a head-on impact at `impact_speed`, s: Hertz's (undamped) with E*: the
  /// adhesion lengthens it.
  static double duration(double m_eff, double r_eff, const PairParams& p, double impact_speed) {
    return kernels::hertz_contact_duration(m_eff, p.kn * std::sqrt(r_eff), 0.0, impact_speed);
  }

  /// The overlap under a static compressive force f, m: F_n(a) = f solved for a^{3/2}
  /// (a quadratic), then delta(a).
  static double overlap_under(double f, double r_eff, const PairParams& p) {
    const double c1 = p.kn / r_eff, c2 = 1.5 * p.kn * p.normal_damping;     // 2 E* c
    const double t = (c2 + std::sqrt(c2 * c2 + 4.0 * c1 * f)) / (2.0 * c1); // a^{3/2}
    const double a = std::cbrt(t * t);
    return a * a / r_eff - p.normal_damping * std::sqrt(a);
  }

  /// `hist[0]`: attached (0 before the first touch: the walk hands over an unattached entry
  /// only when it overlaps). Forming costs nothing in the potential (U(0) = 0): no spring_loss.
  [[gnu::always_inline]] static kernels::NormalResponse respond(const PairParams& pp, double r_eff,
                                                                double m_eff, double overlap,
                                                                double* hist, double& spring_loss) {
    hist[0] = 1.0;
    spring_loss = 0.0;
    return kernels::jkr_normal(pp.kn, pp.normal_damping, r_eff, m_eff, overlap);
  }
  /// The response as the contact breaks (at -delta_c: the contact radius a_c, the potential
  /// U(-delta_c)), for the energy the springs take with them.
  static kernels::NormalResponse at_break(const PairParams& pp, double r_eff) {
    const double p = r_eff * pp.normal_damping;
    const double a_c = std::cbrt(p * p) / std::cbrt(16.0); // a_f / 16^{1/3}
    return {0.0, 0.0, 1.5 * pp.kn * a_c, kernels::jkr_break_energy(pp.kn, pp.normal_damping, r_eff),
            0.0, a_c};
  }
  /// The normal load of the Coulomb and rolling limits, N: F_n + 2 F_c [Thornton & Yin 1991],
  /// 2 F_c = 3 pi w R* = 9/8 kn c^2 R*.
  [[gnu::always_inline]] static double friction_load(const PairParams& pp, double r_eff,
                                                     double f_n) {
    return f_n + 1.125 * pp.kn * pp.normal_damping * pp.normal_damping * r_eff;
  }
  /// Mindlin's k_t = c_t a, N/m.
  [[gnu::always_inline]] static double tangential_stiffness(const PairParams& pp,
                                                            const kernels::NormalResponse& nr) {
    return pp.kt * nr.contact_radius;
  }
  /// Hertz's tangent stiffness 2 E* a at the JKR contact radius, N/m.
  [[gnu::always_inline]] static double rolling_stiffness(const PairParams& /*pp*/,
                                                         const kernels::NormalResponse& nr) {
    return nr.stiffness;
  }
};

} // namespace fluidem::contact_models
