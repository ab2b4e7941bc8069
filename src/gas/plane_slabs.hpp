// The gas grid's z planes shared out by the ranks of a distributed run (docs/parallel.md, "The
// gas on several ranks"): rank r owns the contiguous interior cell planes lo .. hi,
// lo = 1 + r n / P (P <= n ranks, so none is empty), and the first and last ranks also the
// ghost planes 0 and n + 1. A cell-centred or face array in the padded layout of GasGrid is held
// whole by every rank, but between the exchanges below only the own planes and the halo planes
// lo - 1 and hi + 1 are current: the face planes of every velocity component are indexed like
// the cell planes (face k is the high face of cell k), so one split serves all arrays.
#pragma once
#include <vector>

namespace fluidem::gas {

/// Collective over the `active` ranks of `comm` whose contiguous slabs of z planes cover lo .. hi
/// in rank order (ranks >= active hold none and return): this rank (planes k_lo .. k_hi) receives
/// planes k_lo - 1 and k_hi + 1 from its neighbours (along a periodic z, across the period: the
/// images of planes hi and lo in lo - 1 and hi + 1; local copies when active is 1).
void exchange_halo_planes(int comm, int rank, int active, int k_lo, int k_hi, int lo, int hi,
                          bool periodic_z, long plane_size, std::vector<double>& a);

class PlaneSlabs {
public:
  /// One process holding every plane (no MPI call is made).
  PlaneSlabs() = default;
  /// The n interior planes of `plane_size` entries each split over the `size` ranks of `comm`
  /// (its MPI_Comm_c2f handle, or kThisProcessAlone with size 1); size <= n.
  PlaneSlabs(int comm, int rank, int size, int n, bool periodic_z, long plane_size);

  int lo() const { return lo_; }
  int hi() const { return hi_; }
  /// The own planes with the ghost plane at each end of the grid (0 .. n + 1 on one rank).
  int first() const { return rank_ == 0 ? 0 : lo_; }
  int last() const { return rank_ == size_ - 1 ? n_ + 1 : hi_; }
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
  int comm_ = -1, rank_ = 0, size_ = 1, n_ = 0;
  bool periodic_ = false;
  long plane_size_ = 0;
  int lo_ = 1, hi_ = 0;
  std::vector<int> begin_;
};

} // namespace fluidem::gas
