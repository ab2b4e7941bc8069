// The reductions of fixed-point deposition (coupling/rank_sum.hpp) over a communicator's ranks.
#pragma once
#include "coupling/rank_sum.hpp"
#include "parallel/communicator.hpp"

namespace fluidem {

/// The communicator must outlive the returned functions.
inline coupling::RankSum rank_sum_of(const Communicator& c) {
  return {[&c](double v) { return c.max(v); }, [&c](std::int64_t v) { return c.sum(v); },
          [&c](std::span<std::int64_t> v) { c.sum_in_place(v); }};
}

} // namespace fluidem
