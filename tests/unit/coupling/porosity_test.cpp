// Porosity mapping [Deen07 eq. 33-37; Hoomans96 eq. 49].
// References and tolerances:
//  - sum over cells of the exact sphere volume per cell = 4/3 pi R^3, 1e-12 relative, at random
//    positions spanning cell corners (particle diameter 0.6-1.6 cell sizes);
//  - a single cell against independent closed forms: half and quarter spheres (planes through
//    the centre), a spherical cap; 1e-13 relative;
//  - 2-D disc areas sum to pi R^2 (1e-12), quarter disc;
//  - [Hoomans96 eq. 49]: eps_2D = 1 -> 1; hexagonal disc packing 1 - pi/(2 sqrt 3) -> FCC
//    porosity 1 - pi/(3 sqrt 2) (hand-computed 0.25951), 1e-12; eps_2D = 0.5 -> 0.6968694, 1e-7;
//  - a sphere inside one cell, whole or cut by the two faces of one axis (the cap closed form
//    of solid_fraction), against sphere_box_volume of that cell (the octant sums, an independent
//    evaluation), 1e-13 relative, the single-cell ones of 2000 random spheres;
//  - porous cube: total solid volume conserved (1e-12), also for a cube pushed into the domain.
//  - ball_octant_volume (closed form) against an independent reference, the exact disc-quadrant
//    area integrated along x by tanh-sinh quadrature between the integrand's breakpoints (the
//    previous production code, kept here): 2*10^4 random (X, Y, Z) in [-1.2 R, 1.2 R]^3 plus
//    near-tangent and degenerate corners, max |error| / R^3 <= 1e-11 (measured 1.8e-13: the
//    quadrature's own error; at its worst point the closed form is 3e-16 from 40 digits);
//  - 9 corners (incl. near-tangent, tiny volumes) against 40-digit values (mpmath: the same
//    integral, adaptive Gauss-Legendre between breakpoints), |error| <= 1e-15 R^3 (max 2.2e-16);
//  - identities: the 8 octants around a point sum to 4/3 pi R^3 (1e-13), X = Y = Z = 0 is 1/8
//    of the ball, permutation symmetry (bitwise), planes through the centre (cap/4, cap/2
//    closed forms), monotone and -> 0 as the corner approaches the sphere, and the tiny-corner
//    asymptote h^3 / (6 n_x n_y n_z) (h = R - |corner|, n = corner / |corner|).
#include "core/error.hpp"
#include "coupling/porosity.hpp"
#include <algorithm>
#include <array>
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

// Reference for ball_octant_volume: the exact disc-quadrant area A(sqrt(R^2 - x^2), Y, Z)
// integrated along x by tanh-sinh quadrature (step 1/16, |t| <= 3.2) between its breakpoints
// (|Y|, |Z|, sqrt(Y^2 + Z^2) = radius of the slice): error up to ~2e-13 R^3 where a plane is
// within ~1e-4 R of the centre (a breakpoint near x = +-R), ~1e-16 R^3 typically.
struct TanhSinh {
  static constexpr int half = 51; // t = k h, k = -half..half
  std::array<double, 2 * half + 1> gap{}, sign{}, w{};
  TanhSinh() {
    const double h = 1.0 / 16.0;
    for (int k = -half; k <= half; ++k) {
      const double t = k * h;
      const double u = 0.5 * pi * std::sinh(t);
      const double c = std::cosh(u);
      const auto n = static_cast<std::size_t>(k + half);
      gap[n] = 1.0 / (std::exp(2.0 * std::abs(u)) + 1.0) * 2.0; // 1 - |tanh u|, no cancellation
      sign[n] = k < 0 ? -1.0 : 1.0;
      w[n] = h * 0.5 * pi * std::cosh(t) / (c * c);
    }
  }
};

template <class F>
double integrate(F&& f, double a, double b) {
  static const TanhSinh q;
  if (!(b > a)) return 0.0;
  const double hw = 0.5 * (b - a);
  double s = 0.0;
  for (std::size_t n = 0; n < q.w.size(); ++n) {
    const double x = q.sign[n] < 0.0 ? a + hw * q.gap[n] : b - hw * q.gap[n];
    s += q.w[n] * f(x);
  }
  return s * hw;
}

