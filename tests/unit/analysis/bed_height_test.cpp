// bed_height = twice the centre-of-mass height: a uniform bed of L layers of spacing d filling
// [floor, floor + L d] has its centres at d/2 + k d, mean L d / 2, so bed_height = L d exactly
// (tolerance 1e-12 relative, round-off). Reversed gravity measures from the high side.
#include "analysis/bed_height.hpp"
#include <gtest/gtest.h>

using namespace fluidem;

TEST(BedHeight, UniformLayersGiveTheirHeightExactly) {
  const double d = 0.004, floor = 0.1;
  for (int layers : {1, 5, 37}) {
    ParticleStore p;
    long id = 0;
    for (int k = 0; k < layers; ++k)
      for (int i = 0; i < 10; ++i)
        p.add({0.01 * i, 0.0, floor + 0.5 * d + k * d}, {0, 0, 0}, 0.5 * d, 2700.0, 0, id++);
    EXPECT_NEAR(bed_height(p, 2, floor, true, true), layers * d, 1e-12 * layers * d);
    EXPECT_NEAR(bed_height(p, 2, floor, true, false), layers * d, 1e-12 * layers * d);
    // Same bed seen with gravity along +z and the floor at z = floor + layers d.
    EXPECT_NEAR(bed_height(p, 2, floor + layers * d, false, false), layers * d, 1e-12 * layers * d);
  }
  EXPECT_EQ(bed_height(ParticleStore{}, 2, 0.0, true, false), 0.0);
}
