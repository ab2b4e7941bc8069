// Porous-cube mapping weights [Deen07 §3.5, eq. 38-39].
// References and tolerances:
//  - hand-computed 1-D overlaps (exact binary fractions, 1e-15): a cube of side 2h centred on a
//    cell centre covers 1/4, 1/2, 1/4 of the three cells, centred on a face 1/2, 1/2; the face
//    control volumes [x_i - h/2, x_i + h/2] the converse; 3-D weights are the tensor product;
//  - walls: the cube is shifted into the domain (porosity.cpp's shift), the boundary face gets
//    its inside half; a domain narrower than the cube: the cube clipped to it, renormalised;
//  - periodic: overlaps wrap onto the image cells/faces (ghost 0 = cell n, face 0 = face n), a
//    cube wider than the period wraps more than once (each point of the period covered
//    side/period times: hand values 1/6, 1/4, 1/3, 1/4);
//  - sum of the weights = 1 to 1e-14 (the exchange of [Deen07 eq. 39] conserves the force) for
//    random centres and sizes, 2-D and 3-D, walled and periodic axes, every component; weights
//    positive, indices distinct and on the control volumes the solver owns;
//  - porosity.cpp (porous cube, [Deen07 eq. 36-37]) per cell = V_p / V_cell * w_cell, 1e-14
//    (same cube, same shift), 3-D and 2-D (disc area / cell area), walled and periodic axes;
//  - [Deen07 eq. 38] of a constant field is the constant (1e-14 relative); of a field linear in x
//    at the control-volume centres, for a cube whose x-faces lie on control-volume boundaries, it
//    is the exact average of the piecewise-constant field (computed independently from the
//    control-volume lengths), 1e-14;
//  - periodic: the centre shifted by whole periods gives the same indices and weights (1e-15);
//  - once warmed up, a call does not reallocate the output.
#include "coupling/cube_mapping.hpp"
#include "coupling/porosity.hpp"
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <random>

using namespace fluidem;
using namespace fluidem::coupling;

namespace {
constexpr double pi = 3.14159265358979323846;

/// Index -> weight; fails the test on a repeated index.
std::map<long, double> as_map(const CubeWeights& cw) {
  std::map<long, double> m;
  EXPECT_EQ(cw.q.size(), cw.w.size());
  for (std::size_t e = 0; e < cw.size(); ++e) {
    EXPECT_TRUE(m.emplace(cw.q[e], cw.w[e]).second) << "repeated index " << cw.q[e];
  }
  return m;
}

double weight_of(const std::map<long, double>& m, long q) {
  const auto it = m.find(q);
  return it == m.end() ? 0.0 : it->second;
}

/// Sum of the weights, accumulated in long double: the property tested is the weights' own sum,
/// not the round-off of a double summation of hundreds of terms (up to N 2^-53, [Higham02 §4.2]).
double weight_sum(const CubeWeights& cw) {
  long double s = 0.0L;
  for (double v : cw.w) s += v;
  return static_cast<double>(s);
}

/// Expect exactly the given (index, weight) pairs, weights to 1e-15.
void expect_weights(const CubeWeights& cw, const std::map<long, double>& ref) {
  const auto m = as_map(cw);
  EXPECT_EQ(m.size(), ref.size());
  for (const auto& [q, w] : ref) EXPECT_NEAR(weight_of(m, q), w, 1e-15) << "index " << q;
}

// 8^3 unit cells on [0, 8]^3.
gas::GasGrid unit_grid(int dim = 3) {
  return gas::GasGrid(dim, {8, dim == 2 ? 1 : 8, 8}, {0.0, 0.0, 0.0}, {8.0, 8.0, 8.0});
}
} // namespace

