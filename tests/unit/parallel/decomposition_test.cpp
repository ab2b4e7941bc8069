// Decomposition: the choice of the process grid, the owner of a point, the boxes with their
// distances and neighbours (periodic included), the load-balancing cuts and the validation of
// moved cuts. All reference values are computed by hand in the comments; the grids use cell
// sizes that are exact binary fractions (0.5, 0.25, 0.01 only where no exactness is needed) so
// that points on cut planes are exactly on them.
#include "parallel/decomposition.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace fluidem {
namespace {

DecompositionGrid make_grid(std::array<int, 3> cells, std::array<double, 3> hi,
                            std::array<bool, 3> periodic = {false, false, false}) {
  DecompositionGrid g;
  g.cells = cells;
  g.lo = {0.0, 0.0, 0.0};
  g.hi = hi;
  g.periodic = periodic;
  return g;
}

/// Expects std::invalid_argument whose message contains every one of `parts`.
void expect_invalid(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no std::invalid_argument thrown";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    for (const auto& p : parts)
      EXPECT_NE(msg.find(p), std::string::npos)
          << "message \"" << msg << "\" lacks \"" << p << "\"";
  }
}

// A tall 2-D bed, 15 x 1 x 25 cells (gravity along z, axis 2), min_cells 2: on 2, 3 and 4 ranks
// the columns-first rule keeps pz = 1, and y (1 cell) cannot be cut, so the only factorisation
// with pz = 1 is px = ranks; it fits since 15 >= ranks * 2 (8 for 4 ranks). Cuts are the even
// split floor(k * 15 / px): px = 2 -> 0 7 15, px = 3 -> 0 5 10 15, px = 4 -> 0 3 7 11 15.
TEST(DecompositionProcessGrid, TallTwoDimensionalBedIsCutIntoColumns) {
  const auto grid = make_grid({15, 1, 25}, {0.15, 0.01, 0.25});
  const std::vector<std::vector<int>> expected_cuts{{0, 7, 15}, {0, 5, 10, 15}, {0, 3, 7, 11, 15}};
  for (int ranks = 2; ranks <= 4; ++ranks) {
    const Decomposition d(grid, ranks, 2, {0, 0, 0}, 2);
    EXPECT_EQ(d.process_grid(), (std::array<int, 3>{ranks, 1, 1})) << ranks << " ranks";
    EXPECT_EQ(d.ranks(), ranks);
    EXPECT_EQ(d.cuts(0), expected_cuts[static_cast<std::size_t>(ranks - 2)]);
    EXPECT_EQ(d.cuts(1), (std::vector<int>{0, 1}));
    EXPECT_EQ(d.cuts(2), (std::vector<int>{0, 25}));
  }
}

// 3-D 20 x 20 x 40 cells over 0.2 x 0.2 x 0.4 m on 4 ranks (gravity z): pz = 1 is possible, and
// among {4,1,1}, {2,2,1}, {1,4,1} the cut areas are 3*0.2*0.4 = 0.24, 0.2*0.4 + 0.2*0.4 = 0.16,
// 0.24 -> 2 x 2 x 1. On 2 ranks {2,1,1} and {1,2,1} tie at 0.08 m^2: the lower axis gets the
// parts -> 2 x 1 x 1.
TEST(DecompositionProcessGrid, ThreeDimensionalMinimisesCutAreaWithDeterministicTies) {
  const auto grid = make_grid({20, 20, 40}, {0.2, 0.2, 0.4});
  const Decomposition d4(grid, 4, 2);
  EXPECT_EQ(d4.process_grid(), (std::array<int, 3>{2, 2, 1}));
  EXPECT_EQ(d4.cuts(0), (std::vector<int>{0, 10, 20}));
  EXPECT_EQ(d4.cuts(1), (std::vector<int>{0, 10, 20}));
  const Decomposition d2(grid, 2, 2);
  EXPECT_EQ(d2.process_grid(), (std::array<int, 3>{2, 1, 1}));
  // Gravity along x instead: px = 1; {1,4,1} cuts 3 * 0.2*0.4 = 0.24, {1,2,2} cuts
  // 0.2*0.4 + 0.2*0.2 = 0.12, {1,1,4} cuts 3 * 0.2*0.2 = 0.12: a tie (up to rounding), broken
  // towards more parts on the lower axis index (y) -> {1, 2, 2}.
  const Decomposition dx(grid, 4, 0);
  EXPECT_EQ(dx.process_grid(), (std::array<int, 3>{1, 2, 2}));
}

