// The axis gravity points along, for whatever is oriented by it (the initial layers, the bed
// height, the ranks' columns).
#pragma once
#include <array>
#include <cmath>
#include <cstddef>

namespace fluidem {

/// The axis (0, 1, 2) of gravity's largest component; z without gravity.
inline int gravity_axis(const std::array<double, 3>& g) {
  int axis = 2;
  for (int a = 0; a < 3; ++a)
    if (std::abs(g[static_cast<std::size_t>(a)]) > std::abs(g[static_cast<std::size_t>(axis)]))
      axis = a;
  return axis;
}

} // namespace fluidem
