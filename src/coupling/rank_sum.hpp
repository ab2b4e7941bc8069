// Sums over the particles into gas cells that do not depend on how the particles are split over
// MPI ranks, nor on their order (docs/parallel.md, "The gas on several ranks").
//
// In a distributed run each rank holds its own particles and a copy of the gas. Every sum of
// per-particle parts into a grid field (porosity, the drag coefficient and its velocity term,
// Model B's buoyancy source, the cell averages of schemes 1 and 2) is taken in fixed point:
// each part v is rounded to the integer llround(v 2^s), the integers of a cell are added (exact,
// in any order), the ranks' integers are summed exactly, and the cell's value is the integer
// times 2^-s. The scale 2^s is the same on every rank: the largest power of two with
// N max|part| 2^s < 2^62, N the particles of all ranks and max|part| a per-particle bound taken
// over all ranks (a maximum, exact in any order), so no cell sum can overflow. The rounding is
// below N max|part| 2^-62 per part (2e-14 of the largest part for 10^5 particles): the gas sees
// the same bits on every rank count, at a cost far below the physics' own uncertainty.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace fluidem::coupling {

/// The reductions over the ranks that fixed-point deposition needs (parallel::Communicator's,
/// wrapped; one process: the identities).
struct RankSum {
  std::function<double(double)> max;                       ///< over the ranks
  std::function<std::int64_t(std::int64_t)> sum;           ///< over the ranks
  std::function<void(std::span<std::int64_t>)> sum_fields; ///< element-wise, in place
};

/// Several grid fields summed in fixed point over the particles of all ranks.
class FixedPointSum {
public:
  /// Zeroes `max_part.size()` fields of `size` entries each. max_part[f]: a bound on |part| of
  /// field f over this rank's `parts` contributors (particles); both are combined over the
  /// ranks (collective). InstabilityError, on every rank alike, if a bound is not finite.
  void start(std::size_t size, std::span<const double> max_part, std::int64_t particles,
             const RankSum& ranks);
  /// Adds one part (|v| <= the field's max_part) to entry q of field f.
  void add(std::size_t f, std::size_t q, double v) {
    acc_[f * size_ + q] += static_cast<std::int64_t>(std::llround(v * scale_[f]));
  }
  /// Sums every entry over the ranks (collective; only the index range that holds a nonzero
  /// entry on some rank travels).
  void reduce(const RankSum& ranks);
  /// Field f as doubles: out[q] = sum_q 2^-s (out resized to size).
  void result(std::size_t f, std::vector<double>& out) const;
  /// The value one unit of field f stands for, 2^-s.
  double resolution(std::size_t f) const { return 1.0 / scale_[f]; }
  /// The integers' bytes summed over the ranks by reduce() so far, and its reductions (each
  /// reduce() also reduces the range: two more, of one number each).
  double bytes_reduced() const { return bytes_reduced_; }
  long reductions() const { return reductions_; }

private:
  std::size_t size_ = 0;
  std::vector<double> scale_;
  std::vector<std::int64_t> acc_;
  std::vector<std::int64_t> buffer_;
  double bytes_reduced_ = 0.0;
  long reductions_ = 0;
};

} // namespace fluidem::coupling
