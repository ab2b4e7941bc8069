// Normal model "walton_braun": the hysteretic linear loading/unloading spring of Walton & Braun
// (1986, J. Rheol. 30:949). Declared, so that the case may name it, and refused when a run is
// set up (issue 34 implements it).
#pragma once
#include <array>

#include "contact/models/declaration.hpp"

namespace fluidem::contact_models {

struct WaltonBraunNormal {
  static constexpr Kind kind = Kind::Normal;
  static constexpr std::string_view name = "walton_braun";
  static constexpr std::string_view summary = "Walton & Braun (1986), not implemented";
  static constexpr std::array<Coefficient, 0> coefficients{};
  static constexpr int history_width = 0;
  static constexpr std::string_view refusal = "is not implemented yet";
};

} // namespace fluidem::contact_models
