// The map of ranks over a grid of cells (the gas cells of a coupled run): each axis is cut at
// cell boundaries into the process grid's parts; a particle belongs to the rank whose cells hold
// its centre. Pure geometry, no MPI (docs/parallel.md).
#pragma once
#include <array>
#include <vector>

namespace fluidem {

/// The index space a Decomposition cuts: cells per axis over the box [lo, hi).
struct DecompositionGrid {
  std::array<int, 3> cells{1, 1, 1};
  std::array<double, 3> lo{}, hi{};
  std::array<bool, 3> periodic{};
};

class Decomposition {
public:
  /// Boxes of cells of at least min_cells per axis (an axis with fewer cells than that is not
  /// cut). ranks >= 1. vertical_axis: the axis of gravity, cut last (columns first: a tall bed
  /// is cut into columns). forced {px, py, pz} (product == ranks), or {0, 0, 0} to choose.
  /// Throws std::invalid_argument (with the reason) when no process grid fits.
  Decomposition(const DecompositionGrid& grid, int ranks, int vertical_axis,
                std::array<int, 3> forced = {0, 0, 0}, int min_cells = 1);

  int ranks() const;
  const DecompositionGrid& grid() const { return grid_; }
  std::array<int, 3> process_grid() const { return parts_; }
  /// The cut cell indices along axis a: parts+1 values, 0 first, cells[a] last, increasing.
  const std::vector<int>& cuts(int axis) const { return cuts_[axis]; }
  /// Move the cuts of an axis (load balancing); std::invalid_argument if they are not parts+1
  /// increasing indices from 0 to cells with parts of at least min_cells.
  void set_cuts(int axis, std::vector<int> cuts);

  /// Rank of process-grid coordinates (x slowest), and back.
  int rank_of(std::array<int, 3> coords) const;
  std::array<int, 3> coords_of(int rank) const;
  /// The cell along axis a that holds coordinate v (clamped into 0 .. cells-1).
  int cell_of(int axis, double v) const;
  /// The rank whose cells hold the point.
  int owner(double x, double y, double z) const;

  struct Box {
    std::array<int, 3> cell_lo{}, cell_hi{}; ///< cells [cell_lo, cell_hi)
    std::array<double, 3> lo{}, hi{};        ///< m
  };
  Box box(int rank) const;
  /// Squared distance (min image on periodic axes) from the point to the rank's box, m^2.
  double distance2(int rank, double x, double y, double z) const;
  /// The other ranks whose box lies within `width` of the rank's box (min image on periodic
  /// axes), ascending.
  std::vector<int> neighbours(int rank, double width) const;

  /// Cuts of `parts` intervals of a line of cells with the given cost per cell layer: each
  /// interval's cost as near total/parts as the layers allow, at least min_cells each.
  static std::vector<int> balanced_cuts(const std::vector<double>& layer_cost, int parts,
                                        int min_cells);

private:
  DecompositionGrid grid_;
  std::array<int, 3> parts_{1, 1, 1};
  std::array<std::vector<int>, 3> cuts_;
  int min_cells_ = 1;
};

} // namespace fluidem
