// The bubble metric (analysis/bubbles.hpp) on synthetic porosity fields whose bubbles are known
// by construction: a bed of porosity 0.4 below a freeboard of porosity 1, with voids of porosity
// 0.95 painted in as the cells whose centres lie inside a disc or a sphere.
// References: the painted cells themselves (counts, centroids: exact), and the painted shape,
// whose area or volume the cells approximate to within the cells cut by its outline: for the
// radii here (3-5 cells, none with a cell centre on the outline, so that the painted cells are
// symmetric about the centre) the equivalent diameter is that of the shape within half a cell.
#include "analysis/bubbles.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

using namespace fluidem;

namespace {

constexpr double kDense = 0.4, kFree = 1.0, kVoid = 0.95;

// A planar bed (one cell across y) of nx x nz cells of 5 mm, dense below z_bed, free above.
struct Field {
  CellGrid g;
  std::vector<double> eps;
  Field(std::array<int, 3> cells, double h, double z_bed) {
    g.cells = cells;
    g.lo = {0.0, 0.0, 0.0};
    g.spacing = {h, cells[1] == 1 ? 0.004 : h, h};
    eps.assign(g.size(), kDense);
    for_cells([&](std::size_t q, double, double, double z) {
      if (z > z_bed) eps[q] = kFree;
    });
  }
  template <class F>
  void for_cells(F&& f) {
    std::size_t q = 0;
    for (int k = 0; k < g.cells[2]; ++k)
      for (int j = 0; j < g.cells[1]; ++j)
        for (int i = 0; i < g.cells[0]; ++i, ++q)
          f(q, (i + 0.5) * g.spacing[0], (j + 0.5) * g.spacing[1], (k + 0.5) * g.spacing[2]);
  }
  /// Cells whose centre is within r of (x, y, z) (y ignored on a planar grid) get `value`.
  std::size_t paint(double x, double y, double z, double r, double value = kVoid) {
    std::size_t painted = 0;
    for_cells([&](std::size_t q, double cx, double cy, double cz) {
      const double dy = g.planar() ? 0.0 : cy - y;
      if ((cx - x) * (cx - x) + dy * dy + (cz - z) * (cz - z) < r * r) {
        eps[q] = value;
        ++painted;
      }
    });
    return painted;
  }
};

} // namespace

TEST(Bubbles, DiscInsideTheBedIsOneBubbleOfItsSize) {
  const double h = 0.005, r = 0.0205; // 4.1 cells: no centre on the outline
  Field f({30, 1, 60}, h, 0.2);
  const std::size_t painted = f.paint(0.0725, 0.0, 0.1025, r);
  const BubbleFrame b = find_bubbles(f.g, f.eps);
  ASSERT_EQ(b.bubbles.size(), 1u);
  const Bubble& u = b.bubbles[0];
  EXPECT_EQ(u.cells, painted);
  EXPECT_NEAR(u.size, static_cast<double>(painted) * h * h, 1e-15);
  EXPECT_NEAR(u.equivalent_diameter, 2.0 * r, 0.5 * h);
  // Painted symmetrically about a cell centre: the centroid is that centre.
  EXPECT_NEAR(u.centroid[0], 0.0725, 1e-12);
  EXPECT_NEAR(u.centroid[2], 0.1025, 1e-12);
  EXPECT_NEAR(u.z_extent[0], 0.08, 1e-12); // the lowest painted centre: 4 cells below
  EXPECT_FALSE(u.touches_wall);
  // Bed: the 30 x 40 cells below 0.2 m; the fraction is the painted share of them.
  const double cell = h * 0.004 * h;
  EXPECT_NEAR(b.bed_volume, 30 * 40 * cell, 1e-15);
  EXPECT_NEAR(b.bubble_fraction(), static_cast<double>(painted) / (30 * 40), 1e-14);
  std::size_t bubble_cells = 0, freeboard = 0;
  for (const int l : b.label) {
    bubble_cells += l == 0;
    freeboard += l == -2;
  }
  EXPECT_EQ(bubble_cells, painted);
  EXPECT_EQ(freeboard, 30u * 20u);
}

TEST(Bubbles, ExpandedSurfaceAndEruptingVoidAreNotBubbles) {
  // The surface of an expanded bed: a ragged layer of cells above 0.8 (columns alternating
  // 0.85 / 0.75) over four rows, touching the freeboard; a void rising through the surface
  // (a column of dilute cells from inside the bed to the freeboard). The previous metric (cells
  // above 0.8 below twice the centre-of-mass height) counted both; neither is a bubble.
  const double h = 0.005;
  Field f({30, 1, 60}, h, 0.2);
  f.for_cells([&](std::size_t q, double x, double, double z) {
    if (z > 0.2 - 4 * h && z < 0.2) f.eps[q] = static_cast<int>(x / h) % 2 == 0 ? 0.85 : 0.75;
    if (x > 0.05 && x < 0.07 && z > 0.12 && z < 0.2) f.eps[q] = kVoid;
  });
  const BubbleFrame b = find_bubbles(f.g, f.eps);
  EXPECT_TRUE(b.bubbles.empty());
  EXPECT_EQ(b.bubble_fraction(), 0.0);
  // A porosity exactly at the threshold is dense (eps > 0.8 is dilute).
  Field e({10, 1, 20}, h, 0.05);
  e.paint(0.025, 0.0, 0.025, 0.008, 0.8);
  EXPECT_TRUE(find_bubbles(e.g, e.eps).bubbles.empty());
}

