// Degree of segregation of a bidisperse bed [Deen07 eq. 49] (Goldschmidt et al. 2003):
//   s = (S - 1) / (S_max - 1),  S = <h_small> / <h_large>,  S_max = (x_large + 1) / x_large,
// with <h_i> the mean height of the particles of type i above the floor (number average of the
// centre heights) and x_large the volume fraction of the large particles among all solids.
// s = 0 for a perfectly mixed bed (equal mean heights), s = 1 for a completely segregated one
// (all small particles above all large ones, filling the bed uniformly: then <h_large> =
// x_large H / 2 and <h_small> = (1 + x_large) H / 2, S = S_max); s < 0 when the small particles
// sit lower on average.
#pragma once
#include "particles/particle_store.hpp"

namespace fluidem {

struct Segregation {
  double s = 0.0;         ///< degree of segregation [Deen07 eq. 49]
  double ratio = 0.0;     ///< S = <h_small> / <h_large>
  double ratio_max = 0.0; ///< S_max = (x_large + 1) / x_large
  double x_large = 0.0;   ///< volume fraction of the large particles
  double h_small = 0.0;   ///< <h_small>, m
  double h_large = 0.0;   ///< <h_large>, m
  long n_small = 0, n_large = 0;
};

/// Particles with diameter < `split_diameter` are "small", the others "large" (for two species
/// pass any diameter between theirs). Heights h_i = (x_i - floor) along `vertical_axis`,
/// upward (`upward` false: the floor is the high side). Volumes are sphere volumes (3-D) or disc
/// areas (2-D, the solids "volume" fraction of a disc layer). Throws std::invalid_argument if
/// either class is empty or <h_large> is not positive.
Segregation segregation(const ParticleStore& p, double split_diameter, int vertical_axis,
                        double floor, bool upward, bool two_d);

} // namespace fluidem
