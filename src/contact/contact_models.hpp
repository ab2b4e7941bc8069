// The registry of the contact sub-models (contact/models/model_list.hpp) for everything outside
// the contact loop: the case reader (names, coefficient keys, ranges, the messages of its
// errors), the writer, `fluidem check`, and the ContactTable (which models a case chooses,
// whether they take its coefficients).
#pragma once
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "contact/models/declaration.hpp"
#include "core/case_spec.hpp"

namespace fluidem::contact_models {

inline constexpr Kind kKinds[3] = {Kind::Normal, Kind::Tangential, Kind::Rolling};

/// "normal", "tangential", "rolling": the [contact] key that names a model of the kind.
const char* kind_key(Kind kind);
/// The model spec of a kind in a case's [contact].
const ContactModelSpec& of(const ContactSpec& c, Kind kind);
ContactModelSpec& of(ContactSpec& c, Kind kind);

/// The declared models of a kind, in list order.
std::span<const ModelInfo> models(Kind kind);
/// The model of a kind with this name (empty: the kind's default), or nullptr.
const ModelInfo* find(Kind kind, std::string_view name);
const ModelInfo& default_model(Kind kind);
/// Every coefficient key some model declares, in list order, each once (the [contact] schema
/// beside the kinds' keys, characteristic_velocity and max_overlap).
const std::vector<std::string>& coefficient_keys();

/// The models a case's [contact] names (empty names: the defaults).
struct Chosen {
  const ModelInfo* normal = nullptr;
  const ModelInfo* tangential = nullptr;
  const ModelInfo* rolling = nullptr;
  const ModelInfo& of(Kind kind) const {
    return *(kind == Kind::Normal ? normal : kind == Kind::Tangential ? tangential : rolling);
  }
  /// The chosen model (of any kind) that declares `key`, or nullptr.
  const ModelInfo* declaring(std::string_view key) const;
};
/// InputError naming contact.<kind> for a name no model has.
Chosen choose(const CaseSpec& spec);

/// "a number > 0, in N/m"
std::string allowed(const Coefficient& c);
/// Why `key` (a coefficient of another model) is not allowed with the chosen models: "not
/// allowed with normal = "hertz" (only with normal = "linear"; ...)".
std::string not_taken(std::string_view key, const Chosen& chosen);
/// Why a number is not allowed for an "auto"-only coefficient of model m.
std::string only_auto(const ModelInfo& m, const Coefficient& c);
/// Whether "auto" is a value some model declares for `key` (then any model takes it: absent).
bool auto_allowed(std::string_view key);
/// The refusal of a refused model: ""NAME" REFUSAL (implemented: ...)".
std::string refusal(const ModelInfo& m);
/// Why a normal model that takes no elastic constants refuses a shear modulus or a rigid wall.
std::string elastic_constants_not_taken(const ModelInfo& normal);

/// The case's [contact] models and coefficients against the declarations (a case built in code:
/// the reader checks the same, with the file positions, while it reads): InputError naming the
/// key for an unknown model, a coefficient the chosen models do not take, a missing required
/// one, or one out of its range. Refused models pass (the ContactTable refuses them).
Chosen check(const CaseSpec& spec);

} // namespace fluidem::contact_models
