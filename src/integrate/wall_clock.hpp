// Wall-clock timing of a run's parts (the log's "time in ..." lines).
#pragma once
#include <chrono>

namespace fluidem {

using WallClock = std::chrono::steady_clock;

/// Seconds of wall time since t0.
inline double seconds_since(WallClock::time_point t0) {
  return std::chrono::duration<double>(WallClock::now() - t0).count();
}

} // namespace fluidem