TEST(CubeMapping, HandComputedInterior) {
  const auto g = unit_grid();
  const std::array<bool, 3> walls{};
  CubeWeights cw;
  // Side 2h centred on the centre of cell 4 along x (x = 3.5), on the face between cells 4 and 5
  // along y and z (y = z = 4): x gives 1/4, 1/2, 1/4 (cells 3, 4, 5), y and z 1/2, 1/2 (cells 4,
  // 5): 3 x 2 x 2 cells, weights the products.
  cube_weights(g, cell_component, {3.5, 4.0, 4.0}, 1.0, walls, cw);
  std::map<long, double> ref;
  const std::map<int, double> wx{{3, 0.25}, {4, 0.5}, {5, 0.25}}, wyz{{4, 0.5}, {5, 0.5}};
  for (const auto& [i, a] : wx)
    for (const auto& [j, b] : wyz)
      for (const auto& [k, c] : wyz) ref[g.idx(i, j, k)] = a * b * c;
  expect_weights(cw, ref);
  EXPECT_NEAR(weight_of(as_map(cw), g.idx(4, 4, 4)), 0.125, 1e-15);
  EXPECT_NEAR(weight_of(as_map(cw), g.idx(3, 5, 4)), 0.0625, 1e-15);

  // u faces (normal to x): the face control volumes [i - 1/2, i + 1/2] along x. Centre x = 3.5 on
  // a control-volume boundary: faces 3 and 4 get 1/2 each; centre x = 4 (face 4): 1/4, 1/2, 1/4
  // on faces 3, 4, 5. Along y, z the cell extents (as for the cells).
  cube_weights(g, 0, {3.5, 4.0, 4.0}, 1.0, walls, cw);
  ref.clear();
  for (int i : {3, 4})
    for (const auto& [j, b] : wyz)
      for (const auto& [k, c] : wyz) ref[g.idx(i, j, k)] = 0.5 * b * c;
  expect_weights(cw, ref);
  cube_weights(g, 0, {4.0, 4.0, 4.0}, 1.0, walls, cw);
  ref.clear();
  for (const auto& [i, a] : wx)
    for (const auto& [j, b] : wyz)
      for (const auto& [k, c] : wyz) ref[g.idx(i, j, k)] = a * b * c;
  expect_weights(cw, ref);
  // w faces (normal to z) at centre z = 4.0 (face 4): 1/4, 1/2, 1/4 on faces 3, 4, 5 along z.
  cube_weights(g, 2, {3.5, 4.0, 4.0}, 1.0, walls, cw);
  ref.clear();
  for (const auto& [i, a] : wx)
    for (const auto& [j, b] : wyz)
      for (const auto& [k, c] : wx) ref[g.idx(i, j, k)] = a * b * c;
  expect_weights(cw, ref);
}

TEST(CubeMapping, HandComputedWalls) {
  const std::array<bool, 3> walls{};
  CubeWeights cw;
  // 2-D grid, x-z plane, 8 x 8 unit cells. A square of side 2 at x = 0.2 (past the wall's
  // reach) is shifted to x = 1 (porosity.cpp): cells 1 and 2 get 1/2 each along x; along z at
  // 4.5 (cell centre): 1/4, 1/2, 1/4.
  const auto g2 = unit_grid(2);
  cube_weights(g2, cell_component, {0.2, 0.5, 4.5}, 1.0, walls, cw);
  std::map<long, double> ref;
  const std::map<int, double> wz{{4, 0.25}, {5, 0.5}, {6, 0.25}};
  for (const auto& [k, c] : wz) {
    ref[g2.idx(1, 1, k)] = 0.5 * c;
    ref[g2.idx(2, 1, k)] = 0.5 * c;
  }
  expect_weights(cw, ref);
  // u faces of the shifted square [0, 2]: boundary face 0 only its inside half [0, 1/2] -> 1/4,
  // face 1 [1/2, 3/2] -> 1/2, face 2 [3/2, 2] -> 1/4.
  cube_weights(g2, 0, {-3.0, 0.5, 4.5}, 1.0, walls, cw);
  ref.clear();
  for (const auto& [k, c] : wz) {
    ref[g2.idx(0, 1, k)] = 0.25 * c;
    ref[g2.idx(1, 1, k)] = 0.5 * c;
    ref[g2.idx(2, 1, k)] = 0.25 * c;
  }
  expect_weights(cw, ref);
  // High wall along z, w faces: the square shifted to z = 7 ([6, 8]): faces 6 (1/4), 7 (1/2),
  // 8 = the top boundary face (its inside half, 1/4). No v_y in 2-D.
  cube_weights(g2, 2, {3.5, 0.5, 7.9}, 1.0, walls, cw);
  ref.clear();
  for (const auto& [k, c] : std::map<int, double>{{6, 0.25}, {7, 0.5}, {8, 0.25}})
    for (const auto& [i, a] : std::map<int, double>{{3, 0.25}, {4, 0.5}, {5, 0.25}})
      ref[g2.idx(i, 1, k)] = a * c;
  expect_weights(cw, ref);
  cube_weights(g2, 1, {3.5, 0.5, 4.5}, 1.0, walls, cw);
  EXPECT_EQ(cw.size(), 0u);

  // Domain narrower than the cube along x (2 unit cells, cube side 3): the cube is centred on
  // the domain and clipped to [0, 2]: cells 1/2, 1/2; faces 0, 1, 2: 1/4, 1/2, 1/4.
  const gas::GasGrid gn(3, {2, 8, 8}, {0.0, 0.0, 0.0}, {2.0, 8.0, 8.0});
  cube_weights(gn, cell_component, {1.9, 4.0, 4.0}, 1.5, walls, cw);
  EXPECT_NEAR(weight_sum(cw), 1.0, 1e-15);
  auto m = as_map(cw);
  // y, z: side 3 centred on y = 4: cells 3 ([2, 3]: 1/2 -> 1/6), 4 (1/3), 5 (1/3), 6 (1/6).
  EXPECT_NEAR(weight_of(m, gn.idx(1, 4, 5)), 0.5 / 9.0, 1e-15);
  EXPECT_NEAR(weight_of(m, gn.idx(2, 3, 6)), 0.5 / 36.0, 1e-15);
  EXPECT_EQ(m.size(), 2u * 4u * 4u);
  cube_weights(gn, 0, {1.9, 4.0, 4.0}, 1.5, walls, cw);
  m = as_map(cw);
  EXPECT_EQ(m.size(), 3u * 4u * 4u);
  EXPECT_NEAR(weight_of(m, gn.idx(0, 4, 4)), 0.25 / 9.0, 1e-15);
  EXPECT_NEAR(weight_of(m, gn.idx(1, 4, 4)), 0.5 / 9.0, 1e-15);
  EXPECT_NEAR(weight_of(m, gn.idx(2, 4, 4)), 0.25 / 9.0, 1e-15);
}

