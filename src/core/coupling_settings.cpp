// Names of the coupling models for the case file.
#include "core/coupling_settings.hpp"
#include "core/error.hpp"

namespace fluidem::coupling {

namespace drag {
std::string_view to_string(DragModel m) {
  return drag_model_name_table[static_cast<std::size_t>(m)];
}

std::string drag_model_names() {
  std::string s;
  for (DragModel m : all_drag_models) {
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
