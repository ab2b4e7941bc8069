// Rolling model "spring_dashpot": method 1 of [Zhu07 Table 1] (Iwashita & Oda 1998; k_r, C_r as
// in Ai et al. 2011), with a history that turns with the contact normal
// (contact/kernels/rolling_torque.hpp: rolling_spring_dashpot):
//   M_r = -k_r theta_r - C_r dtheta_r/dt, |M_r| <= mu_r R* |F_n|,
//   k_r = 2.25 k_n mu_r^2 R*^2 (k_n: the normal model's stiffness),  C_r = f(e) sqrt(I_r k_r).
#pragma once
#include <array>
#include <cmath>

#include "contact/kernels/normal_force.hpp"
#include "contact/kernels/rolling_torque.hpp"
#include "contact/models/contact_point.hpp"
#include "contact/models/declaration.hpp"
#include "contact/models/material_pair.hpp"
#include "contact/pair_params.hpp"

namespace fluidem::contact_models {

struct SpringDashpotRolling {
  static constexpr Kind kind = Kind::Rolling;
  static constexpr std::string_view name = "spring_dashpot";
  static constexpr std::string_view summary =
      "spring-dashpot with history, limited by mu_r R* |F_n| [Zhu07 Table 1, method 1]";
  static constexpr std::array<Coefficient, 0> coefficients{};
  static constexpr int history_width = 3; ///< the rolling angle theta_r
  static constexpr bool has_torque = true;
  static constexpr std::string_view mixing =
      "mu_r the arithmetic mean of the two materials, a wall's own for a wall; the dashpot from "
      "the mixed e [Deen07 eq. 27]";

  static void mix(PairParams& p, const MaterialPair& m, const Coefficients& /*c*/) {
    p.mu_r = m.mixed.rolling_friction;
    p.rolling_damping = kernels::restitution_damping_factor(m.mixed.restitution);
  }

  /// `hist`: this model's own history values.
  [[gnu::always_inline]] static void add(ContactOutput& out, const ContactInput& c,
                                         const PairParams& pp, double k_rolling, double* hist,
                                         double dt) {
    const Vec3 w_roll = c.w_rel - c.n * dot(c.w_rel, c.n);
    Vec3 theta{hist[0], hist[1], hist[2]};
    if (norm2(theta) > 0.0) theta = c.turned(theta);
    const double k_r = 2.25 * k_rolling * pp.mu_r * pp.mu_r * c.r_eff * c.r_eff;
    const double c_r = pp.rolling_damping * std::sqrt(k_r / c.inv_inertia_sum);
    kernels::RollingResult rr; // declared, then assigned: see rolling_constant_torque.hpp
    rr = kernels::rolling_spring_dashpot(theta, w_roll, k_r, c_r, pp.mu_r, c.r_eff, out.fn_abs, dt);
    hist[0] = theta.x, hist[1] = theta.y, hist[2] = theta.z;
    out.torque_roll = rr.torque;
    out.nc_torque_roll = rr.nonconservative;
    out.elastic += rr.energy;
    out.spring_loss += rr.spring_loss;
  }

  /// The energy of the spring whose history is `hist`, J.
  [[gnu::always_inline]] static double stored_energy(const double* hist, const PairParams& pp,
                                                     double k_rolling, double r_eff) {
    const double k_r = 2.25 * k_rolling * pp.mu_r * pp.mu_r * r_eff * r_eff;
    return 0.5 * k_r * (hist[0] * hist[0] + hist[1] * hist[1] + hist[2] * hist[2]);
  }
};

} // namespace fluidem::contact_models
