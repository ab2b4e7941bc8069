// Height of a fluidised bed (series.csv column `bed_height`).
#pragma once
#include "particles/particle_store.hpp"

namespace fluidem {

/// Bed height, m: twice the height of the solids' centre of mass above the floor,
///   H = 2 (sum_i w_i h_i / sum_i w_i),  h_i = (x_i - floor) along the vertical axis
///   (measured upward: `upward` false means the floor is the HIGH side),
/// with w_i the particle volume (3-D) or disc area (2-D). This is the height of the uniform
/// bed with the same centre of mass (a settled bed of height H gives H up to the half-particle
/// layer at the floor); unlike a surface criterion it does not jump with single particles
/// thrown above the bed. 0 when there are no particles.
double bed_height(const ParticleStore& p, int vertical_axis, double floor, bool upward, bool two_d);

} // namespace fluidem
