// Helpers of the MPI tests that compare results bit for bit across ranks: the world's rank and
// size, a hash of an array's bits (FNV-1a over each double's 64 bits), and whether every rank
// holds the same hash.
#pragma once
#include <cstdint>
#include <cstring>
#include <mpi.h>
#include <vector>

namespace fluidem::test {

inline int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

inline int world_size() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

inline std::uint64_t bits_hash(const std::vector<double>& v) {
  std::uint64_t h = 1469598103934665603ull;
  for (const double d : v) {
    std::uint64_t u = 0;
    std::memcpy(&u, &d, sizeof u);
    h = (h ^ u) * 1099511628211ull;
  }
  return h;
}

/// Collective: true when every rank passed the same h.
inline bool same_on_every_rank(std::uint64_t h) {
  std::vector<std::uint64_t> all(static_cast<std::size_t>(world_size()));
  MPI_Allgather(&h, 1, MPI_UINT64_T, all.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
  for (const auto a : all)
    if (a != h) return false;
  return true;
}

} // namespace fluidem::test
