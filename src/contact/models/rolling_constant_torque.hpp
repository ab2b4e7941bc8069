// Rolling model "constant_torque": method 2 of [Zhu07 Table 1] (Zhou et al. 1999),
// M_r = -mu_r R* |F_n| w_rel/|w_rel|, capped so that it cannot reverse the relative rolling
// velocity within one step (contact/kernels/rolling_torque.hpp: rolling_constant_torque).
#pragma once
#include <array>

#include "contact/kernels/rolling_torque.hpp"
#include "contact/models/contact_point.hpp"
#include "contact/models/declaration.hpp"
#include "contact/models/material_pair.hpp"
#include "contact/pair_params.hpp"

namespace fluidem::contact_models {

struct ConstantTorqueRolling {
  static constexpr Kind kind = Kind::Rolling;
  static constexpr std::string_view name = "constant_torque";
  static constexpr std::string_view summary =
      "constant torque mu_r R* |F_n| [Zhu07 Table 1, method 2]";
  static constexpr std::array<Coefficient, 0> coefficients{};
  static constexpr int history_width = 0;
  static constexpr bool has_torque = true;
  static constexpr std::string_view mixing =
      "mu_r the arithmetic mean of the two materials, a wall's own for a wall";

  static void mix(PairParams& p, const MaterialPair& m, const Coefficients& /*c*/) {
    p.mu_r = m.mixed.rolling_friction;
  }

  [[gnu::always_inline]] static void add(ContactOutput& out, const ContactInput& c,
                                         const PairParams& pp, double /*k_rolling*/,
                                         double* /*hist*/, double dt) {
    const Vec3 w_roll = c.w_rel - c.n * dot(c.w_rel, c.n);
    // Declared, then assigned (not initialised from the call): so GCC splits the result into
    // scalars and the batch loop stays vectorised (initialised, it stayed a struct in memory,
    // and the loop was not if-converted).
    kernels::RollingResult rr;
    rr = kernels::rolling_constant_torque(w_roll, pp.mu_r, c.r_eff, out.fn_abs, c.inv_inertia_sum,
                                          dt);
    out.torque_roll = rr.torque;
    out.nc_torque_roll = rr.nonconservative;
    out.elastic += rr.energy;
    out.spring_loss += rr.spring_loss;
  }
  static double stored_energy(const double*, const PairParams&, double, double) { return 0.0; }
};

} // namespace fluidem::contact_models
