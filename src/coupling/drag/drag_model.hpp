// Drag closure registry: the one list of closures (`Closures` below), and what is found through
// it: the name in the case file -> DragModel (the closure's place in the list) -> its type, chosen
// once per run so that the per-particle loop is a template instantiation that inlines (no virtual
// call).
//
//   DragModel m = drag_model_from_string("beetstra");     // set-up; unknown name -> InputError
//   validate(m, typical_input);                           // set-up; bad eps/d/mu -> InputError
//   with_drag_closure(m, [&](auto closure) {              // one instantiation per closure
//     using C = decltype(closure);
//     for (...) k[i] = C::k(in_i);                        // hot loop, inlined
//   });
//
// Every closure type C (one file in this folder) has: C::name (its case-file name),
// C::needs_mean_diameter, C::validate(in), C::k(in) = beta/(1 - eps) and C::beta(in), in the
// convention of drag_common.hpp; C::total_force = true if its force is the TOTAL gas force on a
// particle (drag and the flow's pressure force together, [Hoomans96 eq. 34]), valid only in the
// particle-force form "total" (absent: a drag coefficient, completed by the pressure-gradient or
// the buoyancy form); and, if a case may not choose it, C::refusal (why, and what to use instead).
// The case (core/coupling_settings.hpp) holds only the name, as a string.
//
// Adding a closure: its file here, its #include and its entry in `Closures` below (two lines),
// tests/models/drag/<name>.toml (tools/drag_reference.py) and its row in docs/drag.md.
#pragma once
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>

#include "core/error.hpp"
#include "coupling/drag/beetstra.hpp"
#include "coupling/drag/chang_joint.hpp"
#include "coupling/drag/di_felice.hpp"
#include "coupling/drag/drag_common.hpp"
#include "coupling/drag/ergun.hpp"
#include "coupling/drag/ergun_wen_yu_min.hpp"
#include "coupling/drag/ergun_wen_yu_switch.hpp"
#include "coupling/drag/hill_koch_ladd.hpp"
#include "coupling/drag/koch_hill.hpp"
#include "coupling/drag/rong_2013.hpp"
#include "coupling/drag/syamlal_obrien.hpp"
#include "coupling/drag/tang_2015.hpp"
#include "coupling/drag/tenneti_garg_subramaniam.hpp"
#include "coupling/drag/wen_yu.hpp"
#include "coupling/drag/wen_yu_single.hpp"

namespace fluidem::coupling::drag {

/// The closures, in the order names are listed in messages.
using Closures = std::tuple<Ergun, WenYu, WenYuSingle, ErgunWenYuSwitch, ErgunWenYuMin,
                            HillKochLadd, Beetstra, BeetstraPoly, DiFelice, KochHill, ChangJoint,
                            SyamlalOBrien, TennetiGargSubramaniam, Rong2013, Tang2015>;

inline constexpr std::size_t drag_model_count = std::tuple_size_v<Closures>;

/// A closure of the registry: its place in `Closures` (opaque outside this file).
class DragModel {
public:
  constexpr DragModel() = default;
  constexpr std::size_t index() const { return index_; }
  friend constexpr bool operator==(DragModel, DragModel) = default;

private:
  constexpr explicit DragModel(std::size_t i) : index_(i) {}
  template <std::size_t... I>
  friend constexpr std::array<DragModel, sizeof...(I)> make_drag_models(std::index_sequence<I...>);
  std::size_t index_ = 0;
};

template <std::size_t... I>
constexpr std::array<DragModel, sizeof...(I)> make_drag_models(std::index_sequence<I...>) {
  return {DragModel(I)...};
}

/// Every closure, in the order of `Closures`.
inline constexpr std::array<DragModel, drag_model_count> all_drag_models =
    make_drag_models(std::make_index_sequence<drag_model_count>{});

namespace detail {
template <class C>
constexpr bool is_default() {
  if constexpr (requires { C::is_default; })
    return C::is_default;
  else
    return false;
}

template <class C>
constexpr bool total_force_of() {
  if constexpr (requires { C::total_force; })
    return C::total_force;
  else
    return false;
}

template <class C>
constexpr std::string_view refusal_of() {
  if constexpr (requires { C::refusal; })
    return C::refusal;
  else
    return {};
}

template <std::size_t I, class F>
decltype(auto) dispatch(std::size_t i, F& f) {
  using C = std::tuple_element_t<I, Closures>;
  if constexpr (I + 1 == drag_model_count) {
    return f(C{}); // the last: every index below it was tried
  } else {
    if (i == I) return f(C{});
    return dispatch<I + 1>(i, f);
  }
}
} // namespace detail

/// Calls f(Closure{}) with the closure type of m; returns what f returns. The choice runs once;
/// inside f the closure's functions are known at compile time.
template <class F>
decltype(auto) with_drag_closure(DragModel m, F&& f) {
  return detail::dispatch<0>(m.index(), f);
}

/// The case-file name of m ("ergun", "wen_yu", ...): the closure's own `name`.
std::string_view to_string(DragModel m);
/// Why a case may not choose m (the closure's `refusal`); empty if it may.
std::string_view drag_model_refusal(DragModel m);
/// Whether m's force is the total gas force on a particle (its `total_force`): the closures valid
/// in coupling.particle_force = "total" and only there.
bool is_total_force(DragModel m);
/// Comma-separated list of the names a case may choose (those without a refusal), for error
/// messages.
std::string drag_model_names();
/// The closure named `name`; InputError "unknown drag model 'x' (valid: ...)" if there is none.
DragModel drag_model_from_string(std::string_view name);
/// The closure that declares itself the default (`is_default`): the one a case gets without
/// coupling.drag.
DragModel default_drag_model();
/// The closure of a case's coupling.drag value: empty (not given) is the default, else
/// drag_model_from_string.
DragModel drag_model_named(std::string_view name);
/// The closure a case names in `coupling.drag` (set-up): an unknown name or a refused closure is
/// an InputError at `where` naming the key coupling.drag and what is allowed.
DragModel drag_model_of_case(std::string_view name, const SourceLocation& where);

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
