// Porosity mapping [Deen07 eq. 33-37; Hoomans96 eq. 49].
// References and tolerances:
//  - sum over cells of the exact sphere volume per cell = 4/3 pi R^3, 1e-12 relative, at random
//    positions spanning cell corners (particle diameter 0.6-1.6 cell sizes);
//  - a single cell against independent closed forms: half and quarter spheres (planes through
//    the centre), a spherical cap; 1e-13 relative;
//  - 2-D disc areas sum to pi R^2 (1e-12), quarter disc;
//  - [Hoomans96 eq. 49]: eps_2D = 1 -> 1; hexagonal disc packing 1 - pi/(2 sqrt 3) -> FCC
//    porosity 1 - pi/(3 sqrt 2) (hand-computed 0.25951), 1e-12; eps_2D = 0.5 -> 0.6968694, 1e-7;
//  - porous cube: total solid volume conserved (1e-12), also for a cube pushed into the domain.
#include "core/error.hpp"
#include "coupling/porosity.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <random>

using namespace fluidem;
using namespace fluidem::coupling;

namespace {
constexpr double pi = 3.14159265358979323846;

double total(const std::vector<double>& frac, double cell_measure) {
  double s = 0.0;
  for (double f : frac) s += f * cell_measure;
  return s;
}
} // namespace

TEST(Porosity, SphereVolumeSumsOverCells) {
  gas::GasGrid g(3, {6, 5, 7}, {0.0, 0.0, 0.0}, {0.006, 0.005, 0.007}); // 1 mm cells
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(0.0018, 0.0032), rad(0.0003, 0.0008);
  double worst = 0.0;
  for (int n = 0; n < 200; ++n) {
    ParticleStore p;
    const double R = rad(rng);
    p.add({pos(rng), pos(rng), pos(rng)}, {0, 0, 0}, R, 2500.0, 0, 0);
    std::vector<double> frac;
    solid_fraction(g, p, {}, frac);
    const double v = total(frac, g.cell_volume());
    worst = std::max(worst, std::abs(v / (4.0 / 3.0 * pi * R * R * R) - 1.0));
  }
  std::printf("max rel. error of the summed sphere volume (200 random spheres): %.2e\n", worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(Porosity, SingleCellClosedForms) {
  const double R = 1.0;
  const double V = 4.0 / 3.0 * pi;
  // Entirely inside.
  EXPECT_NEAR(sphere_box_volume({0, 0, 0}, R, {-2, -2, -2}, {2, 2, 2}) / V, 1.0, 1e-13);
  // Half, quarter, eighth (planes through the centre).
  EXPECT_NEAR(sphere_box_volume({0, 0, 0}, R, {0, -2, -2}, {2, 2, 2}) / V, 0.5, 1e-13);
  EXPECT_NEAR(sphere_box_volume({0, 0, 0}, R, {0, 0, -2}, {2, 2, 2}) / V, 0.25, 1e-13);
  EXPECT_NEAR(sphere_box_volume({0, 0, 0}, R, {0, 0, 0}, {2, 2, 2}) / V, 0.125, 1e-13);
  // Cap of height h = 0.3: pi h^2 (3R - h)/3.
  const double h = 0.3;
  EXPECT_NEAR(sphere_box_volume({0, 0, 0}, R, {-2, -2, 1 - h}, {2, 2, 2}) /
                  (pi * h * h * (3 * R - h) / 3.0),
              1.0, 1e-13);
  // Cap cut in half by a plane through the axis, and in quarters by two (symmetry).
  EXPECT_NEAR(sphere_box_volume({0, 0, 0}, R, {0, 0, 1 - h}, {2, 2, 2}) /
                  (pi * h * h * (3 * R - h) / 12.0),
              1.0, 1e-13);
  // Octant with an off-centre corner: the 8 octants around (a, b, c) sum to the sphere.
  const double a = 0.31, b = -0.42, c = 0.17;
  double s = 0.0;
  for (int m = 0; m < 8; ++m)
    s += sphere_box_volume({0, 0, 0}, R, {(m & 1) ? a : -2, (m & 2) ? b : -2, (m & 4) ? c : -2},
                           {(m & 1) ? 2 : a, (m & 2) ? 2 : b, (m & 4) ? 2 : c});
  EXPECT_NEAR(s / V, 1.0, 1e-13);
}

TEST(Porosity, DiscAreasSumOverCells2D) {
  gas::GasGrid g(2, {6, 1, 7}, {0.0, 0.0, 0.0}, {0.006, 0.002, 0.007});
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> pos(0.0018, 0.0032), rad(0.0003, 0.0008);
  double worst = 0.0;
  for (int n = 0; n < 200; ++n) {
    ParticleStore p;
    const double R = rad(rng);
    p.add({pos(rng), 0.001, pos(rng)}, {0, 0, 0}, R, 2500.0, 0, 0);
    std::vector<double> frac;
    solid_fraction(g, p, {}, frac);
    worst = std::max(worst, std::abs(total(frac, g.h[0] * g.h[2]) / (pi * R * R) - 1.0));
  }
  std::printf("max rel. error of the summed disc area: %.2e\n", worst);
  EXPECT_LT(worst, 1e-12);
  EXPECT_NEAR(disc_rect_area(0, 0, 1.0, 0, 2, 0, 2) / (pi / 4), 1.0, 1e-14);
  EXPECT_NEAR(disc_rect_area(0, 0, 1.0, -2, 2, 0.5, 2) / (pi / 3 - std::sqrt(3.0) / 4), 1.0,
              1e-13); // circular segment at distance 1/2
}

TEST(Porosity, Hoomans49Conversion) {
  EXPECT_NEAR(porosity_2d_to_3d(1.0), 1.0, 1e-15);
  const double hex2d = 1.0 - pi / (2.0 * std::sqrt(3.0)); // 0.0931 hexagonal discs
  const double fcc = 1.0 - pi / (3.0 * std::sqrt(2.0));   // 0.25952 FCC spheres
  EXPECT_NEAR(porosity_2d_to_3d(hex2d), fcc, 1e-12);
  EXPECT_NEAR(fcc, 0.259519, 1e-6);
  // eps_2D = 0.5: 2/sqrt(pi sqrt 3) = 0.8573828, 1 - 0.8573828 * 0.5^1.5 = 0.6968694 (by hand)
  EXPECT_NEAR(porosity_2d_to_3d(0.5), 0.6968694, 1e-7);
}

TEST(Porosity, PorousCubeConservesVolume) {
  gas::GasGrid g(3, {6, 5, 7}, {0.0, 0.0, 0.0}, {0.006, 0.005, 0.007});
  PorositySettings s;
  s.method = PorosityMethod::porous_cube;
  s.cube_factor = 3.0;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> pos(0.0, 0.005);
  ParticleStore p;
  double v = 0.0;
  for (int n = 0; n < 50; ++n) {
    const double R = 0.0003;
    p.add({pos(rng), pos(rng), pos(rng)}, {0, 0, 0}, R, 2500.0, 0, n); // some touch walls
    v += 4.0 / 3.0 * pi * R * R * R;
  }
  std::vector<double> frac;
  solid_fraction(g, p, s, frac);
  EXPECT_NEAR(total(frac, g.cell_volume()) / v, 1.0, 1e-12);
  s.cube_factor = 0.5;
  EXPECT_THROW(validate(s), InputError);
}