TEST(CubeMapping, HandComputedPeriodic) {
  const auto g = unit_grid();
  const std::array<bool, 3> px{true, false, false};
  CubeWeights cw;
  // Cube [-0.75, 1.25] along periodic x (8 unit cells), y, z centred on cell 4 of a side-2 cube.
  // Cells: unwrapped 0 ([-1, 0], 0.75) = image of cell 8, cell 1 (1), cell 2 (0.25); / 2.
  cube_weights(g, cell_component, {0.25, 3.5, 3.5}, 1.0, px, cw);
  std::map<long, double> ref;
  const std::map<int, double> wyz{{3, 0.25}, {4, 0.5}, {5, 0.25}};
  for (const auto& [i, a] : std::map<int, double>{{8, 0.375}, {1, 0.5}, {2, 0.125}})
    for (const auto& [j, b] : wyz)
      for (const auto& [k, c] : wyz) ref[g.idx(i, j, k)] = a * b * c;
  expect_weights(cw, ref);
  // u faces: face -1 ([-1.5, -0.5], 0.25) = face 7, face 0 ([-0.5, 0.5], 1) = face 8 (face 0 is
  // a copy of face n), face 1 ([0.5, 1.5], 0.75); / 2.
  cube_weights(g, 0, {0.25, 3.5, 3.5}, 1.0, px, cw);
  ref.clear();
  for (const auto& [i, a] : std::map<int, double>{{7, 0.125}, {8, 0.5}, {1, 0.375}})
    for (const auto& [j, b] : wyz)
      for (const auto& [k, c] : wyz) ref[g.idx(i, j, k)] = a * b * c;
  expect_weights(cw, ref);

  // Cube of side 6 across a period of 4 unit cells, centre x = 0.5: [-2.5, 3.5] covers cell 1
  // once (1), cell 2 1.5 times ([-3, -2] half, [1, 2]), cell 3 twice, cell 4 1.5 times: / 6.
  const gas::GasGrid g4(3, {4, 8, 8}, {0.0, 0.0, 0.0}, {4.0, 8.0, 8.0});
  cube_weights(g4, cell_component, {0.5, 4.0, 4.0}, 3.0, px, cw);
  const auto m = as_map(cw);
  EXPECT_EQ(m.size(), 4u * 6u * 6u); // y, z: walled, cube [1, 7]: cells 2..7
  const double wy4 = 1.0 / 6.0;      // cell 4 along y, z: 1 of 6
  const std::array<double, 4> wx{1.0 / 6.0, 0.25, 1.0 / 3.0, 0.25};
  for (int i = 1; i <= 4; ++i)
    EXPECT_NEAR(weight_of(m, g4.idx(i, 4, 4)), wx[static_cast<std::size_t>(i - 1)] * wy4 * wy4,
                1e-15);
  EXPECT_NEAR(weight_sum(cw), 1.0, 1e-14);
}

