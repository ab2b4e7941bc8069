// Bubbles of a gas-fluidised bed, found in the porosity field of the gas cells and followed from
// frame to frame.
//
// A bubble is a connected region (cells sharing a face) of cells whose porosity exceeds a
// threshold (0.8 by default), enclosed by the bed: the region must not reach the top layer of
// cells (gravity along -z). The dilute cells connected to the top layer are the freeboard (with
// the dilute surface of an expanded bed and any bubble that is erupting through the surface),
// and the bed is every other cell. A void that touches a side wall or the distributor (the jet
// of [Hoomans96 §5.3.1]) is a bubble. The bubble fraction is the bubbles' volume over the
// bed's.
//
// The size of a bubble is its volume, or, when the grid is one cell across y (2-D runs and the
// pseudo-2-D beds of [Deen07 §6.1]), its area in the x-z plane; its equivalent diameter is that
// of the circle of the same area, sqrt(4 A / pi) (the measure of [Deen07 Fig. 8] and of the
// photographs of pseudo-2-D beds), or of the sphere of the same volume, (6 V / pi)^(1/3).
//
// Following bubbles: a bubble of frame k continues the bubble of frame k - 1 it overlaps most
// (in cells); when several of frame k overlap the same one most, the one with the largest
// overlap continues it (ties: the lower index) and the others are new (a split), so a merger
// continues its largest contributor. A bubble that continues one takes its id and its rise
// velocity is the change of its centroid's height over the time between the frames.
#pragma once
#include <array>
#include <cstddef>
#include <vector>

namespace fluidem {

/// The gas cells of a field: cells per axis, lower corner and cell sizes (m). Arrays are laid
/// out [z][y][x] (x fastest), as fields.h5 stores them.
struct CellGrid {
  std::array<int, 3> cells{1, 1, 1};
  std::array<double, 3> lo{0.0, 0.0, 0.0};
  std::array<double, 3> spacing{1.0, 1.0, 1.0};
  std::size_t size() const {
    return static_cast<std::size_t>(cells[0]) * static_cast<std::size_t>(cells[1]) *
           static_cast<std::size_t>(cells[2]);
  }
  /// True when the size of a bubble is its area in the x-z plane (one cell across y).
  bool planar() const { return cells[1] == 1; }
};

struct Bubble {
  std::size_t cells = 0;            ///< cells in the region
  double size = 0.0;                ///< m^2 (planar grid) or m^3
  double equivalent_diameter = 0.0; ///< m
  std::array<double, 3> centroid{}; ///< m, mean of the cell centres
  std::array<double, 2> z_extent{}; ///< m, lowest and highest cell face along z
  bool touches_wall = false;        ///< reaches a side face or the bottom of the domain
};

struct BubbleFrame {
  std::vector<Bubble> bubbles; ///< in the order of their lowest cell index
  std::vector<int> label;      ///< per cell: bubble index, -1 bed (dense), -2 freeboard
  double bed_volume = 0.0;     ///< m^3 of the cells that are not freeboard
  double bubble_volume = 0.0;  ///< m^3 of the bubbles' cells
  double bubble_fraction() const { return bed_volume > 0.0 ? bubble_volume / bed_volume : 0.0; }
};

/// The bubbles of one porosity field `eps` (grid.size() values, [z][y][x]), cells with
/// eps > threshold being dilute. std::invalid_argument for a size mismatch, a grid without
/// cells or a non-positive spacing.
BubbleFrame find_bubbles(const CellGrid& grid, const std::vector<double>& eps,
                         double threshold = 0.8);

/// For each bubble of `next`, the index of the bubble of `prev` it continues, or -1 (a new
/// bubble): the rule in the header comment. Both frames on the same grid.
std::vector<int> continue_bubbles(const BubbleFrame& prev, const BubbleFrame& next);

} // namespace fluidem
