// ContactTable::duration_inputs: the inputs of a contact's duration that its normal model
// declares, for the time-step rule (integrate/contact_time_limit.hpp).
#include <string>
#include <vector>

#include "contact/contact_table.hpp"

namespace fluidem {

std::vector<ContactTable::DurationInput>
ContactTable::duration_inputs(const CaseSpec& spec, const DurationRow& row) const {
  std::vector<DurationInput> inputs;
  const bool wall = row.face >= 0;
  const int a = row.species_a, b = row.species_b;
  const MaterialSpec& ma = spec.species[a].material;
  const MaterialSpec& mb = wall ? spec.domain.wall_material[row.face] : spec.species[b].material;
  const std::string key = wall ? std::string("walls.") + kFaceNames[row.face] + ".restitution"
                               : "species[" + std::to_string(b) + "].restitution";
  const contact_models::Coefficients& normal = contact_.normal.coefficients;
  // The model's coefficients with a usual range, the same for every contact.
  for (const contact_models::Coefficient& c : models_.normal->coefficients) {
    const auto given = contact_models::coefficient(normal, std::string(c.key));
    if (c.usual_hi <= 0.0 || !given) continue;
    inputs.push_back({"contact." + std::string(c.key), std::string(c.unit), *given, c.usual_lo,
                      c.usual_hi, *given, c.longer_when_larger,
                      [this, &spec, ma, mb, wall, key, normal, k = std::string(c.key)](double v) {
                        contact_models::Coefficients changed = normal;
                        changed[k] = v;
                        return mix(spec, ma, mb, wall, key, changed);
                      }});
  }
  if (models_.normal->takes_elastic_constants) {
    // E* from both materials [Zhu07 Table 1]; the softer one sets E* and is the one named (a
    // pair of one species changes both).
    const bool same = !wall && a == b;
    const bool softer_a = ma.youngs_modulus <= mb.youngs_modulus;
    const MaterialSpec& soft = softer_a ? ma : mb;
    const std::string modulus_key =
        softer_a ? "species[" + std::to_string(a) + "].youngs_modulus"
        : wall   ? std::string("walls.") + kFaceNames[row.face] + ".youngs_modulus"
                 : "species[" + std::to_string(b) + "].youngs_modulus";
    auto with_modulus = [=](double e) {
      MaterialSpec sa = ma, sb = mb;
      if (same || softer_a) sa.youngs_modulus = e;
      if (same || !softer_a) sb.youngs_modulus = e;
      return std::pair{sa, sb};
    };
    const auto [ea, eb] = with_modulus(soft.youngs_modulus);
    inputs.push_back({modulus_key, "Pa", soft.youngs_modulus, 1e3, 1.2e12,
                      1.0 / (contact_models::inv_e_part(ea) + contact_models::inv_e_part(eb)),
                      false, [this, &spec, with_modulus, wall, key, normal](double v) {
                        const auto [sa, sb] = with_modulus(v);
                        return mix(spec, sa, sb, wall, key, normal);
                      }});
  }
  return inputs;
}

} // namespace fluidem
