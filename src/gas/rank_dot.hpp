// Inner products over the ranks whose bits do not depend on how the entries are split between
// them (docs/parallel.md, "The gas on several ranks"): each product a_i b_i is rounded to a whole
// multiple of 2^-s, the integers are added exactly (in any order, then over the ranks), and the
// sum is converted back. The scale is the same on every rank: the largest 2^s with
// max|a_i b_i| 2^s < 2^min(60 - bits(N), 51) (N the entries of all ranks, bits(N) its binary
// digits, the maximum taken over all ranks), so no sum of N products overflows, and the rounding
// is at most 2^-s / 2 <= 2 max(N 2^-60, 2^-52) max|a_i b_i| per product (2e-13 of the largest
// product for 10^5 entries), N times that over the sum, plus one rounding of the result — the
// scheme of coupling/rank_sum.hpp for one number.
#pragma once
#include <cstddef>

namespace fluidem::gas {

/// The ranks a solve is shared by: an MPI communicator (its Fortran handle, MPI_Comm_c2f, so
/// that no header needs mpi.h), or kThisProcessAlone (no MPI call is made).
constexpr int kThisProcessAlone = -1;

/// sum_i a_i b_i over the n entries of this rank and those of the other ranks of `comm`
/// (collective), total_entries = N over all ranks. NaN if a product is not finite on any rank.
double rank_dot(int comm, long total_entries, const double* a, const double* b, std::size_t n);

} // namespace fluidem::gas
