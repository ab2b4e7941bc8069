// Particles binned in the cells of a uniform grid over the box (cell lists [Deen07 §4]), for the
// neighbour lists of both engines: the particles of a cell in ascending index order, and a walk
// over the particles of the (up to 27) cells around a particle's cell (cell_walk.hpp).
//
// The work and memory of a binning are bounded by the particle count, not by the box: a grid of
// at most kDenseCellsPerParticle cells per particle (a bed) is stored as an array over all its
// cells (a counting sort; the cheapest walk); a larger one (a few particles in a big box: one
// 100 um sphere in a 4 cm box makes 3.7e7 cells of 0.12 mm) keeps only its occupied cells, found
// through an open-addressing hash table of their flat indices (at most 2^60 cells, 2^20 per
// axis). Both give the same cells, in the same order, with the same particles: the lists built on
// them do not depend on which one a binning used.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "neighbour/box_geometry.hpp"
#include "neighbour/cell_walk.hpp"

namespace fluidem {

class CellGrid {
public:
  /// Grids of at most this many cells per particle (plus kDenseCellsMin) are stored densely.
  static constexpr std::size_t kDenseCellsPerParticle = 8;
  static constexpr std::size_t kDenseCellsMin = 4096;
  /// The most cells per axis (cell coordinates fit in 20 bits).
  static constexpr int kMaxCellsPerAxis = 1 << 20;

  /// Bins the n particles at (x[i], y[i], z[i]) in cells of side at least cell_size: floor(L /
  /// cell_size) cells on an axis of length L (at least 1, at most kMaxCellsPerAxis); positions
  /// are wrapped into the box on periodic axes and clamped to the edge cells on closed ones.
  /// threaded: the per-particle cell indices are computed on the OpenMP threads.
  void bin(const BoxGeometry& box, double cell_size, const double* x, const double* y,
           const double* z, std::size_t n, bool threaded);

  const std::array<int, 3>& cells_per_axis() const { return ncell_; }
  /// Whether the last binning stored all cells (else only the occupied ones, hashed).
  bool dense() const { return dense_; }
  /// Cells the last binning stored: all of them (dense) or the occupied ones.
  std::size_t stored_cells() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }
  /// The coordinate of particle i's cell along axis a.
  std::uint32_t coordinate(std::size_t i, int a) const {
    return dense_ ? coordinate_in<std::uint32_t>(cell_[i], a)
                  : coordinate_in<std::uint64_t>(cell_[i], a);
  }

  /// Calls visit(j) for every particle j (i included) of the cells around particle i's cell:
  /// cell by cell in for_each_cell_around's order, ascending index within a cell.
  template <class Visit>
  [[gnu::always_inline]] void for_each_near(std::size_t i, const std::array<bool, 3>& periodic,
                                            Visit&& visit) const {
    const std::uint32_t* const start = cell_start_.data();
    const std::uint32_t* const members = cell_particles_.data();
    if (dense_) {
      for_each_cell_around(static_cast<std::uint32_t>(cell_[i]), ncell_, periodic,
                           [&](std::uint32_t cell) {
                             for (std::uint32_t k = start[cell]; k < start[cell + 1]; ++k)
                               visit(members[k]);
                           });
    } else {
      for_each_cell_around(cell_[i], ncell_, periodic, [&](std::uint64_t cell) {
        const std::uint32_t slot = find(cell);
        if (slot == kNone) return;
        for (std::uint32_t k = start[slot]; k < start[slot + 1]; ++k) visit(members[k]);
      });
    }
  }

  /// for_each_near without the particles of index i or below: each pair (i, j > i) once. A
  /// cell's particles are in ascending index order, so its run at or below i is passed over
  /// with integer comparisons only.
  template <class Visit>
  [[gnu::always_inline]] void
  for_each_near_above(std::size_t i, const std::array<bool, 3>& periodic, Visit&& visit) const {
    const std::uint32_t* const start = cell_start_.data();
    const std::uint32_t* const members = cell_particles_.data();
    const auto after = [&](std::uint32_t k0, std::uint32_t k1) {
      std::uint32_t k = k0;
      while (k < k1 && members[k] <= i) ++k;
      for (; k < k1; ++k) visit(members[k]);
    };
    if (dense_) {
      for_each_cell_around(static_cast<std::uint32_t>(cell_[i]), ncell_, periodic,
                           [&](std::uint32_t cell) { after(start[cell], start[cell + 1]); });
    } else {
      for_each_cell_around(cell_[i], ncell_, periodic, [&](std::uint64_t cell) {
        const std::uint32_t slot = find(cell);
        if (slot != kNone) after(start[slot], start[slot + 1]);
      });
    }
  }

  /// Frees the arrays (a binning allocates them again).
  void release();
  std::size_t bytes() const;

private:
  /// (A dense grid's indices fit in 32 bits, whose divisions are the cheaper.)
  template <class Index>
  std::uint32_t coordinate_in(std::uint64_t cell, int a) const {
    const auto c = static_cast<Index>(cell), nx = static_cast<Index>(nx_),
               ny = static_cast<Index>(ny_);
    if (a == 0) return static_cast<std::uint32_t>(c % nx);
    if (a == 1) return static_cast<std::uint32_t>((c / nx) % ny);
    return static_cast<std::uint32_t>(c / (nx * ny));
  }
  static constexpr std::uint32_t kNone = ~0u;
  static constexpr std::uint64_t kEmptyKey = ~std::uint64_t{0};
  std::uint64_t hash_slot(std::uint64_t key) const {
    return (key * 0x9E3779B97F4A7C15ULL) >> hash_shift_; // Fibonacci hashing
  }
  /// The occupied cell number of flat cell index `key`, kNone if the cell is empty.
  std::uint32_t find(std::uint64_t key) const {
    for (std::uint64_t s = hash_slot(key);; s = (s + 1) & hash_mask_) {
      const std::uint64_t k = hash_key_[s];
      if (k == key) return hash_cell_[s];
      if (k == kEmptyKey) return kNone;
    }
  }

  std::array<int, 3> ncell_{1, 1, 1};
  std::uint64_t nx_ = 1, ny_ = 1;
  bool dense_ = true;
  std::vector<std::uint64_t> cell_; ///< each particle's flat cell index
  /// The particles of stored cell c: cell_particles_[cell_start_[c] .. cell_start_[c+1]); stored
  /// cell c is flat cell c (dense) or the occupied cell numbered c (hashed, by first occupant).
  std::vector<std::uint32_t> cell_start_, cell_particles_;
  // Hashed cells: open addressing with linear probing, a power-of-two table at most half full.
  std::vector<std::uint64_t> hash_key_;
  std::vector<std::uint32_t> hash_cell_;
  std::uint64_t hash_mask_ = 0;
  int hash_shift_ = 64;
  std::vector<std::uint32_t> scratch_; ///< hashed grids: each particle's occupied cell
};

} // namespace fluidem
