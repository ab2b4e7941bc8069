// Rounding to an integer without the library call.
#pragma once

namespace fluidem {

/// std::nearbyint(q) in the default rounding mode (to nearest, ties to even), exact for
/// |q| < 2^51, as inline arithmetic: on the x86-64 baseline (no SSE4.1 roundsd) std::nearbyint
/// is a call into libm, and a call inside a particle loop makes the compiler reload every array
/// pointer of the loop on every iteration. Adding 1.5 * 2^52 leaves no bits below the units, so
/// the sum is rounded to an integer by the addition itself; subtracting it again is exact.
/// (Not valid under -ffast-math, which may fold the two operations away; fluidem never uses it.)
inline double nearest_integer(double q) {
  constexpr double magic = 6755399441055744.0; // 1.5 * 2^52
  return (q + magic) - magic;
}

/// std::floor(q) the same way (exact for |q| < 2^51).
inline double floor_integer(double q) {
  const double r = nearest_integer(q);
  return r > q ? r - 1.0 : r;
}

/// Coordinate c moved by a whole number of periods l into [lo, lo + l) (a periodic axis).
inline double wrapped(double c, double lo, double l) {
  return c - l * floor_integer((c - lo) / l);
}

} // namespace fluidem
