#include "contact/contact_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "contact/kernels/normal_damping.hpp"
#include "contact/kernels/normal_force.hpp"
#include "core/material_mixing.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

namespace {

// A rigid wall (youngs_modulus = inf) adds nothing: the particle's compliance alone remains.
double inv_e_part(const MaterialSpec& m) {
  return (1.0 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus;
}
double inv_g_part(const MaterialSpec& m) {
  return (2.0 - m.poisson_ratio) / shear_modulus_of(m);
}

/// Why a soft-sphere contact refuses e = 0 (docs/contact.md).
std::string plastic_limit_message() {
  return "e = 0 (a fully plastic impact) cannot be reached by a soft-sphere contact (allowed: "
         "(0, 1]): its normal force never pulls, so a damped impact always rebounds, and e goes "
         "to 0 only as the damping grows without bound (e = 0.01 needs the damping ratio 4.8, "
         "e = 0.001 needs 16). Give a small e such as 0.01 for a nearly plastic impact "
         "(docs/contact.md), or use simulation.engine = \"hard_sphere\", which takes e = 0 exactly";
}

double auto_characteristic_velocity(const CaseSpec& spec) {
  const auto& g = spec.simulation.gravity;
  const double gabs = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  double height = 0.0;
  if (gabs > 0.0) {
    for (int a = 0; a < 3; ++a)
      height += std::abs(g[a]) / gabs * (spec.domain.hi[a] - spec.domain.lo[a]);
  }
  double v_insert = 0.0;
  for (const auto& ins : spec.inserts) {
    const auto& v = ins.velocity;
    const double s =
        std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + std::sqrt(3.0) * ins.velocity_spread;
    v_insert = std::max(v_insert, s);
  }
  return std::max(0.1, std::sqrt(2.0 * gabs * height) + v_insert);
}

} // namespace

ContactTable::ContactTable(const CaseSpec& spec, std::vector<bool> with_particles)
    : n_(static_cast<int>(spec.species.size())), normal_(spec.contact.normal),
      tangential_(spec.contact.tangential), rolling_(spec.contact.rolling) {
  const auto& c = spec.contact;
  if (normal_ == NormalModel::WaltonBraun) {
    throw InputError(spec.where("contact.normal"), "contact.normal",
                     "\"walton_braun\" is not implemented yet (implemented: \"linear\", "
                     "\"hertz\")");
  }
  v_char_ =
      c.characteristic_velocity ? *c.characteristic_velocity : auto_characteristic_velocity(spec);

  if (normal_ == NormalModel::Hertz && c.stiffness_ratio) {
    throw InputError(spec.where("contact.stiffness_ratio"), "contact.stiffness_ratio",
                     "not allowed with normal = \"hertz\" (Mindlin's k_t = 8 G* sqrt(R* delta) "
                     "follows from the materials: set poisson_ratio or shear_modulus per "
                     "species and wall)");
  }
  auto make = [&](const MaterialSpec& a, const MaterialSpec& b, bool wall, const std::string& key) {
    PairParams p;
    const MixedCoefficients mixed = wall ? wall_coefficients(b) : mix_pair(a, b);
    const double e = mixed.restitution;
    const double beta0 = mixed.tangential_restitution;
    if (!(e > 0.0)) throw InputError(spec.where(key), key, plastic_limit_message());
    p.mu = mixed.friction; // inf: never sliding (tangential_spring)
    p.mu_r = mixed.rolling_friction;
    p.restitution = e;
    p.e_star = 1.0 / (inv_e_part(a) + inv_e_part(b));
    p.tangential_damping = kernels::restitution_damping_factor(beta0);
    p.rolling_damping = kernels::restitution_damping_factor(e);
    if (normal_ == NormalModel::Linear) {
      p.kn = c.stiffness;
      p.normal_damping = kernels::linear_damping_factor(e);
      // [Deen07 eq. 43]: equal normal and tangential contact durations [Deen07 eq. 41-42] (for
      // a force that may pull; kept as published).
      const double lb = beta0 > 0.0 ? std::log(beta0) : 0.0;
      const double le = std::log(e);
      const double pi2 = std::numbers::pi * std::numbers::pi;
      const double ratio =
          c.stiffness_ratio ? *c.stiffness_ratio : 2.0 / 7.0 * (pi2 + lb * lb) / (pi2 + le * le);
      p.kt = ratio * p.kn;
    } else {
      p.kn = 4.0 / 3.0 * p.e_star;
      p.normal_damping = kernels::hertz_damping_alpha(e);
      // Mindlin k_t = 8 G* sqrt(R* delta) [Chang08 eq. 2.16], 1/G* = (2 - nu_a)/G_a +
      // (2 - nu_b)/G_b [Zhu07 Table 1].
      p.kt = 8.0 / (inv_g_part(a) + inv_g_part(b));
    }
    p.tangential_root = std::sqrt(2.0 * p.kt / (7.0 * p.kn));
    return p;
  };

  // Only species with particles meet: the others get no coefficients, no durations and no say
  // in the time step.
  used_ = std::move(with_particles);
  if (used_.empty()) used_.assign(n_, true);
  const std::vector<bool>& used = used_;
  pp_.resize(static_cast<std::size_t>(n_) * n_);
  pw_.resize(static_cast<std::size_t>(n_) * 6);
  t_contact_min_ = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n_; ++i) {
    const auto& si = spec.species[i];
    const double ri = 0.5 * si.diameter, mi = sphere_mass(ri, si.density);
    for (int j = 0; j < n_ && used[i]; ++j) {
      if (!used[j]) continue;
      const auto& sj = spec.species[j];
      pp_[i * n_ + j] =
          make(si.material, sj.material, false, "species[" + std::to_string(j) + "].restitution");
      if (j < i) continue;
      const double rj = 0.5 * sj.diameter, mj = sphere_mass(rj, sj.density);
      const double t =
          contact_duration(mi * mj / (mi + mj), ri * rj / (ri + rj), pp_[i * n_ + j], false);
      rows_.push_back({si.name + "-" + sj.name, t, i, j, -1});
      t_contact_min_ = std::min(t_contact_min_, t);
    }
    // Every species has its wall coefficients (6 per species: the contact loop compares them to
    // find walls alike for all species).
    int first_wall = -1;
    for (int f = 0; f < 6; ++f) {
      // A face on a periodic axis (or a y face of discs) has no contacts: its material is not
      // checked, and it takes the parameters of a face that has (walls_uniform in the loop).
      if (spec.domain.periodic[f / 2]) continue;
      if (spec.simulation.dimension == 2 && f / 2 == 1) continue; // no y walls for discs
      pw_[i * 6 + f] = make(si.material, spec.domain.wall_material[f], true,
                            std::string("walls.") + kFaceNames[f] + ".restitution");
      if (first_wall < 0) first_wall = f;
      if (!used[i]) continue;
      const double t = contact_duration(mi, ri, pw_[i * 6 + f], true);
      rows_.push_back({si.name + "-wall " + kFaceNames[f], t, i, i, f});
      t_contact_min_ = std::min(t_contact_min_, t);
    }
    for (int f = 0; f < 6 && first_wall >= 0; ++f)
      if (spec.domain.periodic[f / 2] || (spec.simulation.dimension == 2 && f / 2 == 1))
        pw_[i * 6 + f] = pw_[i * 6 + first_wall];
  }
}

MemoryShare ContactTable::memory_share(const CaseSpec& spec) {
  const auto n = static_cast<double>(spec.species.size());
  return {"species",
          fmt::format("the contact coefficients of {:.0f} species ({:.3g} pairs)", n, n * n),
          n * n * static_cast<double>(sizeof(PairParams)) +
              n * 6.0 * static_cast<double>(sizeof(PairParams))};
}

double ContactTable::contact_duration(double m_eff, double r_eff, const PairParams& p,
                                      bool wall) const {
  // The force pulse, which ends when the floored force vanishes (normal_damping.hpp): shorter
  // than the time the overlap lasts ([Deen07 eq. 41] for a force that may pull). Hertz at
  // impact_speed(wall): a pair's relative speed, not one particle's.
  if (normal_ == NormalModel::Linear)
    return kernels::linear_contact_duration(m_eff, p.kn, p.normal_damping);
  return kernels::hertz_contact_duration(m_eff, p.kn * std::sqrt(r_eff), p.normal_damping,
                                         impact_speed(wall));
}

} // namespace fluidem
