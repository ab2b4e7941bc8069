#include "analysis/bed_height.hpp"

namespace fluidem {

double bed_height(const ParticleStore& p, int vertical_axis, double floor, bool upward,
                  bool two_d) {
  const std::vector<double>& x = vertical_axis == 0 ? p.x : (vertical_axis == 1 ? p.y : p.z);
  double sw = 0.0, swh = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    const double w = two_d ? r * r : r * r * r;
    sw += w;
    swh += w * (upward ? x[i] - floor : floor - x[i]);
  }
  return sw > 0.0 ? 2.0 * swh / sw : 0.0;
}

} // namespace fluidem