TEST(Bubbles, BubblesAtTheWallsAndTheDistributorCountAndCornersDoNotJoin) {
  const double h = 0.005;
  Field f({30, 1, 60}, h, 0.2);
  f.paint(0.0725, 0.0, 0.0025, 0.012); // on the distributor (a jet's void)
  f.paint(0.0025, 0.0, 0.1025, 0.012); // against the left wall
  f.paint(0.0725, 0.0, 0.1025, 0.012); // inside
  // Two single dilute cells touching only at a corner: two bubbles (faces connect, corners not).
  f.eps[static_cast<std::size_t>(20 + 30 * 30)] = kVoid;
  f.eps[static_cast<std::size_t>(21 + 30 * 31)] = kVoid;
  const BubbleFrame b = find_bubbles(f.g, f.eps);
  ASSERT_EQ(b.bubbles.size(), 5u);
  // Ordered by their lowest cell: the distributor one first.
  EXPECT_TRUE(b.bubbles[0].touches_wall);
  EXPECT_NEAR(b.bubbles[0].z_extent[0], 0.0, 1e-15);
  int at_wall = 0, single = 0;
  for (const Bubble& u : b.bubbles) {
    at_wall += u.touches_wall;
    single += u.cells == 1;
  }
  EXPECT_EQ(at_wall, 2);
  EXPECT_EQ(single, 2);
}

TEST(Bubbles, SphereInA3DBedHasTheSphereDiameter) {
  const double h = 0.01, r = 0.0505; // 5.05 cells: no centre on the outline
  Field f({20, 20, 40}, h, 0.3);
  const std::size_t painted = f.paint(0.105, 0.095, 0.155, r);
  const BubbleFrame b = find_bubbles(f.g, f.eps);
  ASSERT_EQ(b.bubbles.size(), 1u);
  EXPECT_EQ(b.bubbles[0].cells, painted);
  EXPECT_NEAR(b.bubbles[0].size, static_cast<double>(painted) * h * h * h, 1e-15);
  EXPECT_NEAR(b.bubbles[0].equivalent_diameter, 2.0 * r, 0.5 * h);
  EXPECT_NEAR(b.bubbles[0].centroid[0], 0.105, 1e-12);
  EXPECT_NEAR(b.bubbles[0].centroid[1], 0.095, 1e-12);
  EXPECT_NEAR(b.bubbles[0].centroid[2], 0.155, 1e-12);
  EXPECT_NEAR(b.bed_volume, 20 * 20 * 30 * h * h * h, 1e-15);
}

TEST(Bubbles, RisingBubbleIsFollowedAndSplitsAndMergersKeepTheLargerPart) {
  // A disc rising 2 cells per frame: each frame's bubble continues the last one, and its
  // centroid rises by 2 h per frame (rise velocity 2 h / dt).
  const double h = 0.005;
  BubbleFrame prev;
  for (int frame = 0; frame < 4; ++frame) {
    Field f({30, 1, 60}, h, 0.25);
    f.paint(0.0725, 0.0, 0.0525 + 2 * h * frame, 0.0155);
    const BubbleFrame b = find_bubbles(f.g, f.eps);
    ASSERT_EQ(b.bubbles.size(), 1u);
    if (frame > 0) {
      EXPECT_EQ(continue_bubbles(prev, b), std::vector<int>{0});
      EXPECT_NEAR(b.bubbles[0].centroid[2] - prev.bubbles[0].centroid[2], 2 * h, 1e-12);
    }
    prev = b;
  }
  // Split: a large and a small part of the last bubble's place; the large one continues it.
  Field s({30, 1, 60}, h, 0.25);
  s.paint(0.0725, 0.0, 0.0825, 0.0155);
  s.for_cells([&](std::size_t q, double x, double, double) {
    if (x > 0.065 && x < 0.07) s.eps[q] = s.eps[q] == kVoid ? kDense : s.eps[q];
  });
  const BubbleFrame split = find_bubbles(s.g, s.eps);
  ASSERT_EQ(split.bubbles.size(), 2u);
  const int larger = split.bubbles[0].cells > split.bubbles[1].cells ? 0 : 1;
  std::vector<int> expect(2, -1);
  expect[static_cast<std::size_t>(larger)] = 0;
  EXPECT_EQ(continue_bubbles(prev, split), expect);
  // Merger: the two parts join again; the whole continues the larger part (its index).
  EXPECT_EQ(continue_bubbles(split, prev), std::vector<int>{larger});
  // Nothing overlapping: a new bubble.
  Field far({30, 1, 60}, h, 0.25);
  far.paint(0.0225, 0.0, 0.0225, 0.01);
  EXPECT_EQ(continue_bubbles(prev, find_bubbles(far.g, far.eps)), std::vector<int>{-1});
}

TEST(Bubbles, BadInputIsRefused) {
  CellGrid g;
  g.cells = {4, 1, 4};
  EXPECT_THROW(find_bubbles(g, std::vector<double>(15, 0.5)), std::invalid_argument);
  g.spacing[0] = 0.0;
  EXPECT_THROW(find_bubbles(g, std::vector<double>(16, 0.5)), std::invalid_argument);
  g.spacing[0] = 1.0;
  g.cells[2] = 0;
  EXPECT_THROW(find_bubbles(g, {}), std::invalid_argument);
}
