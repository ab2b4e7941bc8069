// Names of the coupling models for the case file.
#include "core/coupling_settings.hpp"
#include "core/error.hpp"

namespace fluidem::coupling {

namespace drag {
std::string_view to_string(DragModel m) {
  return drag_model_name_table[static_cast<std::size_t>(m)];
}

std::string_view drag_model_refusal(DragModel m) {
  if (m != DragModel::wen_yu_single) return {};
  return "\"wen_yu_single\" is not allowed in a coupled case: it is the total gas force on a "
         "particle, drag and pressure together [Hoomans96 eq. 34-37], meant to be used without "
         "a pressure-gradient force, but the exchange always adds one (-V grad p in gas.model = "
         "\"A\", the drag divided by the porosity plus the buoyancy term in \"B\"), so the "
         "pressure force would be counted twice (about 1/eps times the right force). Use "
         "\"wen_yu\" (the same Wen & Yu correlation as a drag coefficient [Deen07 eq. 4], which "
         "the exchange completes with the pressure force) or \"ergun_wen_yu\" (the closure of "
         "the gas phase of [Hoomans96 eq. 45-46])";
}

std::string drag_model_names() {
  std::string s;
  for (DragModel m : all_drag_models) {
    if (!drag_model_refusal(m).empty()) continue;
    if (!s.empty()) s += ", ";
    s += to_string(m);
  }
  return s;
}

DragModel drag_model_from_string(std::string_view name) {
  for (DragModel m : all_drag_models)
    if (to_string(m) == name) return m;
  throw InputError("unknown drag model '" + std::string(name) + "' (valid: " + drag_model_names() +
                   ")");
}
} // namespace drag

std::string_view to_string(PorosityMethod m) {
  return m == PorosityMethod::cell ? "cell" : "porous_cube";
}

PorosityMethod porosity_method_from_string(std::string_view name, const std::string& key) {
  if (name == "cell") return PorosityMethod::cell;
  if (name == "porous_cube") return PorosityMethod::porous_cube;
  throw InputError(key + " = '" + std::string(name) +
                   "': unknown porosity method (valid: cell, porous_cube)");
}

} // namespace fluidem::coupling
