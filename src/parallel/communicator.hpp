// The ranks of a run and what they say to each other: a thin layer over MPI (Open MPI, started
// with mpirun). A process not started by mpirun is one rank and never starts MPI (a singleton
// MPI_Init costs 0.35 s); the code paths above this layer are the same for one rank or many.
// Every call that names no rank is collective: all ranks make it, in the same order.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace fluidem {

class Communicator {
public:
  /// The ranks started together by mpirun (MPI initialised on first use), or this process
  /// alone. The same object for the whole process.
  static Communicator& world();
  /// One rank, without MPI (tests of the serial path inside an MPI run use it too).
  static Communicator& self();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  /// Exact reductions (integers; max and min of doubles do not depend on the order).
  std::int64_t sum(std::int64_t v) const;
  double max(double v) const;
  double min(double v) const;
  bool any(bool v) const;
  /// Element-wise exact sum of integer arrays over the ranks (fixed-point deposition).
  void sum_in_place(std::span<std::int64_t> v) const;

  /// Sends payload[k] to rank to[k] (each destination at most once, never this rank) and
  /// receives from each rank in `from` its payload, returned in the order of `from`. Both lists
  /// must agree between the ranks: rank a lists b in `to` exactly when b lists a in `from`.
  std::vector<std::vector<char>> exchange(const std::vector<int>& to,
                                          const std::vector<std::vector<char>>& payload,
                                          const std::vector<int>& from) const;
  /// Every rank's bytes, in rank order, at the root (other ranks get an empty list).
  std::vector<std::vector<char>> gather(std::span<const char> bytes) const;
  /// The root's bytes on every rank.
  void broadcast(std::vector<char>& bytes) const;
  /// The root's string on every rank (a message all ranks print or throw alike).
  std::string broadcast(const std::string& s) const;
  void barrier() const;
  /// Ends every rank with this exit code (MPI_Abort; exit() for one rank without MPI).
  [[noreturn]] void abort(int code) const;

  /// The communicator's Fortran handle (MPI_Comm_c2f, for libraries that take an MPI_Comm:
  /// hypre), or -1 for a process without MPI.
  int mpi_handle() const;

  /// Whether this process was started by mpirun (then MPI is used, even on one rank).
  static bool launched_by_mpirun();

private:
  Communicator(int rank, int size, bool mpi) : rank_(rank), size_(size), mpi_(mpi) {}
  int rank_ = 0, size_ = 1;
  bool mpi_ = false;
};

} // namespace fluidem
