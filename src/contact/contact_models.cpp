#include "contact/contact_models.hpp"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "contact/models/model_list.hpp"
#include "core/error.hpp"

namespace fluidem::contact_models {

namespace {

template <class M>
constexpr ModelInfo describe(int index) {
  ModelInfo m{};
  m.kind = M::kind;
  m.index = index;
  m.name = M::name;
  m.summary = M::summary;
  m.coefficients = std::span<const Coefficient>(M::coefficients.data(), M::coefficients.size());
  m.history_width = M::history_width;
  if constexpr (requires { M::refusal; }) m.refusal = M::refusal;
  if constexpr (requires { M::is_default; }) m.is_default = M::is_default;
  if constexpr (requires { M::takes_elastic_constants; })
    m.takes_elastic_constants = M::takes_elastic_constants;
  if constexpr (requires { M::uses_impact_speed; }) m.uses_impact_speed = M::uses_impact_speed;
  if constexpr (requires { M::foreign_key_note; }) m.foreign_key_note = M::foreign_key_note;
  if constexpr (requires { M::mixing; }) m.mixing = M::mixing;
  return m;
}

template <class... M>
std::array<ModelInfo, sizeof...(M)> describe_all(ModelList<M...>) {
  int k = 0;
  return {describe<M>(k++)...};
}

const std::array<ModelInfo, NormalModels::size> kNormal = describe_all(NormalModels{});
const std::array<ModelInfo, TangentialModels::size> kTangential = describe_all(TangentialModels{});
const std::array<ModelInfo, RollingModels::size> kRolling = describe_all(RollingModels{});

std::string quoted(std::string_view s) {
  return "\"" + std::string(s) + "\"";
}

/// "a", "a or b", "a, b or c" (`last`: " or ", " and ").
std::string join(const std::vector<std::string>& items, const char* last) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i)
    s += (i == 0 ? "" : i + 1 == items.size() ? last : ", ") + items[i];
  return s;
}

std::string format_number(double x) {
  return fmt::format("{}", x);
}

} // namespace

std::string Interval::allowed() const {
  if (hi == Interval{}.hi)
    return std::string("a number ") + (lo_closed ? ">= " : "> ") + format_number(lo);
  return "a number in " + std::string(lo_closed ? "[" : "(") + format_number(lo) + ", " +
         format_number(hi) + (hi_closed ? "]" : ")");
}

const char* kind_key(Kind kind) {
  return kind == Kind::Normal ? "normal" : kind == Kind::Tangential ? "tangential" : "rolling";
}

const ContactModelSpec& of(const ContactSpec& c, Kind kind) {
  return kind == Kind::Normal ? c.normal : kind == Kind::Tangential ? c.tangential : c.rolling;
}
ContactModelSpec& of(ContactSpec& c, Kind kind) {
  return kind == Kind::Normal ? c.normal : kind == Kind::Tangential ? c.tangential : c.rolling;
}

std::span<const ModelInfo> models(Kind kind) {
  if (kind == Kind::Normal) return kNormal;
  if (kind == Kind::Tangential) return kTangential;
  return kRolling;
}

const ModelInfo& default_model(Kind kind) {
  for (const ModelInfo& m : models(kind))
    if (m.is_default) return m;
  return models(kind).front();
}

const ModelInfo* find(Kind kind, std::string_view name) {
  if (name.empty()) return &default_model(kind);
  for (const ModelInfo& m : models(kind))
    if (m.name == name) return &m;
  return nullptr;
}

const std::vector<std::string>& coefficient_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k;
    for (const Kind kind : kKinds)
      for (const ModelInfo& m : models(kind))
        for (const Coefficient& c : m.coefficients)
          if (std::find(k.begin(), k.end(), c.key) == k.end()) k.emplace_back(c.key);
    return k;
  }();
  return keys;
}

const ModelInfo* Chosen::declaring(std::string_view key) const {
  for (const ModelInfo* m : {normal, tangential, rolling})
    if (m->find(key)) return m;
  return nullptr;
}

