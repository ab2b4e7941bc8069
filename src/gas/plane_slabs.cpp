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
    : comm_(comm), rank_(rank), size_(size), n_(n), periodic_(periodic_z), plane_size_(plane_size) {
  if (size < 1 || size > n || rank < 0 || rank >= size || (comm == kThisProcessAlone && size > 1))
    throw std::logic_error("PlaneSlabs: needs 1 <= size <= planes and 0 <= rank < size");
  begin_.resize(static_cast<std::size_t>(size) + 1);
  for (int r = 0; r <= size; ++r)
    begin_[static_cast<std::size_t>(r)] =
        1 + static_cast<int>(static_cast<long>(n) * r / size); // as StructLinearSolver's parts
  lo_ = begin_[static_cast<std::size_t>(rank)];
  hi_ = begin_[static_cast<std::size_t>(rank) + 1] - 1;
}

void PlaneSlabs::exchange(std::vector<double>& a) const {
  const long sz = plane_size_;
  if (size_ == 1) { // alone: the periodic images are local copies
    if (periodic_) {
      std::copy_n(a.begin() + n_ * sz, sz, a.begin());
      std::copy_n(a.begin() + sz, sz, a.begin() + (n_ + 1) * sz);
    }
    return;
  }
  const int below = rank_ > 0 ? rank_ - 1 : (periodic_ ? size_ - 1 : -1);
  const int above = rank_ + 1 < size_ ? rank_ + 1 : (periodic_ ? 0 : -1);
  const MPI_Comm c = MPI_Comm_f2c(comm_);
  const int count = static_cast<int>(sz);
  MPI_Request req[4];
  int m = 0;
  // Tag 0: a plane sent upwards (it lands below the receiver's planes), 1: downwards.
  if (below >= 0) {
    MPI_Irecv(a.data() + (lo_ - 1) * sz, count, MPI_DOUBLE, below, 0, c, &req[m++]);
    MPI_Isend(a.data() + lo_ * sz, count, MPI_DOUBLE, below, 1, c, &req[m++]);
  }
  if (above >= 0) {
    MPI_Irecv(a.data() + (hi_ + 1) * sz, count, MPI_DOUBLE, above, 1, c, &req[m++]);
    MPI_Isend(a.data() + hi_ * sz, count, MPI_DOUBLE, above, 0, c, &req[m++]);
  }
  MPI_Waitall(m, req, MPI_STATUSES_IGNORE);
}

void PlaneSlabs::gather(double* a, long per_plane) const {
  if (size_ == 1) return;
  std::vector<int> counts(static_cast<std::size_t>(size_)), displs(counts.size());
  for (int r = 0; r < size_; ++r) {
    const int f = r == 0 ? 0 : begin_[static_cast<std::size_t>(r)];
    const int l = r == size_ - 1 ? n_ + 1 : begin_[static_cast<std::size_t>(r) + 1] - 1;
    counts[static_cast<std::size_t>(r)] = static_cast<int>((l - f + 1) * per_plane);
    displs[static_cast<std::size_t>(r)] = static_cast<int>(f * per_plane);
  }
  MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, a, counts.data(), displs.data(), MPI_DOUBLE,
                 MPI_Comm_f2c(comm_));
}

double PlaneSlabs::max(double v) const {
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, MPI_Comm_f2c(comm_));
  return v;
}

} // namespace fluidem::gas