// A forced {2,1,2} on the 3-D grid with 4 ranks is used as given: cuts x 0 10 20, z 0 20 40.
// A forced grid whose product is not ranks ({2,2,2} for 4), or one that does not fit (y of a
// 2-D grid has 1 cell and cannot take 2 parts), is refused with the reason.
TEST(DecompositionProcessGrid, ForcedGridAcceptedOrRefused) {
  const auto grid = make_grid({20, 20, 40}, {0.2, 0.2, 0.4});
  const Decomposition d(grid, 4, 2, {2, 1, 2});
  EXPECT_EQ(d.process_grid(), (std::array<int, 3>{2, 1, 2}));
  EXPECT_EQ(d.cuts(0), (std::vector<int>{0, 10, 20}));
  EXPECT_EQ(d.cuts(2), (std::vector<int>{0, 20, 40}));
  expect_invalid([&] { Decomposition(grid, 4, 2, {2, 2, 2}); }, {"2 x 2 x 2", "4 ranks"});
  expect_invalid([&] { Decomposition(grid, 4, 2, {4, 0, 1}); }, {"4 x 0 x 1"});
  const auto flat = make_grid({20, 1, 40}, {0.2, 0.01, 0.4});
  expect_invalid([&] { Decomposition(flat, 4, 2, {1, 2, 2}); }, {"does not fit", "20 x 1 x 40"});
}

// 5 cells along x of a 2-D grid on 4 ranks with min_cells 2: x takes at most 2 parts (4 <= 5 but
// 8 > 5), y none, so pz = 2 is the fewest vertical parts: 2 x 1 x 2, x cuts 0 2 5, z cuts
// floor(k*25/2) = 0 12 25. With only 3 z cells no factorisation fits ({2,1,2} needs 4 z cells,
// {1,1,4} needs 8): std::invalid_argument naming the ranks, the cells and min_cells.
TEST(DecompositionProcessGrid, NarrowBedCutsVerticalOrThrows) {
  const Decomposition d(make_grid({5, 1, 25}, {0.05, 0.01, 0.25}), 4, 2, {0, 0, 0}, 2);
  EXPECT_EQ(d.process_grid(), (std::array<int, 3>{2, 1, 2}));
  EXPECT_EQ(d.cuts(0), (std::vector<int>{0, 2, 5}));
  EXPECT_EQ(d.cuts(2), (std::vector<int>{0, 12, 25}));
  expect_invalid(
      [] {
        Decomposition(make_grid({5, 1, 3}, {0.05, 0.01, 0.03}), 4, 2, {0, 0, 0}, 2);
      },
      {"4 ranks", "5 x 1 x 3", "2 cells per part"});
  // One rank always fits, even on a grid with fewer cells than min_cells (nothing is cut).
  const Decomposition one(make_grid({1, 1, 1}, {1.0, 1.0, 1.0}), 1, 2, {0, 0, 0}, 4);
  EXPECT_EQ(one.process_grid(), (std::array<int, 3>{1, 1, 1}));
}

// Invalid constructor arguments are refused with the reason: no ranks, a vertical axis outside
// 0..2, min_cells < 1, an empty box (hi <= lo) or an axis without cells.
TEST(DecompositionProcessGrid, InvalidArgumentsRefused) {
  const auto grid = make_grid({4, 4, 4}, {1.0, 1.0, 1.0});
  expect_invalid([&] { Decomposition(grid, 0, 2); }, {"ranks"});
  expect_invalid([&] { Decomposition(grid, 2, 3); }, {"vertical_axis"});
  expect_invalid([&] { Decomposition(grid, 2, 2, {0, 0, 0}, 0); }, {"min_cells"});
  auto empty = grid;
  empty.hi[1] = 0.0;
  expect_invalid([&] { Decomposition(empty, 2, 2); }, {"axis 1", "hi > lo"});
  auto no_cells = grid;
  no_cells.cells[0] = 0;
  expect_invalid([&] { Decomposition(no_cells, 2, 2); }, {"axis 0", "0 x 4 x 4"});
}

