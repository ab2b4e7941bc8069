// Degree of segregation [Deen07 eq. 49] on configurations whose value is known exactly:
//  - completely segregated (small particles in a uniform layer on top of a uniform layer of
//    large ones, each layer filled in proportion to its solids volume): s = 1, because
//    <h_large> = x_L H / 2 and <h_small> = (1 + x_L) H / 2 give S = S_max (to 1e-12 on a fine
//    lattice whose layers hold the exact volume fractions);
//  - perfectly mixed (both species on the same heights): s = 0 (to 1e-14);
//  - reversed (large on top of small): eq. 49 with the hand-computed mean heights and volume
//    fraction (to 1e-12), and s < 0;
//  - 2-D discs use areas for x_large; the volume fraction is checked against a hand count.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "analysis/segregation.hpp"

namespace fluidem {
namespace {

/// n particles of radius r on heights uniformly spaced in [z0, z1) (midpoints), 3-D.
void column(ParticleStore& p, long n, double r, double z0, double z1) {
  for (long k = 0; k < n; ++k) {
    const double z = z0 + (static_cast<double>(k) + 0.5) * (z1 - z0) / static_cast<double>(n);
    p.add({0.0, 0.0, z}, {0.0, 0.0, 0.0}, r, 2500.0, 0, static_cast<std::int64_t>(p.size()));
  }
}

TEST(Segregation, CompletelySegregatedIsOne) {
  // Large: 1000 particles of r = 1 mm (volume 1000 r_L^3), small: 8000 of r = 0.5 mm
  // (volume 8000 r_L^3 / 8 = 1000 r_L^3): x_L = 0.5; H = 1 m, large in [0, 0.5), small above.
  ParticleStore p;
  column(p, 1000, 1e-3, 0.0, 0.5);
  column(p, 8000, 0.5e-3, 0.5, 1.0);
  const Segregation g = segregation(p, 1.5e-3, 2, 0.0, true, false);
  EXPECT_NEAR(g.x_large, 0.5, 1e-12); // sums of 9000 volumes: round-off ~1e-13
  EXPECT_NEAR(g.h_large, 0.25, 1e-12);
  EXPECT_NEAR(g.h_small, 0.75, 1e-12);
  EXPECT_NEAR(g.ratio_max, 3.0, 1e-12);
  EXPECT_NEAR(g.s, 1.0, 1e-12);
}

TEST(Segregation, MixedIsZeroAndReversedIsNegative) {
  ParticleStore p;
  column(p, 300, 1e-3, 0.0, 0.6);
  column(p, 900, 0.6e-3, 0.0, 0.6);
  EXPECT_NEAR(segregation(p, 1.5e-3, 2, 0.0, true, false).s, 0.0, 1e-14);
  // Reversed: large on top of small, x_L = 300 / (300 + 900 * 0.216) = 0.6068...
  ParticleStore q;
  column(q, 900, 0.6e-3, 0.0, 0.4);
  column(q, 300, 1e-3, 0.4, 0.6);
  const Segregation g = segregation(q, 1.5e-3, 2, 0.0, true, false);
  const double xl = 300.0 / (300.0 + 900.0 * 0.216);
  const double S = 0.2 / 0.5, Smax = (xl + 1.0) / xl;
  EXPECT_NEAR(g.x_large, xl, 1e-14);
  EXPECT_NEAR(g.s, (S - 1.0) / (Smax - 1.0), 1e-12);
  EXPECT_LT(g.s, 0.0);
}

TEST(Segregation, DiscsUseAreasAndTheFloorCanBeHigh) {
  // 2-D: 100 large discs r = 2 mm and 400 small r = 1 mm: areas equal, x_L = 0.5. Gravity
  // along +z (floor at z = 1, heights measured downward).
  ParticleStore p;
  column(p, 100, 2e-3, 0.5, 1.0); // large near the floor (z = 1)
  column(p, 400, 1e-3, 0.0, 0.5); // small above (further from the floor)
  const Segregation g = segregation(p, 3e-3, 2, 1.0, false, true);
  EXPECT_NEAR(g.x_large, 0.5, 1e-14);
  EXPECT_NEAR(g.s, 1.0, 1e-12);
  EXPECT_EQ(g.n_large, 100);
  EXPECT_EQ(g.n_small, 400);
}

TEST(Segregation, OneSpeciesOnlyIsAnError) {
  ParticleStore p;
  column(p, 10, 1e-3, 0.0, 0.1);
  EXPECT_THROW(segregation(p, 1.5e-3, 2, 0.0, true, false), std::invalid_argument);
}

} // namespace
} // namespace fluidem