TEST(CubeMapping, WeightsSumToOne) {
  std::mt19937_64 rng(38);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::array<double, 3> lo{-0.03, 0.01, 0.2};
  const std::array<std::array<bool, 3>, 4> pers{
      {{false, false, false}, {true, false, false}, {true, true, true}, {false, true, true}}};
  CubeWeights cw;
  int checked = 0;
  for (int dim : {2, 3}) {
    const std::array<int, 3> n{5, dim == 2 ? 1 : 4, 7};
    const std::array<double, 3> hi{0.02, 0.05, 0.37};
    const gas::GasGrid g(dim, n, lo, hi);
    for (const auto& per : pers)
      for (int comp = -1; comp < 3; ++comp)
        for (int t = 0; t < 400; ++t) {
          Vec3 c;
          for (int d = 0; d < 3; ++d) {
            const double L = hi[d] - lo[d];
            c[d] = lo[d] + (-0.6 + 2.2 * u(rng)) * L; // inside, near and beyond the walls
          }
          // half from a fifth of the smallest cell to 1.5x the largest domain extent (narrower
          // walled domains: clipped cubes; periodic: several wraps).
          const double half = 0.2 * 0.01 * std::exp(u(rng) * std::log(0.33 * 1.5 / 0.2 / 0.01));
          cube_weights(g, comp, c, half, per, cw);
          if (dim == 2 && comp == 1) {
            EXPECT_EQ(cw.size(), 0u);
            continue;
          }
          ASSERT_GT(cw.size(), 0u);
          EXPECT_NEAR(weight_sum(cw), 1.0, 1e-14) << "dim " << dim << " comp " << comp;
          as_map(cw); // distinct indices
          for (std::size_t e = 0; e < cw.size(); ++e) {
            EXPECT_GT(cw.w[e], 0.0);
            // Index on the control volumes the solver owns: cells 1..n; faces along walled d
            // 0..n_d, along periodic d 1..n_d.
            long r = cw.q[e];
            for (int d = 2; d >= 0; --d) {
              const long i = r / g.stride[d];
              r -= i * g.stride[d];
              const long first = (comp == d && !per[d]) ? 0 : 1;
              EXPECT_GE(i, first);
              EXPECT_LE(i, n[d]);
            }
          }
          ++checked;
        }
  }
  EXPECT_EQ(checked, (4 * 3 + 4 * 4) * 400);
}

TEST(CubeMapping, MatchesPorousCubePorosity) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PorositySettings s;
  s.method = PorosityMethod::porous_cube;
  CubeWeights cw;
  std::vector<double> frac;
  // Walled domain (the cube shifted in) and periodic x, z (solid_fraction's periodic argument:
  // the cube unshifted, its cells folded onto the images).
  for (const auto& per : {std::array<bool, 3>{}, std::array<bool, 3>{true, false, true}})
    for (int dim : {3, 2}) {
      const std::array<double, 3> lo{0.01, -0.002, 0.003}, hi{0.016, 0.004, 0.0105};
      const gas::GasGrid g(dim, {6, dim == 2 ? 1 : 5, 7}, lo, hi);
      const double cell_measure = dim == 2 ? g.h[0] * g.h[2] : g.cell_volume();
      for (int t = 0; t < 200; ++t) {
        s.cube_factor = 1.0 + 3.0 * u(rng);
        const double R = (0.2 + 0.5 * u(rng)) * 1e-3 / s.cube_factor; // cube side <= 1.4 mm
        Vec3 x;
        for (int d = 0; d < 3; ++d) x[d] = lo[d] + (-0.1 + 1.2 * u(rng)) * (hi[d] - lo[d]);
        ParticleStore p;
        p.add(x, {0, 0, 0}, R, 2500.0, 0, 0);
        solid_fraction(g, p, s, frac, per);
        const double half = 0.5 * s.cube_factor * 2.0 * R; // [Deen07 eq. 34]
        cube_weights(g, cell_component, x, half, per, cw);
        const auto m = as_map(cw);
        // 3-D: V_p / V_cell; 2-D: disc area / cell area (solid_fraction before [Hoomans96 eq. 49])
        const double scale =
            (dim == 2 ? pi * R * R : 4.0 / 3.0 * pi * R * R * R) / cell_measure; // [eq. 36-37]
        double max_frac = 0.0;
        for (int k = 1; k <= g.n[2]; ++k)
          for (int j = 1; j <= g.n[1]; ++j)
            for (int i = 1; i <= g.n[0]; ++i) {
              const long q = g.idx(i, j, k);
              max_frac = std::max(max_frac, frac[static_cast<std::size_t>(q)]);
              EXPECT_NEAR(frac[static_cast<std::size_t>(q)], scale * weight_of(m, q), 1e-14)
                  << "periodic " << per[0] << " dim " << dim << " cell " << i << " " << j << " "
                  << k;
            }
        EXPECT_GT(max_frac, 1e-4); // the comparison is not vacuous
      }
    }
}