// rank_of is x slowest: on a 2 x 3 x 4 process grid (1,2,3) -> (1*3+2)*4+3 = 23 and
// (0,1,2) -> (0*3+1)*4+2 = 6; coords_of inverts it for every rank.
TEST(DecompositionRanks, RankOfAndCoordsOfAreInverse) {
  const Decomposition d(make_grid({4, 6, 8}, {1.0, 1.0, 1.0}), 24, 2, {2, 3, 4});
  EXPECT_EQ(d.rank_of({1, 2, 3}), 23);
  EXPECT_EQ(d.rank_of({0, 1, 2}), 6);
  for (int r = 0; r < 24; ++r) EXPECT_EQ(d.rank_of(d.coords_of(r)), r);
  EXPECT_EQ(d.coords_of(6), (std::array<int, 3>{0, 1, 2}));
  // Outside the process grid: std::out_of_range, not a wrong rank.
  EXPECT_THROW(d.coords_of(24), std::out_of_range);
  EXPECT_THROW(d.coords_of(-1), std::out_of_range);
  EXPECT_THROW(d.rank_of({2, 0, 0}), std::out_of_range);
}

// 6 x 1 x 8 cells of 0.5 m (box 3 x 0.5 x 4 m) on 4 ranks: auto -> 4 x 1 x 1 (x cuts
// floor(k*6/4) = 0 1 3 4 6), forced -> 2 x 1 x 2 (x 0 3 6, z 0 4 8). Every cell centre
// ((i + 0.5) * 0.5) must map to the rank whose box holds it, both in metres and in cells; the
// ranks own 1, 2, 1, 2 columns of 8 cells = 8, 16, 8, 16 cells (auto) and 12 each (forced).
TEST(DecompositionOwner, EveryCellCentreBelongsToTheBoxThatHoldsIt) {
  const auto grid = make_grid({6, 1, 8}, {3.0, 0.5, 4.0});
  const Decomposition automatic(grid, 4, 2);
  ASSERT_EQ(automatic.process_grid(), (std::array<int, 3>{4, 1, 1}));
  EXPECT_EQ(automatic.cuts(0), (std::vector<int>{0, 1, 3, 4, 6}));
  const Decomposition forced(grid, 4, 2, {2, 1, 2});
  const std::vector<std::vector<int>> expected_counts{{8, 16, 8, 16}, {12, 12, 12, 12}};
  int which = 0;
  for (const Decomposition* d : {&automatic, &forced}) {
    std::vector<int> count(4, 0);
    for (int i = 0; i < 6; ++i)
      for (int k = 0; k < 8; ++k) {
        const double x = (i + 0.5) * 0.5, y = 0.25, z = (k + 0.5) * 0.5;
        const int r = d->owner(x, y, z);
        ASSERT_GE(r, 0);
        ASSERT_LT(r, 4);
        ++count[static_cast<std::size_t>(r)];
        const auto b = d->box(r);
        EXPECT_LE(b.lo[0], x);
        EXPECT_LT(x, b.hi[0]);
        EXPECT_LE(b.lo[2], z);
        EXPECT_LT(z, b.hi[2]);
        EXPECT_LE(b.cell_lo[0], i);
        EXPECT_LT(i, b.cell_hi[0]);
        EXPECT_LE(b.cell_lo[2], k);
        EXPECT_LT(k, b.cell_hi[2]);
        EXPECT_EQ(d->distance2(r, x, y, z), 0.0);
      }
    EXPECT_EQ(count, expected_counts[static_cast<std::size_t>(which)]);
    ++which;
  }
}

// A point exactly on a cut plane belongs to the upper part: x = 0.5 m is cell 1, the first cell
// of rank 1 (cuts 0 1 3 4 6); x = 1.5 m is cell 3 -> rank 2; x = 2.0 m is cell 4 -> rank 3. Forced
// 2 x 1 x 2: x = 1.5 (cell 3, cx 1) and z = 2.0 (cell 4, cz 1) -> rank (1*1+0)*2+1 = 3.
TEST(DecompositionOwner, PointOnCutPlaneBelongsToUpperPart) {
  const auto grid = make_grid({6, 1, 8}, {3.0, 0.5, 4.0});
  const Decomposition d(grid, 4, 2);
  EXPECT_EQ(d.owner(0.5, 0.25, 1.0), 1);
  EXPECT_EQ(d.owner(1.5, 0.25, 1.0), 2);
  EXPECT_EQ(d.owner(2.0, 0.25, 1.0), 3);
  const Decomposition f(grid, 4, 2, {2, 1, 2});
  EXPECT_EQ(f.owner(1.5, 0.25, 2.0), 3);
  EXPECT_EQ(f.owner(1.5, 0.25, 1.999), 2);
  EXPECT_EQ(f.owner(1.499, 0.25, 2.0), 1);
}

