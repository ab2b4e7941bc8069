// Normal model "walton_braun": the hysteretic ("semi-latched") linear spring of Walton & Braun
// (1986, J. Rheol. 30:949) [Zhu07 Table 1] (contact/kernels/normal_force.hpp:
// walton_braun_normal), with history delta_max (the largest overlap of the contact so far):
//   loading (delta >= delta_max):   F_n = k1 delta                       (delta_max <- delta)
//   unloading and reloading:        F_n = max(0, k2 (delta - delta0)),   delta0 = delta_max (1 -
//   k1/k2)
// so that a head-on impact rebounds with e = sqrt(k1/k2) at any speed. k1 is the case's
// `stiffness`, k2 = k1/e^2 from the pair's mixed restitution (the materials' `restitution`, as
// for the other normal models): no dashpot, the hysteresis is the dissipation.
// k_t = stiffness_ratio k1 ("auto": the linear model's rule [Deen07 eq. 43]); the rolling spring
// scales with k1.
#pragma once
#include <array>
#include <cmath>
#include <numbers>

#include "contact/kernels/normal_damping.hpp"
#include "contact/kernels/normal_force.hpp"
#include "contact/models/contact_point.hpp"
#include "contact/models/declaration.hpp"
#include "contact/models/material_pair.hpp"
#include "contact/models/normal_linear.hpp"
#include "contact/pair_params.hpp"

namespace fluidem::contact_models {

struct WaltonBraunNormal {
  static constexpr Kind kind = Kind::Normal;
  static constexpr std::string_view name = "walton_braun";
  static constexpr std::string_view summary =
      "Walton & Braun hysteretic spring, loading k1, unloading k2 = k1/e^2 [Zhu07 Table 1; "
      "Walton & Braun 1986]";
  static constexpr std::array<Coefficient, 2> coefficients{{
      {.key = "stiffness",
       .unit = "N/m",
       .range = Interval::positive(),
       .given = Given::Required,
       .meaning = "loading stiffness k1 [Zhu07 Table 1]; the unloading stiffness is "
                  "k2 = k1/e^2 from the pair's restitution e",
       .usual_lo = 1.0,
       .usual_hi = 1e10,
       .longer_when_larger = false},
      {.key = "stiffness_ratio",
       .unit = "",
       .range = Interval::positive(),
       .given = Given::Auto,
       .meaning = "k_t/k1; \"auto\": 2/7 (pi^2 + ln^2 beta0)/(pi^2 + ln^2 e), the linear "
                  "model's rule [Deen07 eq. 43] with k_n = k1",
       .mixing = "the same for every species pair and wall; \"auto\": from the pair's mixed e "
                 "and beta0"},
  }};
  static constexpr int history_width = 1; ///< delta_max, the largest overlap so far, m
  static constexpr bool takes_elastic_constants = false;
  static constexpr std::string_view mixing =
      "k1 and k_t from [contact], the same for every contact; k2 = k1/e^2 from the pair's mixed e";
  /// k_t does not vanish as the overlap closes (and the tangential spring's energy is released
  /// when a contact ends, as for the linear model).
  static constexpr bool springs_hold_energy_at_separation = true;

  /// kn: k1; normal_damping: k1/k2 = e^2 (the model's own use of the field); kt: k_t.
  static void mix(PairParams& p, const MaterialPair& m, const Coefficients& c) {
    const double e = m.mixed.restitution;
    p.kn = c.at("stiffness");
    p.normal_damping = e * e;                          // k1/k2 [Zhu07 Table 1]: e = sqrt(k1/k2)
    p.kt = LinearNormal::stiffness_ratio(m, c) * p.kn; // the linear model's rule, with k1
  }

  /// The force pulse of a head-on impact, s: half a period on k1 while loading and half a
  /// period on k2 while unloading, pi/2 sqrt(m*/k1) (1 + e) [Walton & Braun 1986].
  static double duration(double m_eff, double /*r_eff*/, const PairParams& p,
                         double /*impact_speed*/) {
    const double half = 0.5 * std::numbers::pi * std::sqrt(m_eff / p.kn);
    return half * (1.0 + std::sqrt(p.normal_damping));
  }

  /// The overlap under a static force f (first loading), m.
  static double overlap_under(double f, double /*r_eff*/, const PairParams& p) { return f / p.kn; }

  /// `hist`: the model's own history (delta_max); `spring_loss`: the energy the loading moved
  /// out of the recoverable spring this step, J.
  [[gnu::always_inline]] static kernels::NormalResponse respond(const PairParams& pp,
                                                                double /*r_eff*/, double m_eff,
                                                                double overlap, double* hist,
                                                                double& spring_loss) {
    kernels::WaltonBraunResult wb;
    wb = kernels::walton_braun_normal(pp.kn, pp.normal_damping, hist[0], overlap);
    hist[0] = wb.delta_max;
    spring_loss = wb.spring_loss;
    // No dashpot; the tangential dashpot scales with sqrt(m* k1) [Deen07 eq. 30].
    return {wb.force, 0.0, wb.stiffness, wb.energy, std::sqrt(m_eff * pp.kn), 0.0};
  }
  /// k_t = stiffness_ratio k1, N/m (also as the contact ends).
  [[gnu::always_inline]] static double tangential_stiffness(const PairParams& pp,
                                                            const kernels::NormalResponse&) {
    return pp.kt;
  }
  /// The rolling spring scales with k1, N/m.
  [[gnu::always_inline]] static double rolling_stiffness(const PairParams& pp,
                                                         const kernels::NormalResponse&) {
    return pp.kn;
  }
};

} // namespace fluidem::contact_models
