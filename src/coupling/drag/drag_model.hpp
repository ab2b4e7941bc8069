// Drag closure registry: the name in the case file -> DragModel -> one closure type, chosen once
// per run so the per-particle loop is a template instantiation that inlines (no virtual call).
//
//   DragModel m = drag_model_from_string("beetstra");     // set-up; unknown name -> InputError
//   validate(m, typical_input);                           // set-up; bad eps/d/mu -> InputError
//   with_drag_closure(m, [&](auto closure) {              // one instantiation per closure
//     using C = decltype(closure);
//     for (...) k[i] = C::k(in_i);                        // hot loop, inlined
//   });
//
// Every closure type C has: C::name, C::needs_mean_diameter, C::validate(in), C::k(in) =
// beta/(1 - eps) and C::beta(in), in the convention of drag_common.hpp.
#pragma once
#include <array>
#include <string>
#include <string_view>

#include "core/coupling_settings.hpp"
#include "coupling/drag/beetstra.hpp"
#include "coupling/drag/chang_joint.hpp"
#include "coupling/drag/di_felice.hpp"
#include "coupling/drag/drag_common.hpp"
#include "coupling/drag/ergun.hpp"
#include "coupling/drag/ergun_wen_yu_min.hpp"
#include "coupling/drag/ergun_wen_yu_switch.hpp"
#include "coupling/drag/hill_koch_ladd.hpp"
#include "coupling/drag/koch_hill.hpp"
#include "coupling/drag/wen_yu.hpp"
#include "coupling/drag/wen_yu_single.hpp"

namespace fluidem::coupling::drag {

/// Calls f(Closure{}) with the closure type of m; returns what f returns. The switch runs once;
/// inside f the closure's functions are known at compile time.
template <class F>
decltype(auto) with_drag_closure(DragModel m, F&& f) {
  switch (m) {
  case DragModel::ergun:
    return f(Ergun{});
  case DragModel::wen_yu:
    return f(WenYu{});
  case DragModel::wen_yu_single:
    return f(WenYuSingle{});
  case DragModel::ergun_wen_yu:
    return f(ErgunWenYuSwitch{});
  case DragModel::ergun_wen_yu_min:
    return f(ErgunWenYuMin{});
  case DragModel::hill_koch_ladd:
    return f(HillKochLadd{});
  case DragModel::beetstra:
    return f(Beetstra{});
  case DragModel::beetstra_poly:
    return f(BeetstraPoly{});
  case DragModel::di_felice:
    return f(DiFelice{});
  case DragModel::koch_hill:
    return f(KochHill{});
  case DragModel::chang_joint:
    return f(ChangJoint{});
  }
  return f(Ergun{}); // unreachable: every enumerator is handled above
}

/// Set-up check of one representative input for model m (InputError naming the quantity).
void validate(DragModel m, const DragInput& in);

/// Does model m need DragInput::d_mean (Sauter mean diameter)?
bool needs_mean_diameter(DragModel m);

/// Convenience (dispatches per call; for set-up, tests and diagnostics, not the hot loop):
/// K = beta/(1 - eps), beta, and the normalised drag F of model m.
double drag_k(DragModel m, const DragInput& in);
double drag_beta(DragModel m, const DragInput& in);
double drag_normalised(DragModel m, const DragInput& in);

} // namespace fluidem::coupling::drag