// Outside the box the cell clamps into 0 .. cells-1, so the point goes to the edge rank:
// x < 0 -> rank 0, x >= 3 (hi itself included) -> rank 3, huge and infinite values too.
// NaN (a particle that blew up) goes to cell 0 without undefined behaviour.
TEST(DecompositionOwner, OutsidePointsClampAndNaNDoesNotCrash) {
  const Decomposition d(make_grid({6, 1, 8}, {3.0, 0.5, 4.0}), 4, 2);
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(d.owner(-1.0, 0.25, 1.0), 0);
  EXPECT_EQ(d.owner(3.0, 0.25, 1.0), 3);
  EXPECT_EQ(d.owner(100.0, -7.0, 99.0), 3);
  EXPECT_EQ(d.owner(1e300, 1e300, 1e300), 3);
  EXPECT_EQ(d.owner(-inf, 0.25, inf), 0);
  EXPECT_EQ(d.cell_of(0, -1e300), 0);
  EXPECT_EQ(d.cell_of(0, inf), 5);
  EXPECT_EQ(d.cell_of(2, 3.99), 7);
  EXPECT_EQ(d.cell_of(0, nan), 0);
  EXPECT_EQ(d.cell_of(2, nan), 0);
  EXPECT_EQ(d.owner(nan, nan, nan), 0);
}

// The first box starts at grid.lo and the last ends at grid.hi exactly, even where
// lo + cells * h rounds differently (lo 0.1, hi 0.7, 3 cells: h = 0.6/3 in floating point);
// neighbouring boxes share their face value.
TEST(DecompositionBox, OuterFacesAreTheGridFacesExactly) {
  DecompositionGrid g = make_grid({3, 1, 1}, {0.7, 1.0, 1.0});
  g.lo[0] = 0.1;
  const Decomposition d(g, 3, 2);
  ASSERT_EQ(d.process_grid(), (std::array<int, 3>{3, 1, 1}));
  EXPECT_EQ(d.box(0).lo[0], 0.1);
  EXPECT_EQ(d.box(2).hi[0], 0.7);
  EXPECT_EQ(d.box(0).hi[0], d.box(1).lo[0]);
  EXPECT_EQ(d.box(1).hi[0], d.box(2).lo[0]);
  EXPECT_EQ(d.box(1).cell_lo, (std::array<int, 3>{1, 0, 0}));
  EXPECT_EQ(d.box(1).cell_hi, (std::array<int, 3>{2, 1, 1}));
}

// 9 x 1 x 4 cells of 0.25 m (box 2.25 x 0.25 x 1 m), 3 ranks along x: boxes x [0, 0.75],
// [0.75, 1.5], [1.5, 2.25]. Periodic x: rank 0 and rank 2 touch through the periodic face, so
// for width 0.1 every rank has both others as neighbours. Without periodicity rank 0 only sees
// rank 1 until width reaches the gap 1.5 - 0.75 = 0.75 to rank 2.
TEST(DecompositionNeighbours, PeriodicFaceJoinsFirstAndLastRank) {
  const auto periodic = make_grid({9, 1, 4}, {2.25, 0.25, 1.0}, {true, false, false});
  const Decomposition d(periodic, 3, 2);
  ASSERT_EQ(d.process_grid(), (std::array<int, 3>{3, 1, 1}));
  EXPECT_EQ(d.neighbours(0, 0.1), (std::vector<int>{1, 2}));
  EXPECT_EQ(d.neighbours(1, 0.1), (std::vector<int>{0, 2}));
  EXPECT_EQ(d.neighbours(2, 0.1), (std::vector<int>{0, 1}));
  // lo = 0 makes the wrapped face exact (2.25 - 2.25 = 0): touching even at width 0.
  EXPECT_EQ(d.neighbours(0, 0.0), (std::vector<int>{1, 2}));

  const Decomposition open(make_grid({9, 1, 4}, {2.25, 0.25, 1.0}), 3, 2);
  EXPECT_EQ(open.neighbours(0, 0.1), (std::vector<int>{1}));
  EXPECT_EQ(open.neighbours(0, 0.7), (std::vector<int>{1}));
  EXPECT_EQ(open.neighbours(0, 0.75), (std::vector<int>{1, 2}));
  EXPECT_EQ(open.neighbours(2, 0.1), (std::vector<int>{1}));
}