TEST(CubeMapping, AverageOfConstantAndLinearFields) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const gas::GasGrid g(3, {9, 6, 8}, {0.1, 0.2, 0.3}, {1.0, 0.8, 1.1}); // h = 0.1
  CubeWeights cw;
  const std::vector<double> one(g.size(), 3.7);
  for (const auto& per : {std::array<bool, 3>{}, std::array<bool, 3>{true, false, true}})
    for (int comp = -1; comp < 3; ++comp)
      for (int t = 0; t < 100; ++t) {
        const Vec3 c{-0.2 + 1.4 * u(rng), 0.2 + 0.6 * u(rng), 0.3 + 0.8 * u(rng)};
        cube_weights(g, comp, c, 0.02 + 0.4 * u(rng), per, cw);
        // Double summation of N terms: error <= N 2^-53 sum |w a| [Higham02 eq. 4.4] (measured
        // up to 1e-14 relative for N ~ 500), plus the weights' own 1e-15.
        EXPECT_NEAR(cube_average(cw, one), 3.7,
                    3.7 * (1e-15 + static_cast<double>(cw.size()) * 1.2e-16));
      }

  // phi = 2 - 5 x at the control-volume centres (cells: x_i = lo + (i - 1/2) h; u faces:
  // lo + i h), constant in y, z. The exact average over [a, b] of the piecewise-constant field
  // is sum_i |[a, b] cap CV_i| phi_i / (b - a), the lengths written out by hand below.
  const double h = 0.1, lo = 0.1;
  auto phi = [](double x) { return 2.0 - 5.0 * x; };
  std::vector<double> fc(g.size()), fu(g.size());
  for (int k = 0; k < g.padded[2]; ++k)
    for (int j = 0; j < g.padded[1]; ++j)
      for (int i = 0; i < g.padded[0]; ++i) {
        const auto q = static_cast<std::size_t>(g.idx(i, j, k));
        fc[q] = phi(lo + (i - 0.5) * h);
        fu[q] = phi(lo + i * h);
      }
  const std::array<bool, 3> walls{};
  // Cells: cube [0.3, 0.6] in x (cells 3, 4, 5 whole), off-grid in y and z.
  cube_weights(g, cell_component, {0.45, 0.537, 0.611}, 0.15, walls, cw);
  double ref = (0.1 * phi(0.35) + 0.1 * phi(0.45) + 0.1 * phi(0.55)) / 0.3;
  EXPECT_NEAR(cube_average(cw, fc), ref, 1e-14);
  // u faces: cube [0.25, 0.65] in x: faces 2..5 ([0.25, 0.35] ... [0.55, 0.65]) whole.
  cube_weights(g, 0, {0.45, 0.537, 0.611}, 0.2, walls, cw);
  ref = (0.1 * phi(0.3) + 0.1 * phi(0.4) + 0.1 * phi(0.5) + 0.1 * phi(0.6)) / 0.4;
  EXPECT_NEAR(cube_average(cw, fu), ref, 1e-14);
  // u faces at the low wall: the cube [0.1, 0.4] (shifted from x = 0.12): boundary face 0 its
  // inside half [0.1, 0.15], faces 1, 2 whole, face 3 [0.35, 0.4].
  cube_weights(g, 0, {0.12, 0.537, 0.611}, 0.15, walls, cw);
  ref = (0.05 * phi(0.1) + 0.1 * phi(0.2) + 0.1 * phi(0.3) + 0.05 * phi(0.4)) / 0.3;
  EXPECT_NEAR(cube_average(cw, fu), ref, 1e-14);
  // Cells across the periodic x boundary: cube [0.8, 1.2] = cells 8, 9 and the images of
  // cells 1, 2 (values of cells 1, 2).
  cube_weights(g, cell_component, {1.0, 0.537, 0.611}, 0.2, {true, false, false}, cw);
  ref = (0.1 * phi(0.85) + 0.1 * phi(0.95) + 0.1 * phi(0.15) + 0.1 * phi(0.25)) / 0.4;
  EXPECT_NEAR(cube_average(cw, fc), ref, 1e-14);
}

