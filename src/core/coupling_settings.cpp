// Names of the coupling models for the case file.
#include "core/coupling_settings.hpp"
#include "core/error.hpp"

namespace fluidem::coupling {

std::string_view to_string(PorosityMethod m) {
  return m == PorosityMethod::cell ? "cell" : "porous_cube";
}

std::string_view to_string(CouplingMode m) {
  switch (m) {
  case CouplingMode::two_way:
    return "two_way";
  case CouplingMode::one_way:
    return "one_way";
  case CouplingMode::frozen:
    return "frozen";
  }
  return "?";
}

std::string_view to_string(ParticleForceForm f) {
  switch (f) {
  case ParticleForceForm::pressure_gradient:
    return "pressure_gradient";
  case ParticleForceForm::buoyancy:
    return "buoyancy";
  case ParticleForceForm::total:
    return "total";
  }
  return "?";
}

PorosityMethod porosity_method_from_string(std::string_view name, const std::string& key) {
  if (name == "cell") return PorosityMethod::cell;
  if (name == "porous_cube") return PorosityMethod::porous_cube;
  throw InputError(key + " = '" + std::string(name) +
                   "': unknown porosity method (valid: cell, porous_cube)");
}

} // namespace fluidem::coupling
