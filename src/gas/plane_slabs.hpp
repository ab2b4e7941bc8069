// The gas grid's z planes shared out by the ranks of a distributed run (docs/parallel.md, "The
// gas on several ranks"): rank r owns the contiguous interior cell planes lo .. hi,
// lo = 1 + r n / P (as StructLinearSolver's parts; with more ranks than planes some own none),
// and the owners of planes 1 and n also the ghost planes 0 and n + 1. A cell-centred or face array
// in the padded layout of GasGrid is held whole by every rank, but between the exchanges below only
// the own planes and the halo planes lo - 1 and hi + 1 are current: the face planes of every
// velocity component are indexed like the cell planes (face k is the high face of cell k), so one
// split serves all arrays.
#pragma once
#include <vector>

namespace fluidem::gas {

/// Collective over the ranks of `comm` that hold z planes: rank r holds the contiguous planes
/// plane_begin[r] .. plane_begin[r + 1] - 1 (none when equal), the planes plane_begin.front() ..
/// plane_begin.back() - 1 in rank order. This rank receives the planes beside its own from the
/// ranks that hold them (along a periodic z, across the period: the images of the last and first
/// planes; local copies when it holds all planes). Ranks without planes return at once.
void exchange_halo_planes(int comm, int rank, const std::vector<int>& plane_begin, bool periodic_z,
                          long plane_size, std::vector<double>& a);

/// Collective over the ranks of `comm` (plane_begin.size() - 1 of them; one: nothing to do):
/// every rank receives the other ranks' planes plane_begin[r] .. plane_begin[r + 1] - 1 of an
/// array whose planes hold `per_plane` entries each, from `first_plane` (plane_begin.front()) on.
void allgather_planes(int comm, const std::vector<int>& plane_begin, long per_plane,
                      double* first_plane);

class PlaneSlabs {
public:
  /// No planes yet: assign a split made by the constructor below before use.
  PlaneSlabs() = default;
  /// The n interior planes of `plane_size` entries each split over the `size` ranks of `comm`
  /// (its MPI_Comm_c2f handle, or kThisProcessAlone with size 1).
  PlaneSlabs(int comm, int rank, int size, int n, bool periodic_z, long plane_size);

  int lo() const { return lo_; }
  int hi() const { return hi_; }
  /// The own planes with the ghost plane at each end of the grid (0 .. n + 1 on one rank;
  /// last() < first() when the rank owns none).
  int first() const { return held_[static_cast<std::size_t>(rank_)]; }
  int last() const { return held_[static_cast<std::size_t>(rank_) + 1] - 1; }
  /// The first interior plane of each rank and n + 1 (size + 1 entries).
  const std::vector<int>& plane_begin() const { return begin_; }

  /// Collective: the halo planes lo - 1 and hi + 1 from the ranks that own them (along a
  /// periodic z, across the period: the images of planes n and 1 in planes 0 and n + 1, local
  /// copies on one rank). Whole padded planes, so their periodic x and y images come along.
  void exchange(std::vector<double>& a) const;
  /// Collective: every rank receives the other ranks' planes first() .. last() of `a`, whose
  /// planes hold `per_plane` entries each (the grid's plane size for a field, or a few numbers
  /// per plane).
  void gather(double* a, long per_plane) const;
  /// Collective: the largest of the ranks' values.
  double max(double v) const;

private:
  int comm_ = -1, rank_ = 0, size_ = 1;
  bool periodic_ = false;
  long plane_size_ = 0;
  int lo_ = 1, hi_ = 0;
  std::vector<int> begin_;
  std::vector<int> held_; ///< begin_ with the ghost planes 0 and n + 1 given to their owners
};

} // namespace fluidem::gas
