// Mixing rules for the collision coefficients of unlike materials, shared by the soft-sphere
// contact table and the hard-sphere collision table: for a particle pair the arithmetic means of
// the two materials' e_n, mu, beta_0 and mu_r; a particle-wall contact takes the wall's values.
#pragma once
#include "core/case_spec.hpp"

namespace fluidem {

struct MixedCoefficients {
  double restitution = 0.0, friction = 0.0, tangential_restitution = 0.0, rolling_friction = 0.0;
};

inline MixedCoefficients mix_pair(const MaterialSpec& a, const MaterialSpec& b) {
  return {0.5 * (a.restitution + b.restitution), 0.5 * (a.friction + b.friction),
          0.5 * (a.tangential_restitution + b.tangential_restitution),
          0.5 * (a.rolling_friction + b.rolling_friction)};
}

inline MixedCoefficients wall_coefficients(const MaterialSpec& wall) {
  return {wall.restitution, wall.friction, wall.tangential_restitution, wall.rolling_friction};
}

} // namespace fluidem