// distance2 on the same grid: the point x = 2.2 (0.05 below hi) is 1.45 m from rank 0's box
// [0, 0.75] directly but 0.05 m through the periodic face: 0.05^2 = 0.0025 m^2 (open grid:
// 1.45^2 = 2.1025). A point outside along all axes, (0.5, 0.5, 1.5) to rank 1 (x [0.75, 1.5],
// y [0, 0.25], z [0, 1]): 0.25^2 + 0.25^2 + 0.5^2 = 0.375 (the images 2.75 and -1.75 are
// farther).
TEST(DecompositionNeighbours, Distance2UsesTheMinimumImage) {
  const auto periodic = make_grid({9, 1, 4}, {2.25, 0.25, 1.0}, {true, false, false});
  const Decomposition d(periodic, 3, 2);
  EXPECT_NEAR(d.distance2(0, 2.2, 0.1, 0.5), 0.0025, 1e-12);
  EXPECT_EQ(d.distance2(2, 2.2, 0.1, 0.5), 0.0);
  EXPECT_EQ(d.distance2(1, 0.5, 0.5, 1.5), 0.375);
  const Decomposition open(make_grid({9, 1, 4}, {2.25, 0.25, 1.0}), 3, 2);
  EXPECT_NEAR(open.distance2(0, 2.2, 0.1, 0.5), 2.1025, 1e-12);
}

