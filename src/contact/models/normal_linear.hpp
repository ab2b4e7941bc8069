// Normal model "linear": spring-dashpot [Deen07 eq. 24-26], the force floored at zero
// [Schwager & Poeschel 2008] (contact/kernels/normal_force.hpp: linear_normal):
//   F_n = max(0, k_n delta + eta_n v_n),  eta_n = f(e) sqrt(m* k_n)  (f: normal_damping.hpp)
// k_n and k_t are [contact] keys, the same for every contact, walls included; "auto" k_t/k_n
// gives equal normal and tangential contact durations [Deen07 eq. 41-43].
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

struct LinearNormal {
  static constexpr Kind kind = Kind::Normal;
  static constexpr std::string_view name = "linear";
  static constexpr std::string_view summary = "linear spring-dashpot [Deen07 eq. 24-26]";
  static constexpr std::array<Coefficient, 2> coefficients{{
      {.key = "stiffness",
       .unit = "N/m",
       .range = Interval::positive(),
       .given = Given::Required,
       .meaning = "k_n [Deen07 eq. 24]",
       .usual_lo = 1.0,
       .usual_hi = 1e10,
       .longer_when_larger = false},
      {.key = "stiffness_ratio",
       .unit = "",
       .range = Interval::positive(),
       .given = Given::Auto,
       .meaning = "k_t/k_n; \"auto\": 2/7 (pi^2 + ln^2 beta0)/(pi^2 + ln^2 e), equal normal and "
                  "tangential contact durations [Deen07 eq. 43]",
       .mixing = "the same for every species pair and wall; \"auto\": from the pair's mixed e "
                 "and beta0"},
  }};
  static constexpr int history_width = 0;
  static constexpr bool takes_elastic_constants = false;
  static constexpr std::string_view mixing = "k_n, k_t from [contact], the same for every "
                                             "contact; the dashpot from the mixed e";
  /// Its springs do not vanish as the overlap closes: a contact that ends releases their energy.
  static constexpr bool springs_hold_energy_at_separation = true;

  static void mix(PairParams& p, const MaterialPair& m, const Coefficients& c) {
    p.kn = c.at("stiffness");
    p.normal_damping = kernels::linear_damping_factor(m.mixed.restitution);
    p.kt = stiffness_ratio(m, c) * p.kn;
  }

  /// k_t/k_n: the case's `stiffness_ratio`, or "auto": [Deen07 eq. 43], equal normal and
  /// tangential contact durations [Deen07 eq. 41-42] (for a force that may pull; kept as
  /// published), from the pair's mixed e and beta0. (walton_braun takes the same rule.)
  static double stiffness_ratio(const MaterialPair& m, const Coefficients& c) {
    const double e = m.mixed.restitution, beta0 = m.mixed.tangential_restitution;
    const double lb = beta0 > 0.0 ? std::log(beta0) : 0.0;
    const double le = std::log(e);
    const double pi2 = std::numbers::pi * std::numbers::pi;
    const auto given = coefficient(c, "stiffness_ratio");
    return given ? *given : 2.0 / 7.0 * (pi2 + lb * lb) / (pi2 + le * le);
  }

  /// The force pulse of a head-on impact, s (normal_damping.hpp).
  static double duration(double m_eff, double /*r_eff*/, const PairParams& p,
                         double /*impact_speed*/) {
    return kernels::linear_contact_duration(m_eff, p.kn, p.normal_damping);
  }

  /// The overlap under a static force f, m.
  static double overlap_under(double f, double /*r_eff*/, const PairParams& p) { return f / p.kn; }

  [[gnu::always_inline]] static kernels::NormalResponse
  respond(const PairParams& pp, double /*r_eff*/, double m_eff, double overlap) {
    return kernels::linear_normal(pp.kn, pp.normal_damping, m_eff, overlap);
  }
  /// The tangential stiffness at a contact with response `nr` (also as it ends: nr = {}), N/m.
  [[gnu::always_inline]] static double tangential_stiffness(const PairParams& pp,
                                                            const kernels::NormalResponse&) {
    return pp.kt;
  }
  /// The normal stiffness the rolling spring scales with (also as it ends: nr = {}), N/m.
  [[gnu::always_inline]] static double rolling_stiffness(const PairParams& pp,
                                                         const kernels::NormalResponse&) {
    return pp.kn;
  }
};

} // namespace fluidem::contact_models
