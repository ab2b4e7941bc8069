#include "integrate/coarse_graining.hpp"

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "contact/contact_models.hpp"
#include "core/error.hpp"

namespace fluidem {

namespace {

/// InputError at `key` for something W > 1 does not go with.
[[noreturn]] void refuse(const CaseSpec& c, const std::string& key, const std::string& what) {
  throw InputError(c.where(key), key,
                   fmt::format("{} does not go with coarse_graining.ratio = {:.6g} (no scaling of "
                               "it to parcels is derived: docs/coarse-graining.md; allowed: "
                               "coarse_graining.ratio = 1)",
                               what, c.coarse_graining.ratio));
}

void check_supported(const CaseSpec& c) {
  const auto* normal = contact_models::find(contact_models::Kind::Normal, c.contact.normal.name);
  if (normal != nullptr && normal->name == "jkr")
    refuse(c, "contact.normal", "normal = \"jkr\" (adhesion energy)");
  if (c.noncontact.van_der_waals) refuse(c, "van_der_waals", "[van_der_waals]");
  if (c.noncontact.electrostatics) refuse(c, "electrostatics", "[electrostatics]");
  if (c.noncontact.liquid_bridge) refuse(c, "liquid_bridge", "[liquid_bridge]");
  const auto& f = c.coupling.forces;
  if (c.gas) {
    if (f.basset) refuse(c, "coupling.forces.basset", "coupling.forces.basset");
    if (f.saffman) refuse(c, "coupling.forces.saffman", "coupling.forces.saffman");
    if (f.magnus != "off") refuse(c, "coupling.forces.magnus", "coupling.forces.magnus");
    if (f.torque != "off") refuse(c, "coupling.forces.torque", "coupling.forces.torque");
  }
  for (std::size_t k = 0; k < c.inserts.size(); ++k)
    if (c.inserts[k].placement == Placement::File)
      refuse(c, fmt::format("insert[{}].placement", k),
             "placement = \"file\" (a file lists the particles as simulated)");
}

void scale_elastic_constants(MaterialSpec& m, double f) {
  if (std::isfinite(m.youngs_modulus)) m.youngs_modulus *= f; // a rigid wall stays rigid
  if (m.shear_modulus && std::isfinite(*m.shear_modulus)) *m.shear_modulus *= f;
}

} // namespace

CaseSpec simulated_case(const CaseSpec& user) {
  const CoarseGrainingSpec& cg = user.coarse_graining;
  if (!cg.active()) return user;
  check_supported(user);
  CaseSpec s = user;
  const double w = cg.ratio;
  const double sd = coarse_graining::diameter_factor(w);
  for (SpeciesSpec& sp : s.species) sp.diameter *= sd; // [Chang08 eq. 2.27]
  for (InsertSpec& ins : s.inserts) // a size distribution's diameters (fractions unchanged)
    if (ins.size_distribution) {
      SizeDistributionSpec& dist = *ins.size_distribution;
      for (double* x : {&dist.mean, &dist.std, &dist.median, &dist.min, &dist.max}) *x *= sd;
      for (double& x : dist.diameters) x *= sd;
    }
  const auto* normal = contact_models::find(contact_models::Kind::Normal, s.contact.normal.name);
  if (normal != nullptr && normal->takes_elastic_constants) { // Hertz-Mindlin: E and G
    const double f = coarse_graining::youngs_modulus_factor(cg.contact_scaling, w);
    for (SpeciesSpec& sp : s.species) scale_elastic_constants(sp.material, f);
    for (MaterialSpec& m : s.domain.wall_material) scale_elastic_constants(m, f);
  } else if (auto it = s.contact.normal.coefficients.find("stiffness");
             it != s.contact.normal.coefficients.end()) { // linear, Walton-Braun
    it->second *= coarse_graining::linear_stiffness_factor(cg.contact_scaling, w);
  }
  s.coupling.drag_diameter_factor = coarse_graining::drag_diameter_factor(cg.drag_diameter, w);
  return s;
}

double simulated_over_user(const CaseSpec& spec, std::string_view key) {
  const CoarseGrainingSpec& cg = spec.coarse_graining;
  if (!cg.active()) return 1.0;
  if (key.ends_with(".diameter")) return coarse_graining::diameter_factor(cg.ratio);
  const auto* normal = contact_models::find(contact_models::Kind::Normal, spec.contact.normal.name);
  const bool elastic = normal != nullptr && normal->takes_elastic_constants;
  if (elastic && (key.ends_with(".youngs_modulus") || key.ends_with(".shear_modulus")))
    return coarse_graining::youngs_modulus_factor(cg.contact_scaling, cg.ratio);
  if (!elastic && key == "contact.stiffness")
    return coarse_graining::linear_stiffness_factor(cg.contact_scaling, cg.ratio);
  return 1.0;
}

CaseSpec user_values(const CaseSpec& simulated, const CaseSpec& user) {
  if (!user.coarse_graining.active()) return simulated;
  CaseSpec c = simulated;
  c.species = user.species;
  c.inserts = user.inserts;
  c.domain.wall_material = user.domain.wall_material;
  c.contact.normal.coefficients = user.contact.normal.coefficients;
  c.coupling.drag_diameter_factor = user.coupling.drag_diameter_factor;
  return c;
}

} // namespace fluidem
