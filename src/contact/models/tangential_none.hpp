// Tangential model "none": no tangential force (frictionless contacts).
#pragma once
#include <array>

#include "contact/models/contact_point.hpp"
#include "contact/models/declaration.hpp"
#include "contact/models/material_pair.hpp"
#include "contact/pair_params.hpp"

namespace fluidem::contact_models {

struct NoTangential {
  static constexpr Kind kind = Kind::Tangential;
  static constexpr std::string_view name = "none";
  static constexpr std::string_view summary = "no tangential force";
  static constexpr std::array<Coefficient, 0> coefficients{};
  static constexpr int history_width = 0;
  static constexpr bool has_force = false;
  static void mix(PairParams&, const MaterialPair&, const Coefficients&) {}
  [[gnu::always_inline]] static void add(ContactOutput&, const ContactInput&, const PairParams&,
                                         const kernels::NormalResponse&, double, double, double*,
                                         double) {}
  static double stored_energy(const double*, double) { return 0.0; }
};

} // namespace fluidem::contact_models
