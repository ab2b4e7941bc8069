// What a model's `mix` function is given for one species pair or one (species, wall) contact:
// the two materials, mixed by the rules shared with the hard spheres (core/material_mixing.hpp),
// and the model's coefficients from the case.
#pragma once
#include "contact/models/declaration.hpp"
#include "core/case_spec.hpp"
#include "core/material_mixing.hpp"

namespace fluidem::contact_models {

struct MaterialPair {
  const MaterialSpec& a; ///< the particle's (species i)
  const MaterialSpec& b; ///< the partner's (species j, or the wall's)
  bool wall;
  MixedCoefficients mixed; ///< e, mu, beta0, mu_r of the pair [mix_pair] or the wall's
};

// A rigid wall (youngs_modulus = inf) adds nothing: the particle's compliance alone remains.
/// (1 - nu^2)/E of a material [Zhu07 Table 1].
inline double inv_e_part(const MaterialSpec& m) {
  return (1.0 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus;
}
/// (2 - nu)/G of a material [Zhu07 Table 1; Chang08 eq. 2.16].
inline double inv_g_part(const MaterialSpec& m) {
  return (2.0 - m.poisson_ratio) / shear_modulus_of(m);
}

} // namespace fluidem::contact_models