Chosen choose(const CaseSpec& spec) {
  Chosen chosen;
  for (const Kind kind : kKinds) {
    const std::string& name = of(spec.contact, kind).name;
    const ModelInfo* m = find(kind, name);
    if (m == nullptr) {
      std::vector<std::string> names;
      for (const ModelInfo& known : models(kind)) names.push_back(quoted(known.name));
      const std::string key = std::string("contact.") + kind_key(kind);
      throw InputError(spec.where(key), key,
                       "unknown value " + quoted(name) + " (allowed: " + join(names, ", ") + ")");
    }
    (kind == Kind::Normal       ? chosen.normal
     : kind == Kind::Tangential ? chosen.tangential
                                : chosen.rolling) = m;
  }
  return chosen;
}

std::string allowed(const Coefficient& c) {
  std::string s = c.range.allowed();
  if (!c.unit.empty()) s += ", in " + std::string(c.unit);
  return s;
}

std::string not_taken(std::string_view key, const Chosen& chosen) {
  // The kind of the models that declare the key (the first one's), and those of its models.
  std::vector<std::string> owners;
  Kind kind = Kind::Normal;
  for (const Kind k : kKinds)
    for (const ModelInfo& m : models(k))
      if (m.find(key) && m.find(key)->given != Given::AutoOnly) {
        if (owners.empty()) kind = k;
        if (k == kind) owners.push_back(std::string(kind_key(k)) + " = " + quoted(m.name));
      }
  const ModelInfo& mine = chosen.of(kind);
  std::string s = std::string("not allowed with ") + kind_key(kind) + " = " + quoted(mine.name) +
                  " (only with " + join(owners, " or ");
  if (!mine.foreign_key_note.empty()) s += "; " + std::string(mine.foreign_key_note);
  return s + ")";
}

std::string only_auto(const ModelInfo& m, const Coefficient& c) {
  return std::string("not allowed with ") + kind_key(m.kind) + " = " + quoted(m.name) +
         " (allowed: \"auto\"): " + std::string(c.meaning);
}

bool auto_allowed(std::string_view key) {
  for (const Kind k : kKinds)
    for (const ModelInfo& m : models(k))
      if (const Coefficient* c = m.find(key); c && c->given != Given::Required) return true;
  return false;
}

std::string refusal(const ModelInfo& m) {
  std::vector<std::string> implemented;
  for (const ModelInfo& other : models(m.kind))
    if (other.refusal.empty()) implemented.push_back(quoted(other.name));
  return quoted(m.name) + " " + std::string(m.refusal) +
         " (implemented: " + join(implemented, ", ") + ")";
}

std::string elastic_constants_not_taken(const ModelInfo& normal) {
  std::vector<std::string> keys, takers;
  for (const Coefficient& c : normal.coefficients) keys.push_back("contact." + std::string(c.key));
  for (const ModelInfo& m : models(Kind::Normal))
    if (m.takes_elastic_constants && m.refusal.empty()) takers.push_back(quoted(m.name));
  return "not allowed with contact.normal = " + quoted(normal.name) + ", whose stiffnesses are " +
         join(keys, " and ") + " for every contact, walls included (the materials' elastic " +
         "constants act only with normal = " + join(takers, " or ") + ")";
}

Chosen check(const CaseSpec& spec) {
  const Chosen chosen = choose(spec);
  for (const Kind kind : kKinds) {
    const ModelInfo& m = chosen.of(kind);
    const ContactModelSpec& given = of(spec.contact, kind);
    for (const auto& [key, value] : given.coefficients) {
      const std::string path = "contact." + key;
      const Coefficient* c = m.find(key);
      if (c == nullptr) throw InputError(spec.where(path), path, not_taken(key, chosen));
      if (c->given == Given::AutoOnly) throw InputError(spec.where(path), path, only_auto(m, *c));
      if (!c->range.contains(value))
        throw InputError(spec.where(path), path,
                         fmt::format("{} is out of range (allowed: {})", value, allowed(*c)));
    }
    if (!m.refusal.empty()) continue;
    for (const Coefficient& c : m.coefficients)
      if (c.given == Given::Required && !given.coefficients.contains(std::string(c.key)))
        throw InputError(spec.where("contact"), "contact." + std::string(c.key),
                         "missing required key in [contact] (" + allowed(c) + ", required with " +
                             kind_key(kind) + " = " + quoted(m.name) + ")");
  }
  return chosen;
}

} // namespace fluidem::contact_models
