#include "coupling/rank_sum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"

namespace fluidem::coupling {

void FixedPointSum::start(std::size_t size, std::span<const double> max_part,
                          std::int64_t particles, const RankSum& ranks) {
  size_ = size;
  scale_.assign(max_part.size(), 1.0);
  acc_.assign(max_part.size() * size, 0);
  const double n = static_cast<double>(ranks.sum(particles));
  for (std::size_t f = 0; f < max_part.size(); ++f) {
    // A NaN bound is infinite, so that the maximum over the ranks sees it in any order.
    const double mine =
        std::isnan(max_part[f]) ? std::numeric_limits<double>::infinity() : std::abs(max_part[f]);
    const double bound = ranks.max(mine) * n;
    if (!std::isfinite(bound))
      throw InstabilityError("the particle-gas exchange has a part that is not finite (a "
                             "particle's velocity, size or drag is NaN or infinite)");
    if (bound > 0.0) {
      int e = 0;
      std::frexp(bound, &e); // bound < 2^e
      scale_[f] = std::ldexp(1.0, 62 - e);
    }
  }
}

void FixedPointSum::reduce(const RankSum& ranks) {
  // The range of entries (over all fields' indices) that holds a nonzero part on some rank.
  long lo = static_cast<long>(size_), hi = -1;
  for (std::size_t f = 0; f < scale_.size(); ++f)
    for (std::size_t q = 0; q < size_; ++q)
      if (acc_[f * size_ + q] != 0) {
        lo = std::min(lo, static_cast<long>(q));
        hi = std::max(hi, static_cast<long>(q));
      }
  lo = -static_cast<long>(ranks.max(-static_cast<double>(lo)));
  hi = static_cast<long>(ranks.max(static_cast<double>(hi)));
  if (hi < lo) return; // no part anywhere
  const auto width = static_cast<std::size_t>(hi - lo + 1);
  buffer_.resize(width * scale_.size());
  for (std::size_t f = 0; f < scale_.size(); ++f)
    std::copy_n(acc_.begin() + static_cast<long>(f * size_) + lo, width,
                buffer_.begin() + static_cast<long>(f * width));
  ranks.sum_fields(buffer_);
  bytes_reduced_ += static_cast<double>(buffer_.size() * sizeof(std::int64_t));
  ++reductions_;
  for (std::size_t f = 0; f < scale_.size(); ++f)
    std::copy_n(buffer_.begin() + static_cast<long>(f * width), width,
                acc_.begin() + static_cast<long>(f * size_) + lo);
}

void FixedPointSum::result(std::size_t f, std::vector<double>& out) const {
  out.resize(size_);
  const double unit = 1.0 / scale_[f];
  for (std::size_t q = 0; q < size_; ++q) out[q] = static_cast<double>(acc_[f * size_ + q]) * unit;
}

} // namespace fluidem::coupling
