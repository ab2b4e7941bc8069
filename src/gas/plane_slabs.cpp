// The gas grid's z planes shared out by the ranks (plane_slabs.hpp).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include "gas/plane_slabs.hpp"
#include "gas/rank_dot.hpp"
#include <algorithm>
#include <mpi.h>
#include <stdexcept>

namespace fluidem::gas {

PlaneSlabs::PlaneSlabs(int comm, int rank, int size, int n, bool periodic_z, long plane_size)
    : comm_(comm), rank_(rank), size_(size), periodic_(periodic_z), plane_size_(plane_size) {
  if (size < 1 || rank < 0 || rank >= size || (comm == kThisProcessAlone && size > 1))
    throw std::logic_error("PlaneSlabs: needs size >= 1 and 0 <= rank < size");
  begin_.resize(static_cast<std::size_t>(size) + 1);
  for (int r = 0; r <= size; ++r)
    begin_[static_cast<std::size_t>(r)] =
        1 + static_cast<int>(static_cast<long>(n) * r / size); // as StructLinearSolver's parts
  lo_ = begin_[static_cast<std::size_t>(rank)];
  hi_ = begin_[static_cast<std::size_t>(rank) + 1] - 1;
  // The ghost planes go to the owners of planes 1 and n (ranks without planes before the first
  // owner keep none).
  held_ = begin_;
  for (int& b : held_)
    if (b == 1) b = 0;
  held_.back() = n + 2;
}

void exchange_halo_planes(int comm, int rank, const std::vector<int>& plane_begin, bool periodic_z,
                          long plane_size, std::vector<double>& a) {
  const auto r = static_cast<std::size_t>(rank);
  const int k_lo = plane_begin[r], k_hi = plane_begin[r + 1] - 1;
  if (k_hi < k_lo) return; // no planes
  const int lo = plane_begin.front(), hi = plane_begin.back() - 1;
  // The rank holding plane k (the last whose first plane is at or below k: empty ranks share
  // their first plane with the next one).
  const auto owner = [&](int k) {
    return static_cast<int>(std::upper_bound(plane_begin.begin(), plane_begin.end() - 1, k) -
                            plane_begin.begin()) -
           1;
  };
  const int below = k_lo > lo ? owner(k_lo - 1) : (periodic_z ? owner(hi) : -1);
  const int above = k_hi < hi ? owner(k_hi + 1) : (periodic_z ? owner(lo) : -1);
  const long sz = plane_size;
  if (below == rank || above == rank) { // alone on the planes: the periodic images are local
    std::copy_n(a.begin() + hi * sz, sz, a.begin() + (lo - 1) * sz);
    std::copy_n(a.begin() + lo * sz, sz, a.begin() + (hi + 1) * sz);
    return;
  }
  if (below < 0 && above < 0) return; // alone on the planes of a non-periodic z
  const MPI_Comm c = MPI_Comm_f2c(comm);
  const int count = static_cast<int>(sz);
  MPI_Request req[4];
  int m = 0;
  // Tag 0: a plane sent upwards (it lands below the receiver's planes), 1: downwards.
  if (below >= 0) {
    MPI_Irecv(a.data() + (k_lo - 1) * sz, count, MPI_DOUBLE, below, 0, c, &req[m++]);
    MPI_Isend(a.data() + k_lo * sz, count, MPI_DOUBLE, below, 1, c, &req[m++]);
  }
  if (above >= 0) {
    MPI_Irecv(a.data() + (k_hi + 1) * sz, count, MPI_DOUBLE, above, 1, c, &req[m++]);
    MPI_Isend(a.data() + k_hi * sz, count, MPI_DOUBLE, above, 0, c, &req[m++]);
  }
  MPI_Waitall(m, req, MPI_STATUSES_IGNORE);
}

void PlaneSlabs::exchange(std::vector<double>& a) const {
  exchange_halo_planes(comm_, rank_, begin_, periodic_, plane_size_, a);
}

void allgather_planes(int comm, const std::vector<int>& plane_begin, long per_plane,
                      double* first_plane) {
  const std::size_t size = plane_begin.size() - 1;
  if (size == 1) return;
  std::vector<int> counts(size), displs(size);
  for (std::size_t r = 0; r < size; ++r) {
    counts[r] = static_cast<int>((plane_begin[r + 1] - plane_begin[r]) * per_plane);
    displs[r] = static_cast<int>((plane_begin[r] - plane_begin.front()) * per_plane);
  }
  MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, first_plane, counts.data(), displs.data(),
                 MPI_DOUBLE, MPI_Comm_f2c(comm));
}

void PlaneSlabs::gather(double* a, long per_plane) const {
  allgather_planes(comm_, held_, per_plane, a);
}

double PlaneSlabs::max(double v) const {
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, MPI_Comm_f2c(comm_));
  return v;
}

} // namespace fluidem::gas
