#include "parallel/communicator.hpp"

#include <cstdlib>
// The C interface only (Open MPI would otherwise pull in its deprecated C++ bindings).
#define OMPI_SKIP_MPICXX 1
#include <mpi.h>
#include <stdexcept>

namespace fluidem {

namespace {

void finalize_mpi() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

} // namespace

bool Communicator::launched_by_mpirun() {
  // Open MPI's launcher sets these in every process it starts (PMIx: PMIX_RANK).
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr;
}

Communicator& Communicator::world() {
  static Communicator* w = [] {
    if (!launched_by_mpirun()) return new Communicator(0, 1, false);
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) {
      int provided = 0;
      // The ranks' OpenMP threads never call MPI (only the main thread does).
      check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
      std::atexit(finalize_mpi); // before hypre's finalisation is registered: runs after it
    }
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    return new Communicator(rank, size, true);
  }();
  return *w;
}

int Communicator::mpi_handle() const {
  return mpi_ ? static_cast<int>(MPI_Comm_c2f(MPI_COMM_WORLD)) : -1;
}

Communicator& Communicator::self() {
  static Communicator s(0, 1, false);
  return s;
}

std::int64_t Communicator::sum(std::int64_t v) const {
  if (!mpi_ || size_ == 1) return v;
  std::int64_t out = 0;
  check(MPI_Allreduce(&v, &out, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce");
  return out;
}

double Communicator::max(double v) const {
  if (!mpi_ || size_ == 1) return v;
  double out = 0.0;
  check(MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
  return out;
}

double Communicator::min(double v) const {
  if (!mpi_ || size_ == 1) return v;
  double out = 0.0;
  check(MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD), "MPI_Allreduce");
  return out;
}

bool Communicator::any(bool v) const {
  return sum(v ? 1 : 0) > 0;
}

void Communicator::sum_in_place(std::span<std::int64_t> v) const {
  if (!mpi_ || size_ == 1 || v.empty()) return;
  check(MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_INT64_T, MPI_SUM,
                      MPI_COMM_WORLD),
        "MPI_Allreduce");
}

std::vector<std::vector<char>> Communicator::exchange(const std::vector<int>& to,
                                                      const std::vector<std::vector<char>>& payload,
                                                      const std::vector<int>& from) const {
  std::vector<std::vector<char>> in(from.size());
  if (to.empty() && from.empty()) return in;
  if (!mpi_) throw std::logic_error("Communicator::exchange: one rank has no one to talk to");
  // Sizes first, then the bytes; tag 1 and 2, point to point between the neighbours only.
  std::vector<MPI_Request> req;
  req.reserve(2 * (to.size() + from.size()));
  std::vector<std::uint64_t> out_size(to.size()), in_size(from.size());
  for (std::size_t k = 0; k < from.size(); ++k) {
    req.emplace_back();
    check(MPI_Irecv(&in_size[k], 1, MPI_UINT64_T, from[k], 1, MPI_COMM_WORLD, &req.back()),
          "MPI_Irecv");
  }
  for (std::size_t k = 0; k < to.size(); ++k) {
    out_size[k] = payload[k].size();
    req.emplace_back();
    check(MPI_Isend(&out_size[k], 1, MPI_UINT64_T, to[k], 1, MPI_COMM_WORLD, &req.back()),
          "MPI_Isend");
  }
  check(MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE), "MPI_Waitall");
  req.clear();
  // Messages of up to 2^31 - 1 bytes (MPI's int counts): a rank's halo stays far below.
  for (std::size_t k = 0; k < from.size(); ++k) {
    in[k].resize(in_size[k]);
    req.emplace_back();
    check(MPI_Irecv(in[k].data(), static_cast<int>(in_size[k]), MPI_BYTE, from[k], 2,
                    MPI_COMM_WORLD, &req.back()),
          "MPI_Irecv");
  }
  for (std::size_t k = 0; k < to.size(); ++k) {
    req.emplace_back();
    check(MPI_Isend(payload[k].data(), static_cast<int>(payload[k].size()), MPI_BYTE, to[k], 2,
                    MPI_COMM_WORLD, &req.back()),
          "MPI_Isend");
  }
  check(MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE), "MPI_Waitall");
  return in;
}

std::vector<std::vector<char>> Communicator::gather(std::span<const char> bytes) const {
  if (!mpi_ || size_ == 1) return {std::vector<char>(bytes.begin(), bytes.end())};
  const std::uint64_t n = bytes.size();
  std::vector<std::uint64_t> sizes(root() ? static_cast<std::size_t>(size_) : 0);
  check(MPI_Gather(&n, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD),
        "MPI_Gather");
  std::vector<std::vector<char>> out;
  if (!root()) {
    check(MPI_Send(bytes.data(), static_cast<int>(n), MPI_BYTE, 0, 3, MPI_COMM_WORLD), "MPI_Send");
    return out;
  }
  out.resize(static_cast<std::size_t>(size_));
  out[0].assign(bytes.begin(), bytes.end());
  for (int r = 1; r < size_; ++r) {
    auto& b = out[static_cast<std::size_t>(r)];
    b.resize(sizes[static_cast<std::size_t>(r)]);
    check(MPI_Recv(b.data(), static_cast<int>(b.size()), MPI_BYTE, r, 3, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE),
          "MPI_Recv");
  }
  return out;
}

void Communicator::broadcast(std::vector<char>& bytes) const {
  if (!mpi_ || size_ == 1) return;
  std::uint64_t n = bytes.size();
  check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
  bytes.resize(n);
  check(MPI_Bcast(bytes.data(), static_cast<int>(n), MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
}

std::string Communicator::broadcast(const std::string& s) const {
  std::vector<char> b(s.begin(), s.end());
  broadcast(b);
  return {b.begin(), b.end()};
}

void Communicator::barrier() const {
  if (mpi_ && size_ > 1) check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier");
}

void Communicator::abort(int code) const {
  if (mpi_ && size_ > 1) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

} // namespace fluidem