// A 2 x 2 x 1 grid of boxes: the diagonal box touches along an edge, so at width 0 every other
// rank is a neighbour; the rank itself never is.
TEST(DecompositionNeighbours, DiagonalBoxesTouch) {
  const Decomposition d(make_grid({20, 20, 40}, {0.2, 0.2, 0.4}), 4, 2);
  ASSERT_EQ(d.process_grid(), (std::array<int, 3>{2, 2, 1}));
  EXPECT_EQ(d.neighbours(0, 0.0), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(d.neighbours(3, 0.0), (std::vector<int>{0, 1, 2}));
}

// Uniform cost: the cut nearest k*total/parts. 12 layers, 3 parts: targets 4, 8 -> 0 4 8 12.
// 10 layers, 4 parts: targets 2.5, 5, 7.5; the half-way ties go to the lower index -> 0 2 5 7 10,
// the even split floor(k*10/4).
TEST(DecompositionBalancedCuts, UniformCostGivesEvenSplit) {
  EXPECT_EQ(Decomposition::balanced_cuts(std::vector<double>(12, 1.0), 3, 1),
            (std::vector<int>{0, 4, 8, 12}));
  EXPECT_EQ(Decomposition::balanced_cuts(std::vector<double>(10, 1.0), 4, 1),
            (std::vector<int>{0, 2, 5, 7, 10}));
}

// 10 layers, cost 10 in layers 0-2 and 1 in 3-9: total 30 + 7 = 37, half 18.5. Cumulative
// costs at the boundaries 0, 10, 20, 30, 31, ..., 37: |20 - 18.5| = 1.5 is the nearest -> cut at
// 2 (parts of cost 20 and 17). Three parts: targets 12.33 (nearest 10 at 1) and 24.67 (20 at 2,
// 4.67 < 5.33) -> 0 1 2 10.
TEST(DecompositionBalancedCuts, BottomHeavyCostCutsNearHalfTheCumulativeCost) {
  std::vector<double> cost(10, 1.0);
  cost[0] = cost[1] = cost[2] = 10.0;
  EXPECT_EQ(Decomposition::balanced_cuts(cost, 2, 1), (std::vector<int>{0, 2, 10}));
  EXPECT_EQ(Decomposition::balanced_cuts(cost, 3, 1), (std::vector<int>{0, 1, 2, 10}));
}

// min_cells clamps the cuts: the bottom-heavy cut 2 becomes 3 with min_cells 3 (range 3 .. 7)
// and 5 with min_cells 5 (range 5 .. 5); 0 1 2 10 with min_cells 2 becomes 0 2 4 10. All cost in
// the top layer (10 layers, 3 parts, min_cells 2): targets 1/3 and 2/3 are nearest to the
// boundaries 0 (cumulative 0) and 10 (cumulative 1), clamped to 2 and, leaving room for the
// last part, 10 - 2 = 8 -> 0 2 8 10.
TEST(DecompositionBalancedCuts, MinCellsRespected) {
  std::vector<double> cost(10, 1.0);
  cost[0] = cost[1] = cost[2] = 10.0;
  EXPECT_EQ(Decomposition::balanced_cuts(cost, 2, 3), (std::vector<int>{0, 3, 10}));
  EXPECT_EQ(Decomposition::balanced_cuts(cost, 2, 5), (std::vector<int>{0, 5, 10}));
  EXPECT_EQ(Decomposition::balanced_cuts(cost, 3, 2), (std::vector<int>{0, 2, 4, 10}));
  std::vector<double> top(10, 0.0);
  top[9] = 1.0;
  EXPECT_EQ(Decomposition::balanced_cuts(top, 3, 2), (std::vector<int>{0, 2, 8, 10}));
}

// Ties between equally near boundaries go to the lower index: cost 1 0 0 1, 2 parts, target 1
// is met exactly at boundaries 1, 2 and 3 -> 1. Zero total cost: the even split floor(k*7/3) =
// 0 2 4 7. Too few layers (5 < 3 parts * 2) and negative costs throw.
TEST(DecompositionBalancedCuts, TiesZeroCostAndInvalidInput) {
  EXPECT_EQ(Decomposition::balanced_cuts({1.0, 0.0, 0.0, 1.0}, 2, 1), (std::vector<int>{0, 1, 4}));
  EXPECT_EQ(Decomposition::balanced_cuts(std::vector<double>(7, 0.0), 3, 1),
            (std::vector<int>{0, 2, 4, 7}));
  EXPECT_EQ(Decomposition::balanced_cuts({3.0, 1.0}, 1, 1), (std::vector<int>{0, 2}));
  expect_invalid([] { Decomposition::balanced_cuts(std::vector<double>(5, 1.0), 3, 2); },
                 {"5 layers", "3 parts", "2 cells"});
  expect_invalid([] { Decomposition::balanced_cuts({1.0, -1.0, 1.0}, 2, 1); }, {"layer 1"});
}

// set_cuts on 12 x 1 x 8 cells with 3 parts along x and min_cells 2: each invalid vector is
// refused with its reason; a valid one is stored and moves the boxes and owners (cell 9, centre
// 9.5 * 0.5 = 4.75 m, is in part 1 of 0 2 10 12).
TEST(DecompositionSetCuts, ValidationMessages) {
  Decomposition d(make_grid({12, 1, 8}, {6.0, 0.5, 4.0}), 3, 2, {3, 1, 1}, 2);
  expect_invalid([&] { d.set_cuts(0, {0, 4, 12}); }, {"axis 0", "needs 4 cuts", "got 3"});
  expect_invalid([&] { d.set_cuts(0, {1, 4, 8, 12}); }, {"first cut must be 0"});
  expect_invalid([&] { d.set_cuts(0, {0, 4, 8, 11}); }, {"last cut", "12"});
  expect_invalid([&] { d.set_cuts(0, {0, 6, 5, 12}); }, {"increase"});
  expect_invalid([&] { d.set_cuts(0, {0, 1, 8, 12}); }, {"part 0", "1 cells", "min_cells 2"});
  expect_invalid([&] { d.set_cuts(3, {0, 12}); }, {"axis"});
  EXPECT_EQ(d.cuts(0), (std::vector<int>{0, 4, 8, 12})); // unchanged by the refusals
  d.set_cuts(0, {0, 2, 10, 12});
  EXPECT_EQ(d.cuts(0), (std::vector<int>{0, 2, 10, 12}));
  EXPECT_EQ(d.box(1).cell_lo[0], 2);
  EXPECT_EQ(d.box(1).cell_hi[0], 10);
  EXPECT_EQ(d.box(1).lo[0], 1.0);
  EXPECT_EQ(d.box(1).hi[0], 5.0);
  EXPECT_EQ(d.owner(4.75, 0.25, 1.0), 1);
  EXPECT_EQ(d.owner(5.0, 0.25, 1.0), 2);
  // An uncut axis (1 part) needs only 0 and cells; min_cells does not apply to it.
  d.set_cuts(2, {0, 8});
  EXPECT_EQ(d.cuts(2), (std::vector<int>{0, 8}));
}

} // namespace
} // namespace fluidem