double octant_reference(double R, double X, double Y, double Z) {
  if (!(R > 0.0) || X <= -R || Y <= -R || Z <= -R) return 0.0;
  std::array<double, 3> c{std::min(X, R), std::min(Y, R), std::min(Z, R)};
  std::sort(c.begin(), c.end()); // integrate along the axis of the largest bound
  const double Xe = c[2], Ya = c[0], Za = c[1];
  std::vector<double> br{-R, Xe};
  for (double r2 : {R * R - Ya * Ya, R * R - Za * Za, R * R - Ya * Ya - Za * Za})
    if (r2 > 0.0)
      for (double x : {-std::sqrt(r2), std::sqrt(r2)})
        if (x > -R && x < Xe) br.push_back(x);
  std::sort(br.begin(), br.end());
  auto area = [&](double x) {
    return disc_quadrant_area(std::sqrt(std::max(R * R - x * x, 0.0)), Ya, Za);
  };
  double v = 0.0;
  for (std::size_t m = 0; m + 1 < br.size(); ++m) v += integrate(area, br[m], br[m + 1]);
  return v;
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

namespace {
// One layer of cells 4 mm deep in y between walls (the 3-D Tsuji bed: spheres of 4 mm touch
// or cut both y walls) and 10 x 20 mm in x-z, and `count` single spheres at random in it
// (R = 1.5 .. 2.1 mm): f(x, R, solid fraction of the grid's cells) for each.
gas::GasGrid layer_grid() {
  return gas::GasGrid(3, {4, 1, 3}, {0.0, 0.0, 0.0}, {0.04, 0.004, 0.06});
}
template <class F>
void random_spheres_in_layer(const gas::GasGrid& g, unsigned seed, int count, F f) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(0.0, 0.04), uy(0.0, 0.004), uz(0.0, 0.06);
  std::uniform_real_distribution<double> rad(0.0015, 0.0021);
  for (int n = 0; n < count; ++n) {
    ParticleStore p;
    const Vec3 x{ux(rng), uy(rng), uz(rng)};
    const double R = rad(rng);
    p.add(x, {0, 0, 0}, R, 2500.0, 0, 0);
    std::vector<double> frac;
    solid_fraction(g, p, {}, frac);
    f(x, R, frac);
  }
}
/// Corners lo, hi of cell (i, 1, k) of the layer.
std::array<std::array<double, 3>, 2> layer_cell(const gas::GasGrid& g, int i, int k) {
  const std::array<double, 3> lo{g.lo[0] + (i - 1) * g.h[0], g.lo[1], g.lo[2] + (k - 1) * g.h[2]};
  return {lo, {lo[0] + g.h[0], g.lo[1] + g.h[1], lo[2] + g.h[2]}};
}
} // namespace

TEST(Porosity, SingleCellCapsMatchOctantSums) {
  // Spheres inside one cell in x-z: whole, or cut by one or both y walls.
  const gas::GasGrid g = layer_grid();
  double worst = 0.0;
  int single = 0;
  random_spheres_in_layer(
      g, 11, 2000, [&](const Vec3& x, double R, const std::vector<double>& frac) {
        const auto c = g.cell_of(x);
        const auto [lo, hi] = layer_cell(g, c[0], c[2]);
        const bool inside_xz =
            x[0] - R >= lo[0] && x[0] + R <= hi[0] && x[2] - R >= lo[2] && x[2] + R <= hi[2];
        if (!inside_xz) return;
        ++single;
        const double ref = sphere_box_volume(x, R, lo, hi) / g.cell_volume();
        const double got = frac[static_cast<std::size_t>(g.idx(c[0], c[1], c[2]))];
        worst = std::max(worst, std::abs(got / ref - 1.0));
      });
  std::printf("single-cell spheres: %d, max rel. difference caps vs octant sums %.2e\n", single,
              worst);
  EXPECT_GT(single, 200);
  EXPECT_LT(worst, 1e-13);
}

TEST(Porosity, RowOfCellsSlabsMatchOctantSums) {
  // Spheres whose range crosses cell faces along x or along z but not both (each cell holds a
  // slab of the ball between two parallel planes: the ball minus two caps). Reference:
  // sphere_box_volume of each cell (the octant inclusion-exclusion), to 1e-13 of the ball's
  // volume per cell (both are exact formulas; round-off only).
  const gas::GasGrid g = layer_grid();
  double worst = 0.0;
  int rows = 0;
  random_spheres_in_layer(
      g, 12, 4000, [&](const Vec3& x, double R, const std::vector<double>& frac) {
        const auto c0 = g.cell_of({x[0] - R, x[1], x[2] - R});
        const auto c1 = g.cell_of({x[0] + R, x[1], x[2] + R});
        if ((c0[0] != c1[0]) == (c0[2] != c1[2])) return; // one cell, or a corner: other paths
        ++rows;
        const double V = 4.0 / 3.0 * pi * R * R * R;
        for (int k = c0[2]; k <= c1[2]; ++k)
          for (int i = c0[0]; i <= c1[0]; ++i) {
            const auto [lo, hi] = layer_cell(g, i, k);
            const double ref = sphere_box_volume(x, R, lo, hi);
            const double got = frac[static_cast<std::size_t>(g.idx(i, 1, k))] * g.cell_volume();
            worst = std::max(worst, std::abs(got - ref) / V);
          }
      });
  std::printf("spheres across one axis of faces: %d, max |slabs - octant sums| / V %.2e\n", rows,
              worst);
  EXPECT_GT(rows, 1000);
  EXPECT_LT(worst, 1e-13);
}