TEST(CubeMapping, PeriodicShiftInvariance) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  CubeWeights a, b;
  const std::array<bool, 3> per{true, true, true};
  // shift_ulps = 0: lo, the periods and the centres are multiples of 2^-18 with few bits, so
  // c + k L is exact and the weights must agree to 1e-15 (indices identical). shift_ulps = 4:
  // arbitrary values; c + k L is then rounded (by <= 2 ulp of the largest operand), which moves
  // the cube by delta and each weight by up to delta / (2 half) (1-D), so the tolerance is
  // 3 * 4 ulp(|c| + 2 L) / (2 half) (three axes); indices still identical.
  for (int exact = 1; exact >= 0; --exact)
    for (int dim : {2, 3}) {
      const std::array<double, 3> lo = exact ? std::array<double, 3>{-0.25, 0.0, 0.125}
                                             : std::array<double, 3>{-0.05, 0.0, 0.02};
      const std::array<double, 3> hi =
          exact ? std::array<double, 3>{0.5, 0.375, 1.125} : std::array<double, 3>{0.07, 0.03, 0.2};
      const gas::GasGrid g(dim, {6, dim == 2 ? 1 : 3, 9}, lo, hi);
      double span = 0.0;
      for (int d = 0; d < 3; ++d) span = std::max(span, std::abs(lo[d]) + 3.0 * (hi[d] - lo[d]));
      for (int comp = -1; comp < 3; ++comp)
        for (int t = 0; t < 200; ++t) {
          Vec3 c;
          for (int d = 0; d < 3; ++d) {
            const double f = exact ? std::floor(u(rng) * 65536.0) / 65536.0 : u(rng);
            c[d] = lo[d] + f * (hi[d] - lo[d]);
          }
          // up to wider than every period
          const double half = (exact ? 0.04 : 0.005) + (exact ? 1.2 : 0.15) * u(rng);
          const double tol =
              exact ? 1e-15 : std::max(1e-15, 3.0 * 4.0 * span * 2.3e-16 / (2.0 * half));
          cube_weights(g, comp, c, half, per, a);
          for (int shift : {1, -1, 2}) {
            Vec3 cs = c;
            cs[0] += shift * (hi[0] - lo[0]);
            cs[2] -= shift * (hi[2] - lo[2]);
            if (dim == 3) cs[1] += shift * (hi[1] - lo[1]);
            cube_weights(g, comp, cs, half, per, b);
            ASSERT_EQ(a.q, b.q);
            for (std::size_t e = 0; e < a.size(); ++e) EXPECT_NEAR(a.w[e], b.w[e], tol);
          }
        }
    }
}

TEST(CubeMapping, NoReallocationOnceWarm) {
  const auto g = unit_grid();
  const std::array<bool, 3> walls{};
  CubeWeights cw;
  cube_weights(g, 1, {4.0, 4.0, 4.0}, 2.0, walls, cw);
  const auto* q = cw.q.data();
  const auto* w = cw.w.data();
  const auto* ax = cw.axes.cell_w[0].data(); // component 1: cells along x
  cube_weights(g, 1, {2.3, 5.1, 6.7}, 1.7, walls, cw);
  EXPECT_EQ(cw.q.data(), q);
  EXPECT_EQ(cw.w.data(), w);
  EXPECT_EQ(cw.axes.cell_w[0].data(), ax);
}
