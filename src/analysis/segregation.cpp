#include "analysis/segregation.hpp"

#include <stdexcept>
#include <string>

namespace fluidem {

Segregation segregation(const ParticleStore& p, double split_diameter, int vertical_axis,
                        double floor, bool upward, bool two_d) {
  Segregation r;
  double sum_h_small = 0.0, sum_h_large = 0.0, v_small = 0.0, v_large = 0.0;
  const std::vector<double>& x = vertical_axis == 0 ? p.x : (vertical_axis == 1 ? p.y : p.z);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double rad = p.radius[i];
    const double h = upward ? x[i] - floor : floor - x[i];
    const double v = two_d ? rad * rad : rad * rad * rad; // common factors cancel in x_large
    if (2.0 * rad < split_diameter) {
      sum_h_small += h;
      v_small += v;
      ++r.n_small;
    } else {
      sum_h_large += h;
      v_large += v;
      ++r.n_large;
    }
  }
  if (r.n_small == 0 || r.n_large == 0)
    throw std::invalid_argument("segregation: need small and large particles (split diameter " +
                                std::to_string(split_diameter) + " m; " +
                                std::to_string(r.n_small) + " small, " + std::to_string(r.n_large) +
                                " large)");
  r.h_small = sum_h_small / static_cast<double>(r.n_small);
  r.h_large = sum_h_large / static_cast<double>(r.n_large);
  if (!(r.h_large > 0.0))
    throw std::invalid_argument("segregation: the mean height of the large particles is not "
                                "above the floor");
  r.x_large = v_large / (v_small + v_large);
  r.ratio = r.h_small / r.h_large;
  r.ratio_max = (r.x_large + 1.0) / r.x_large;
  r.s = (r.ratio - 1.0) / (r.ratio_max - 1.0); // [Deen07 eq. 49]
  return r;
}

} // namespace fluidem
