// Tangential model "mindlin_deresiewicz": the simplified Hertz-Mindlin-Deresiewicz force of
// Langston et al. (1994) [Zhu07 Table 1] (contact/kernels/tangential_force.hpp:
// mindlin_deresiewicz), without Table 1's dashpot (C_t = 0: the friction hysteresis is its only
// dissipation):
//   F_t = -mu |F_n| (1 - (1 - |delta_t|/delta_t,max)^{3/2}) delta_t/|delta_t|,
//   delta_t,max = mu delta_n (2 - nu)/(2 (1 - nu)),
// delta_t the tangential displacement (history, turned with the contact normal [Deen07 eq.
// 31-32]), clipped to delta_t,max: full sliding, |F_t| = mu |F_n|. |F_n| is the floored normal
// force (Table 1 writes the elastic part |f_n,e|; with the whole force the gross-sliding impulse
// is J_t = mu J_n, as for "history"). (2 - nu)/(2 (1 - nu)) of a pair is E*/(4 G*) with the
// mixed 1/E* = sum (1 - nu^2)/E, 1/G* = sum (2 - nu)/G [Zhu07 Table 1]: exactly
// (2 - nu)/(2 (1 - nu)) for like materials and for a rigid wall, and what makes the initial
// stiffness 3/2 mu |F_n|/delta_t,max Mindlin's 8 G* sqrt(R* delta_n) under a Hertz force.
// Energy: the whole force is non-conservative (its work goes into the dissipation with the
// full-step velocities, as for the dashpots): its "spring" depends on |F_n| and delta_n, which
// change every step, so a potential would need a spring_loss booking for each of them; as
// dissipation the balance closes to the integrator's accuracy with no further assumption (the
// energy it holds while sticking appears in e_dsp and comes back out as the contact unloads).
#pragma once
#include <array>
#include <cmath>
#include <string>

#include "contact/kernels/normal_force.hpp"
#include "contact/kernels/tangential_force.hpp"
#include "contact/models/contact_point.hpp"
#include "contact/models/declaration.hpp"
#include "contact/models/material_pair.hpp"
#include "contact/pair_params.hpp"
#include "core/error.hpp"

namespace fluidem::contact_models {

struct MindlinDeresiewiczTangential {
  static constexpr Kind kind = Kind::Tangential;
  static constexpr std::string_view name = "mindlin_deresiewicz";
  static constexpr std::string_view summary =
      "simplified Hertz-Mindlin-Deresiewicz, mu |F_n| (1 - (1 - |d_t|/d_t,max)^{3/2}), no "
      "dashpot [Zhu07 Table 1; Langston et al. 1994]";
  static constexpr std::array<Coefficient, 0> coefficients{};
  static constexpr int history_width = 3; ///< the tangential displacement delta_t
  static constexpr bool has_force = true;
  static constexpr std::string_view mixing =
      "mu the arithmetic mean of the two materials, a wall's own for a wall (finite); "
      "(2 - nu)/(2 (1 - nu)) as E*/(4 G*) of the pair [Zhu07 Table 1]";

  static void mix(PairParams& p, const MaterialPair& m, const Coefficients& /*c*/) {
    p.mu = m.mixed.friction;
    if (!std::isfinite(p.mu))
      throw InputError("friction = inf (never sliding) is not allowed with contact.tangential = "
                       "\"mindlin_deresiewicz\", whose slip distance mu delta_n (2 - nu)/"
                       "(2 (1 - nu)) it scales (allowed: a finite number >= 0; \"history\" "
                       "takes inf)");
    const double inv_e = inv_e_part(m.a) + inv_e_part(m.b);
    const double inv_g = inv_g_part(m.a) + inv_g_part(m.b);
    p.slip_factor = inv_g / (4.0 * inv_e); // E*/(4 G*) = (2 - nu)/(2 (1 - nu)) alike
  }

  [[gnu::always_inline]] static void add(ContactOutput& out, const ContactInput& c,
                                         const PairParams& pp, const kernels::NormalResponse&,
                                         double /*k_t*/, double vn, double* hist, double dt) {
    const Vec3 v_t = c.v_rel - c.n * vn;
    Vec3 delta{hist[0], hist[1], hist[2]};
    if (norm2(delta) > 0.0) delta = c.turned(delta);
    const double delta_t_max = pp.mu * c.overlap * pp.slip_factor;
    // Declared, then assigned: so GCC splits the result into scalars and the batch loop stays
    // vectorised (see rolling_constant_torque.hpp).
    kernels::TangentialResult tr;
    tr = kernels::mindlin_deresiewicz(delta, v_t, pp.mu, out.fn_abs, delta_t_max, dt);
    hist[0] = delta.x, hist[1] = delta.y, hist[2] = delta.z;
    out.force += tr.force;
    out.torque_unit = cross(c.n, tr.force);
    out.nc_force += tr.nonconservative;
    out.nc_torque_unit = cross(c.n, tr.nonconservative);
  }

  /// Nothing is stored: its work is booked as dissipation.
  static double stored_energy(const double*, double) { return 0.0; }
};

} // namespace fluidem::contact_models
