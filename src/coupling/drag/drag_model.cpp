// Drag closure registry: names, lookup with a helpful error, per-call dispatch helpers.
#include "coupling/drag/drag_model.hpp"

#include <stdexcept>

namespace fluidem::coupling::drag {

std::string_view to_string(DragModel m) {
  return with_drag_closure(m, [](auto c) { return std::string_view(decltype(c)::name); });
}

std::string_view drag_model_refusal(DragModel m) {
  return with_drag_closure(m, [](auto c) { return detail::refusal_of<decltype(c)>(); });
}

bool is_total_force(DragModel m) {
  return with_drag_closure(m, [](auto c) { return detail::total_force_of<decltype(c)>(); });
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

DragModel default_drag_model() {
  for (DragModel m : all_drag_models)
    if (with_drag_closure(m, [](auto c) { return detail::is_default<decltype(c)>(); })) return m;
  throw std::logic_error("no drag closure declares itself the default (drag_model.hpp)");
}

DragModel drag_model_named(std::string_view name) {
  return name.empty() ? default_drag_model() : drag_model_from_string(name);
}

DragModel drag_model_of_case(std::string_view name, const SourceLocation& where) {
  DragModel m;
  try {
    m = drag_model_named(name);
  } catch (const InputError& e) {
    throw InputError(where, "coupling.drag", e.what());
  }
  if (const auto why = drag_model_refusal(m); !why.empty())
    throw InputError(where, "coupling.drag", std::string(why));
  return m;
}

void validate(DragModel m, const DragInput& in) {
  with_drag_closure(m, [&](auto c) { decltype(c)::validate(in); });
}

bool needs_mean_diameter(DragModel m) {
  return with_drag_closure(m, [](auto c) { return decltype(c)::needs_mean_diameter; });
}

double drag_k(DragModel m, const DragInput& in) {
  return with_drag_closure(m, [&](auto c) { return decltype(c)::k(in); });
}

double drag_beta(DragModel m, const DragInput& in) {
  return with_drag_closure(m, [&](auto c) { return decltype(c)::beta(in); });
}

double drag_normalised(DragModel m, const DragInput& in) {
  return normalised_from_k(drag_k(m, in), in);
}

} // namespace fluidem::coupling::drag