TEST(Porosity, DiscsAcrossOneAxisOfFacesMatchQuadrantSums2D) {
  // 2-D: a disc whose cell faces cut it along one axis at most (inside one cell, or a row of
  // cells along x or along z; also where a domain wall clamps the range and cuts the disc) gets
  // the disc minus its circular segments. Reference: disc_rect_area of every cell of the
  // range (the quadrant inclusion-exclusion), to 1e-13 of the disc's area per cell (both exact
  // formulas; round-off only). Centres anywhere in the domain, so discs cross the walls too.
  const gas::GasGrid g(2, {4, 1, 3}, {0.0, 0.0, 0.0}, {0.04, 0.004, 0.06});
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> ux(0.0, 0.04), uz(0.0, 0.06), rad(0.0015, 0.0045);
  double worst = 0.0;
  int single = 0, rows = 0, walls = 0;
  for (int n = 0; n < 4000; ++n) {
    ParticleStore p;
    const Vec3 x{ux(rng), 0.002, uz(rng)};
    const double R = rad(rng);
    p.add(x, {0, 0, 0}, R, 2500.0, 0, 0);
    std::vector<double> frac;
    solid_fraction(g, p, {}, frac);
    const auto c0 = g.cell_of({x[0] - R, x[1], x[2] - R});
    const auto c1 = g.cell_of({x[0] + R, x[1], x[2] + R});
    const bool inside = x[0] - R >= 0.0 && x[0] + R <= 0.04 && x[2] - R >= 0.0 && x[2] + R <= 0.06;
    if (c0[0] == c1[0] && c0[2] == c1[2]) ++single;
    if ((c0[0] != c1[0]) != (c0[2] != c1[2])) ++rows;
    if (!inside) ++walls;
    for (int k = c0[2]; k <= c1[2]; ++k)
      for (int i = c0[0]; i <= c1[0]; ++i) {
        const double x0 = (i - 1) * g.h[0], z0 = (k - 1) * g.h[2];
        const double ref = disc_rect_area(x[0], x[2], R, x0, x0 + g.h[0], z0, z0 + g.h[2]);
        const double got = frac[static_cast<std::size_t>(g.idx(i, 1, k))] * g.h[0] * g.h[2];
        worst = std::max(worst, std::abs(got - ref) / (pi * R * R));
      }
  }
  std::printf("discs: %d in one cell, %d across one axis of faces, %d across a wall; max |got - "
              "quadrant sums| / area %.2e\n",
              single, rows, walls, worst);
  EXPECT_GT(single, 200);
  EXPECT_GT(rows, 1000);
  EXPECT_GT(walls, 500);
  EXPECT_LT(worst, 1e-13);
  // Discs touching a cell face (centre R from it, Hoomans' grid of 10 x 20 mm cells, 4 mm
  // discs): the range takes in the cell beyond the face, where the segment's height is 2R up to
  // round-off, which can make it larger (it once gave a NaN porosity); the cells must still hold
  // the whole disc.
  const gas::GasGrid bed(2, {15, 1, 25}, {0.0, 0.0, 0.0}, {0.15, 0.004, 0.5});
  const double r = 0.002;
  int checked = 0;
  for (int k = 1; k < 15; ++k)
    for (const double side : {-r, r}) {
      for (const Vec3& x :
           {Vec3{k * 0.01 + side, 0.002, 0.25}, Vec3{0.075, 0.002, k * 0.02 + side}}) {
        ParticleStore p;
        p.add(x, {0, 0, 0}, r, 2500.0, 0, 0);
        std::vector<double> frac;
        solid_fraction(bed, p, {}, frac);
        EXPECT_NEAR(total(frac, bed.h[0] * bed.h[2]) / (pi * r * r), 1.0, 1e-13)
            << "disc at " << x[0] << ", " << x[2];
        ++checked;
      }
    }
  EXPECT_EQ(checked, 56);
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

TEST(Porosity, BallOctantClosedFormVsQuadrature) {
  std::mt19937_64 rng(2024);
  for (double R : {1.0, 0.0013, 37.0}) {
    std::uniform_real_distribution<double> u(-1.2 * R, 1.2 * R);
    std::vector<std::array<double, 3>> pts;
    for (int n = 0; n < 20000; ++n) pts.push_back({u(rng), u(rng), u(rng)});
    // Degenerate and near-tangent corners: planes through the centre, touching the ball, the
    // corner on (or just inside) the sphere, edges tangent to it, all sign combinations.
    std::uniform_real_distribution<double> dir(-1.0, 1.0);
    for (int n = 0; n < 2000; ++n) {
      std::array<double, 3> p{dir(rng), dir(rng), dir(rng)};
      const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      const double shrink = 1.0 - std::pow(10.0, -1.0 - 14.0 * (n % 8) / 7.0); // 0.9 .. 1-1e-15
      for (double s : {1.0, shrink})
        pts.push_back({s * R * p[0] / len, s * R * p[1] / len, s * R * p[2] / len});
      const double e = R * std::sqrt(std::max(1.0 - p[0] * p[0], 0.0)); // edge tangent to ball
      pts.push_back({p[0] * R, (n % 2 ? -1.0 : 1.0) * e * shrink, p[2] * R});
    }
    for (double a : {0.0, 1e-300, 1e-14, 0.3, 1.0 - 1e-15, 1.0, 1.0 + 1e-15})
      for (double b : {0.0, -1e-14, -0.5, -(1.0 - 1e-15), -1.0, 0.7})
        for (double c : {0.0, 2e-16, -0.2, 0.999999999999}) pts.push_back({a * R, b * R, c * R});
    double worst = 0.0;
    std::array<double, 3> at{};
    for (const auto& p : pts) {
      const double err = std::abs(ball_octant_volume(R, p[0], p[1], p[2]) -
                                  octant_reference(R, p[0], p[1], p[2])) /
                         (R * R * R);
      if (err > worst) {
        worst = err;
        at = p;
      }
    }
    std::printf("R = %g: max |closed form - quadrature| / R^3 = %.2e over %zu corners, at (%.17g, "
                "%.17g, %.17g) R\n",
                R, worst, pts.size(), at[0] / R, at[1] / R, at[2] / R);
    EXPECT_LT(worst, 1e-11);
  }
}

TEST(Porosity, BallOctantHighPrecision) {
  // (X, Y, Z) / R and V / R^3 from mpmath at 40 digits (the doubles below taken exactly).
  const std::array<std::array<double, 4>, 9> ref{{
      {-0.28137044164482361, 0.58688072765983734, 2.2259006305702655e-05, 0.563750615005947296905},
      {0.3, 0.4, 0.5, 1.91104532676739852404},
      {-0.3, -0.4, -0.5, 0.0191870701427551218942},
      {-0.57, -0.57, -0.57, 0.00000177018275849281895978},
      {-0.5, -0.5, -0.7071, 1.03941392831791401359e-16},
      {-0.6, -0.79999999, 0.3, 8.99492305549073288419e-21},
      {0.999999999999, 0.999999999999, -0.999999, 3.14159160657291912032e-12},
      {1e-12, -1e-12, 0.5, 0.883572933822129348318},
      {-0.05, 0.7, -0.7124, 0.103606219696429045782},
  }};
  double worst = 0.0;
  for (const auto& r : ref)
    worst = std::max(worst, std::abs(ball_octant_volume(1.0, r[0], r[1], r[2]) - r[3]));
  std::printf("max |closed form - 40-digit value| = %.2e R^3\n", worst);
  EXPECT_LT(worst, 1e-15);
}

TEST(Porosity, BallOctantIdentities) {
  const double R = 0.75;
  const double V = 4.0 / 3.0 * pi * R * R * R;
  EXPECT_NEAR(ball_octant_volume(R, 0, 0, 0) / V, 0.125, 1e-15);
  EXPECT_NEAR(ball_octant_volume(R, 5, -0.0, 2) / V, 0.5, 1e-15);
  EXPECT_NEAR(ball_octant_volume(R, 0, 0, R) / V, 0.25, 1e-15);
  EXPECT_EQ(ball_octant_volume(R, 1, 1, 1), V);
  EXPECT_EQ(ball_octant_volume(R, -R, 0, 0), 0.0);
  // Corner on the sphere: nothing left; planes through the centre cut caps into halves, quarters.
  EXPECT_EQ(ball_octant_volume(R, -0.6 * R, -0.8 * R, 0.0 * R - 0.0), 0.0);
  EXPECT_NEAR(ball_octant_volume(R, -0.6 * R, -0.8 * R, 0.01 * R), 0.0, 1e-15 * V);
  for (double h : {1e-6, 0.01, 0.3, 0.9, 1.0, 1.5, 1.99}) {
    const double cap = pi * h * h * (3.0 - h) / 3.0 * R * R * R; // height h R
    const double zc = (1.0 - h) * R;                             // cap {z > zc}
    EXPECT_NEAR(ball_octant_volume(R, 0, 0, -zc), cap / 4.0, 1e-15 * V);
    EXPECT_NEAR(ball_octant_volume(R, 0, 3 * R, -zc), cap / 2.0, 1e-15 * V);
    EXPECT_NEAR(ball_octant_volume(R, 0, -0.0, zc) + ball_octant_volume(R, 0, 0, -zc), V / 4.0,
                1e-15 * V);
  }
  // The 8 octants around a point (inside or outside the ball) sum to the ball;
  // {x > X} is the mirror image of {x < -X}. Permutations give identical values.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.1 * R, 1.1 * R);
  double worst_sum = 0.0, worst_perm = 0.0;
  for (int n = 0; n < 20000; ++n) {
    const double X = u(rng), Y = u(rng), Z = u(rng);
    double s = 0.0;
    for (int m = 0; m < 8; ++m)
      s += ball_octant_volume(R, (m & 1) ? -X : X, (m & 2) ? -Y : Y, (m & 4) ? -Z : Z);
    worst_sum = std::max(worst_sum, std::abs(s / V - 1.0));
    const double v = ball_octant_volume(R, X, Y, Z);
    for (const auto& p :
         {std::array<double, 3>{X, Z, Y}, {Y, X, Z}, {Y, Z, X}, {Z, X, Y}, {Z, Y, X}})
      worst_perm = std::max(worst_perm, std::abs(ball_octant_volume(R, p[0], p[1], p[2]) - v));
  }
  std::printf("8-octant sum: max rel. error %.2e; permutations: max difference %.2e R^3\n",
              worst_sum, worst_perm / (R * R * R));
  EXPECT_LT(worst_sum, 1e-13);
  EXPECT_EQ(worst_perm, 0.0);
}

TEST(Porosity, BallOctantNearTangency) {
  // Corner approaching the sphere along a fixed direction n (all components < 0, so the region
  // is the small piece beyond the corner): the volume is nonnegative, does not increase as the
  // corner moves out (up to the ~1e-16 R^3 rounding floor), vanishes on the sphere, and follows
  // the tetrahedron cut off by the tangent plane, h^3 / (6 n_x n_y n_z), h = R - |corner|:
  // |V - h^3 / (6 n_x n_y n_z)| <= C V h / R + 1e-15 R^3 for h = 1e-1 .. 1e-15 R, C = 1 + 10 / min
  // n (the sphere's curvature over the tetrahedron's longest edge, h / min n).
  const double R = 2.0, R3 = R * R * R;
  for (const auto& n :
       {std::array<double, 3>{0.6, 0.48, 0.64}, {0.05, 0.7, 0.71}, {0.577, 0.577, 0.5776}}) {
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double nx = n[0] / len, ny = n[1] / len, nz = n[2] / len;
    const double C = 1.0 + 10.0 / std::min({nx, ny, nz});
    double prev = 1e300, worst = 0.0;
    for (int k = 0; k <= 2000; ++k) {
      const double h = R * std::pow(10.0, -1.0 - 14.0 * k / 2000.0); // 0.1 R .. 1e-15 R
      const double d = R - h;
      const double v = ball_octant_volume(R, -d * nx, -d * ny, -d * nz);
      const double asym = h * h * h / (6.0 * nx * ny * nz);
      EXPECT_GE(v, 0.0);
      EXPECT_LE(v, prev + 1e-15 * R3) << "h = " << h;
      prev = v;
      worst = std::max(worst, std::abs(v - asym) / (C * asym * h / R + 1e-15 * R3));
    }
    EXPECT_EQ(ball_octant_volume(R, -R * nx, -R * ny, -R * nz), 0.0);
    std::printf("tiny corner n = (%.3f, %.3f, %.3f): |V - h^3/(6 n_x n_y n_z)| <= %.2f of the "
                "bound\n",
                nx, ny, nz, worst);
    EXPECT_LE(worst, 1.0);
  }
}
