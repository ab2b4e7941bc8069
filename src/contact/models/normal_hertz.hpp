// Normal model "hertz": Hertz with Tsuji's damping [Zhu07 Table 1; Chang08 eq. 2.15, 2.22], the
// force floored at zero [Schwager & Poeschel 2008] (contact/kernels/normal_force.hpp:
// hertz_normal), Mindlin's tangential stiffness [Chang08 eq. 2.16]:
//   F_n = max(0, K delta^{3/2} + alpha(e) sqrt(m* K) delta^{1/4} v_n),  K = 4/3 E* sqrt(R*)
//   k_t = 8 G* sqrt(R* delta)
// Mixing [Zhu07 Table 1]: 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b, 1/G* = (2 - nu_a)/G_a +
// (2 - nu_b)/G_b (G given or E/(2(1+nu))); a rigid wall adds no compliance.
#pragma once
#include <array>
#include <cmath>

#include "contact/kernels/normal_damping.hpp"
#include "contact/kernels/normal_force.hpp"
#include "contact/models/contact_point.hpp"
#include "contact/models/declaration.hpp"
#include "contact/models/material_pair.hpp"
#include "contact/pair_params.hpp"

namespace fluidem::contact_models {

struct HertzNormal {
  static constexpr Kind kind = Kind::Normal;
  static constexpr std::string_view name = "hertz";
  static constexpr std::string_view summary =
      "Hertz-Mindlin with Tsuji's damping [Zhu07 Table 1; Chang08 eq. 2.15, 2.16, 2.22]";
  static constexpr bool is_default = true;
  static constexpr std::array<Coefficient, 1> coefficients{{
      {.key = "stiffness_ratio",
       .unit = "",
       .range = Interval::positive(),
       .given = Given::AutoOnly,
       .meaning = "Mindlin's k_t = 8 G* sqrt(R* delta) follows from the materials; set "
                  "poisson_ratio or shear_modulus per species and wall"},
  }};
  static constexpr int history_width = 0;
  static constexpr bool takes_elastic_constants = true;
  static constexpr bool uses_impact_speed = true;
  static constexpr std::string_view foreign_key_note =
      "Hertzian stiffness follows from the material";
  static constexpr std::string_view mixing =
      "1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b, 1/G* = (2 - nu_a)/G_a + (2 - nu_b)/G_b "
      "[Zhu07 Table 1]; a rigid wall adds no compliance; the dashpot from the mixed e";
  static constexpr bool springs_hold_energy_at_separation = false; // k_t -> 0 with the overlap

  static void mix(PairParams& p, const MaterialPair& m, const Coefficients& /*c*/) {
    p.kn = 4.0 / 3.0 * p.e_star; // e_star: the table's 1/((1-nu_a^2)/E_a + (1-nu_b^2)/E_b)
    p.normal_damping = kernels::hertz_damping_alpha(m.mixed.restitution);
    // Mindlin k_t = 8 G* sqrt(R* delta) [Chang08 eq. 2.16], 1/G* = (2 - nu_a)/G_a +
    // (2 - nu_b)/G_b [Zhu07 Table 1].
    p.kt = 8.0 / (inv_g_part(m.a) + inv_g_part(m.b));
  }

  /// The force pulse of a head-on impact at `impact_speed`, s (normal_damping.hpp).
  static double duration(double m_eff, double r_eff, const PairParams& p, double impact_speed) {
    return kernels::hertz_contact_duration(m_eff, p.kn * std::sqrt(r_eff), p.normal_damping,
                                           impact_speed);
  }

  /// The overlap under a static force f, m: (f/K)^{2/3}.
  static double overlap_under(double f, double r_eff, const PairParams& p) {
    return std::pow(f / (p.kn * std::sqrt(r_eff)), 2.0 / 3.0);
  }

  [[gnu::always_inline]] static kernels::NormalResponse respond(const PairParams& pp, double r_eff,
                                                                double m_eff, double overlap) {
    return kernels::hertz_normal(pp.kn, r_eff, pp.normal_damping, m_eff, overlap);
  }
  /// Mindlin's k_t = c_t sqrt(R* delta), N/m.
  [[gnu::always_inline]] static double tangential_stiffness(const PairParams& pp,
                                                            const kernels::NormalResponse& nr) {
    return pp.kt * nr.contact_radius;
  }
  /// The tangent stiffness dF/d(delta), N/m.
  [[gnu::always_inline]] static double rolling_stiffness(const PairParams& /*pp*/,
                                                         const kernels::NormalResponse& nr) {
    return nr.stiffness;
  }
};

} // namespace fluidem::contact_models
