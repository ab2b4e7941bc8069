// The vocabulary a contact sub-model declares itself in (contact/models/<kind>_<model>.hpp): its
// coefficients (case key in [contact], unit, allowed range, default, meaning) and its flags. The
// reader validates against these declarations, the writer writes from them, `fluidem check`
// prints them, the ContactTable mixes with them (contact_models.hpp: the registry).
#pragma once
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace fluidem::contact_models {

enum class Kind { Normal, Tangential, Rolling };

/// A model's coefficients as the case gives them (key -> value, SI; "auto": absent).
using Coefficients = std::map<std::string, double>;

inline std::optional<double> coefficient(const Coefficients& c, const std::string& key) {
  const auto it = c.find(key);
  return it == c.end() ? std::nullopt : std::optional<double>(it->second);
}

/// The allowed values of a coefficient: an interval of the reals.
struct Interval {
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  bool lo_closed = false, hi_closed = false;
  static constexpr Interval positive() { return {}; }
  static constexpr Interval non_negative() { return {0.0, Interval{}.hi, true, false}; }
  static constexpr Interval unit() { return {0.0, 1.0, true, true}; }
  static constexpr Interval open_unit() { return {0.0, 1.0, false, false}; }
  bool contains(double x) const {
    return std::isfinite(x) && (lo_closed ? x >= lo : x > lo) && (hi_closed ? x <= hi : x < hi);
  }
  /// "a number > 0", "a number in [0, 1]", ... (the reader's wording)
  std::string allowed() const;
};

/// How a coefficient may be left out of the case.
enum class Given {
  Required, ///< must be given
  Auto,     ///< a number or "auto" (absent from ContactModelSpec::coefficients): the model's rule
  AutoOnly, ///< only "auto": the model derives it (the declaration's `meaning` says from what)
};

/// One coefficient of a model: a key of [contact].
struct Coefficient {
  std::string_view key;  ///< case key in [contact]
  std::string_view unit; ///< SI unit, "" when dimensionless
  Interval range;
  Given given = Given::Required;
  /// What it is and its source; for Auto, what "auto" does; for AutoOnly, why only "auto".
  std::string_view meaning;
  /// Mixing for unlike materials: how the value of a species pair and of a species-wall
  /// contact follow from it (a [contact] key: the same for every pair and wall).
  std::string_view mixing = "the same for every species pair and wall";
  /// The range met in practice (the time-step rule names the input farthest outside it when
  /// the contact is too short); 0, 0: not an input of the contact duration.
  double usual_lo = 0.0, usual_hi = 0.0;
  bool longer_when_larger = false; ///< a larger value lengthens the contact
};

/// A model as the registry sees it: everything but its kernel and its mixing function.
struct ModelInfo {
  Kind kind;
  int index; ///< its place in its kind's list (contact/models/model_list.hpp)
  std::string_view name;
  std::string_view summary; ///< one line with its source, for `fluidem check` and errors
  std::span<const Coefficient> coefficients;
  int history_width;                 ///< doubles of history per contact
  std::string_view refusal;          ///< non-empty: named but refused at run time (why)
  bool is_default;                   ///< the kind's default when the case names none
  bool takes_elastic_constants;      ///< normal: reads E and nu (or G) of the materials
  bool uses_impact_speed;            ///< normal: its duration depends on the impact speed
  std::string_view foreign_key_note; ///< normal: why it takes no other model's coefficient
  std::string_view mixing;           ///< its mixing rules for the materials' constants
  const Coefficient* find(std::string_view key) const {
    for (const Coefficient& c : coefficients)
      if (c.key == key) return &c;
    return nullptr;
  }
};

} // namespace fluidem::contact_models
