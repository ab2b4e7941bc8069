// The simulation box as the neighbour search sees it: its corners, which axes are periodic and
// which faces carry a wall.
#pragma once
#include <array>

namespace fluidem {

struct BoxGeometry {
  std::array<double, 3> lo{}, hi{};
  std::array<bool, 3> periodic{};
  /// Which faces carry a wall (closed, non-periodic; no y walls for 2-D discs).
  std::array<bool, 6> wall{};
  double length(int a) const { return hi[a] - lo[a]; }
};

} // namespace fluidem
