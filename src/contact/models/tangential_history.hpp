// Tangential model "history": spring-dashpot with history and a Coulomb limit [Deen07 eq. 28-32]
// (contact/kernels/tangential_force.hpp: tangential_spring). The history turns with the contact
// normal [Deen07 eq. 31-32]; k_t is the normal model's (linear: k_t from [contact]; Hertz:
// Mindlin's); eta_t = factor(beta0) sqrt(2 k_t/(7 k_n)) times the normal dashpot's scale
// [Deen07 eq. 30].
#pragma once
#include <array>
#include <cmath>

#include "contact/kernels/normal_force.hpp"
#include "contact/kernels/tangential_force.hpp"
#include "contact/models/contact_point.hpp"
#include "contact/models/declaration.hpp"
#include "contact/models/material_pair.hpp"
#include "contact/pair_params.hpp"

namespace fluidem::contact_models {

struct HistoryTangential {
  static constexpr Kind kind = Kind::Tangential;
  static constexpr std::string_view name = "history";
  static constexpr std::string_view summary =
      "spring with history, Coulomb-limited [Deen07 eq. 28-32]";
  static constexpr bool is_default = true;
  static constexpr std::array<Coefficient, 0> coefficients{};
  static constexpr int history_width = 3; ///< the tangential displacement
  static constexpr bool has_force = true;
  static constexpr std::string_view mixing =
      "mu and beta0 the arithmetic means of the two materials, a wall's own for a wall";

  /// After the normal model's mix (k_n, k_t).
  static void mix(PairParams& p, const MaterialPair& m, const Coefficients& /*c*/) {
    p.mu = m.mixed.friction; // inf: never sliding (tangential_spring)
    p.tangential_damping = kernels::restitution_damping_factor(m.mixed.tangential_restitution);
    p.tangential_root = std::sqrt(2.0 * p.kt / (7.0 * p.kn));
  }

  [[gnu::always_inline]] static void add(ContactOutput& out, const ContactInput& c,
                                         const PairParams& pp, const kernels::NormalResponse& nr,
                                         double k_t, double vn, double* hist, double dt) {
    const Vec3 v_t = c.v_rel - c.n * vn;
    Vec3 delta{hist[0], hist[1], hist[2]};
    if (norm2(delta) > 0.0) delta = c.turned(delta);
    // eta_t = factor sqrt(2/7 m* k_t) [Deen07 eq. 30], from the normal dashpot's sqrt(m* K).
    const double eta_t = pp.tangential_damping * pp.tangential_root * nr.damping_scale;
    const auto tr = kernels::tangential_spring(delta, v_t, k_t, eta_t, pp.mu, out.fn_abs, dt);
    hist[0] = delta.x, hist[1] = delta.y, hist[2] = delta.z;
    out.force += tr.force;
    out.torque_unit = cross(c.n, tr.force);
    out.nc_force += tr.nonconservative;
    out.nc_torque_unit = cross(c.n, tr.nonconservative);
    out.elastic += tr.energy;
    out.spring_loss += tr.spring_loss;
  }

  /// The energy of the spring whose history is `hist`, at stiffness k_t, J.
  [[gnu::always_inline]] static double stored_energy(const double* hist, double k_t) {
    return 0.5 * k_t * (hist[0] * hist[0] + hist[1] * hist[1] + hist[2] * hist[2]);
  }
};

} // namespace fluidem::contact_models
