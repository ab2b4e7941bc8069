// Rolling model "none": no rolling resistance.
#pragma once
#include <array>

#include "contact/models/contact_point.hpp"
#include "contact/models/declaration.hpp"
#include "contact/models/material_pair.hpp"
#include "contact/pair_params.hpp"

namespace fluidem::contact_models {

struct NoRolling {
  static constexpr Kind kind = Kind::Rolling;
  static constexpr std::string_view name = "none";
  static constexpr std::string_view summary = "no rolling resistance";
  static constexpr bool is_default = true;
  static constexpr std::array<Coefficient, 0> coefficients{};
  static constexpr int history_width = 0;
  static constexpr bool has_torque = false;
  static void mix(PairParams&, const MaterialPair&, const Coefficients&) {}
  [[gnu::always_inline]] static void add(ContactOutput&, const ContactInput&, const PairParams&,
                                         double, double*, double) {}
  static double stored_energy(const double*, const PairParams&, double, double) { return 0.0; }
};

} // namespace fluidem::contact_models
