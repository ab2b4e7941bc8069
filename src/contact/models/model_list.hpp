// The contact sub-models, by kind: the one place a new model is listed (its #include and its
// entry below). The order of a list is the order the case-file errors name the models in.
//
// Every model is a type that declares itself (contact/models/declaration.hpp): `kind`, `name`,
// `summary`, `coefficients`, `history_width`, optional `is_default`, `refusal`, `mixing`; an
// implemented model also has its `mix` function (its coefficients for one species pair or one
// species-wall contact) and its kernel, inlined into the contact loop per combination:
//   normal:     duration(), overlap_under(), respond(), tangential_stiffness(),
//               rolling_stiffness(),
//               springs_hold_energy_at_separation; optional takes_elastic_constants,
//               (a normal model with history_width > 0: respond(pp, r_eff, m_eff, overlap,
//               hist, spring_loss), its own history first in the contact's)
//               uses_impact_speed, foreign_key_note
//   tangential: has_force, add(), stored_energy()
//   rolling:    has_torque, add(), stored_energy()
// A model with a `refusal` is named in the case but refused when a run is set up; its kernel
// is never instantiated.
#pragma once
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

#include "contact/models/normal_hertz.hpp"
#include "contact/models/normal_jkr.hpp"
#include "contact/models/normal_linear.hpp"
#include "contact/models/normal_walton_braun.hpp"
#include "contact/models/rolling_constant_torque.hpp"
#include "contact/models/rolling_none.hpp"
#include "contact/models/rolling_spring_dashpot.hpp"
#include "contact/models/tangential_history.hpp"
#include "contact/models/tangential_mindlin_deresiewicz.hpp"
#include "contact/models/tangential_none.hpp"

namespace fluidem::contact_models {

template <class... M>
struct ModelList {
  static constexpr int size = sizeof...(M);
};

using NormalModels = ModelList<LinearNormal, HertzNormal, WaltonBraunNormal, JkrNormal>;
using TangentialModels = ModelList<HistoryTangential, NoTangential, MindlinDeresiewiczTangential>;
using RollingModels = ModelList<NoRolling, ConstantTorqueRolling, SpringDashpotRolling>;

/// Whether model M is refused at run time (declared with a `refusal`).
template <class M>
constexpr bool is_refused() {
  if constexpr (requires { M::refusal; })
    return !M::refusal.empty();
  else
    return false;
}

/// Calls f(M{}) with the model at `index` of List (0 <= index < List::size) and returns what it
/// returns. The choice runs once per call; inside f the model's functions are known at compile
/// time.
template <class... M, class F>
decltype(auto) with_model(ModelList<M...>, int index, F&& f) {
  using R = decltype(f(std::declval<typename std::tuple_element<0, std::tuple<M...>>::type>()));
  if constexpr (std::is_void_v<R>) {
    int k = 0;
    static_cast<void>(((k++ == index ? (f(M{}), true) : false) || ...));
  } else {
    R result{};
    int k = 0;
    static_cast<void>(((k++ == index ? (result = f(M{}), true) : false) || ...));
    return result;
  }
}

/// f.template operator()<N, T, R>() with the types of the models at these indices of their
/// lists, and what it returns; a combination with a refused model is never instantiated (Result{}
/// is returned: the ContactTable refuses such a case). The choice runs once per call.
template <class Result, class F>
Result with_chosen_models(int normal, int tangential, int rolling, F&& f) {
  return with_model(NormalModels{}, normal, [&]<class N>(N) {
    return with_model(TangentialModels{}, tangential, [&]<class T>(T) {
      return with_model(RollingModels{}, rolling, [&]<class R>(R) {
        if constexpr (is_refused<N>() || is_refused<T>() || is_refused<R>())
          return Result{};
        else
          return f.template operator()<N, T, R>();
      });
    });
  });
}

} // namespace fluidem::contact_models
