#include "contact/contact_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "contact/models/model_list.hpp"
#include "core/material_mixing.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

namespace {

using contact_models::inv_e_part;
using contact_models::with_model;

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
    : n_(static_cast<int>(spec.species.size())), models_(contact_models::check(spec)),
      contact_(spec.contact) {
  for (const contact_models::Kind kind : contact_models::kKinds)
    if (!models_.of(kind).refusal.empty()) {
      const std::string key = std::string("contact.") + contact_models::kind_key(kind);
      throw InputError(spec.where(key), key, contact_models::refusal(models_.of(kind)));
    }
  // JKR's contact lives on in tension (delta < 0), where the slip distance of
  // mindlin_deresiewicz, mu delta_n (2 - nu)/(2 (1 - nu)), would be negative.
  if (models_.of(contact_models::Kind::Normal).name == "jkr" &&
      models_.of(contact_models::Kind::Tangential).name == "mindlin_deresiewicz")
    throw InputError(spec.where("contact.tangential"), "contact.tangential",
                     "\"mindlin_deresiewicz\" cannot follow normal = \"jkr\", whose contacts "
                     "pull with a negative overlap, where its slip distance mu delta_n (2 - nu)/"
                     "(2 (1 - nu)) is negative (allowed with jkr: \"history\" or \"none\")");
  const auto& c = spec.contact;
  v_char_ =
      c.characteristic_velocity ? *c.characteristic_velocity : auto_characteristic_velocity(spec);
  auto make = [&](const MaterialSpec& a, const MaterialSpec& b, bool wall, const std::string& key) {
    return mix(spec, a, b, wall, key, contact_.normal.coefficients);
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

PairParams ContactTable::mix(const CaseSpec& spec, const MaterialSpec& a, const MaterialSpec& b,
                             bool wall, const std::string& key,
                             const contact_models::Coefficients& normal) const {
  PairParams p;
  const MixedCoefficients mixed = wall ? wall_coefficients(b) : mix_pair(a, b);
  if (!(mixed.restitution > 0.0)) throw InputError(spec.where(key), key, plastic_limit_message());
  p.restitution = mixed.restitution;
  p.e_star = 1.0 / (inv_e_part(a) + inv_e_part(b));
  const contact_models::MaterialPair pair{a, b, wall, mixed};
  // The normal model first: the tangential and rolling models scale with its stiffnesses.
  with_model(contact_models::NormalModels{}, models_.normal->index, [&]<class M>(M) {
    if constexpr (!contact_models::is_refused<M>()) M::mix(p, pair, normal);
  });
  with_model(contact_models::TangentialModels{}, models_.tangential->index,
             [&]<class M>(M) { M::mix(p, pair, contact_.tangential.coefficients); });
  with_model(contact_models::RollingModels{}, models_.rolling->index,
             [&]<class M>(M) { M::mix(p, pair, contact_.rolling.coefficients); });
  return p;
}

int ContactTable::history_width() const {
  return models_.normal->history_width + models_.tangential->history_width +
         models_.rolling->history_width;
}

double ContactTable::contact_duration(double m_eff, double r_eff, const PairParams& p,
                                      bool wall) const {
  // The force pulse, which ends when the floored force vanishes (normal_damping.hpp): shorter
  // than the time the overlap lasts ([Deen07 eq. 41] for a force that may pull). At
  // impact_speed(wall) for a model whose duration depends on it: a pair's relative speed, not
  // one particle's.
  return with_model(contact_models::NormalModels{}, models_.normal->index, [&]<class M>(M) {
    if constexpr (contact_models::is_refused<M>())
      return 0.0;
    else
      return M::duration(m_eff, r_eff, p, impact_speed(wall));
  });
}

double ContactTable::overlap_under(double f, double r_eff, const PairParams& p) const {
  return with_model(contact_models::NormalModels{}, models_.normal->index, [&]<class M>(M) {
    if constexpr (contact_models::is_refused<M>())
      return 0.0;
    else
      return M::overlap_under(f, r_eff, p);
  });
}

double ContactTable::attached_reach(double r_max) const {
  return with_model(contact_models::NormalModels{}, models_.normal->index, [&]<class M>(M) {
    double reach = 0.0;
    if constexpr (requires { M::detaches_in_tension; }) {
      for (const PairParams& p : pp_) reach = std::max(reach, M::detach_distance(p, r_max));
      for (const PairParams& p : pw_) reach = std::max(reach, M::detach_distance(p, r_max));
    }
    // A margin of 1e-9 of it: the list's test (gap < reach + skin) and the walk's (overlap >
    // -delta_c) round differently, and an attached pair the list dropped would end unbooked.
    return reach * (1.0 + 1e-9);
  });
}

} // namespace fluidem
