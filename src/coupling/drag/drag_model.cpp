// Drag closure registry: names, lookup with a helpful error, per-call dispatch helpers.
#include "coupling/drag/drag_model.hpp"

namespace fluidem::coupling::drag {

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
