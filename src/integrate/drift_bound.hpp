// Whether the next velocity-Verlet step can carry any particle further than half the list's skin
// from where the last neighbour-list build saw it, decided before the step from what the last
// steps left: then the step needs no list rebuild, which is known only after the drift otherwise,
// and the integrator's pass over the particles can run inside the contact loop, slab by slab
// (Simulation::step's folded step), instead of before it.
//
// The next drift moves particle i by dt |v_i^{n+1/2}| with
//   v_i^{n+1/2} = v_i^{n-1/2} + dt (F_i^n / m_i + g)            (its two half kicks)
// and F_i^n the sum of at most E contact forces (E: the most list entries of any particle), each
// at most F_max, so |x_i^{n+1} - x_i^build| <= d_max + dt (v_max + dt (E F_max max(1/m) + |g|)),
// with v_max the largest drift speed of the last step and d_max a bound on every particle's
// distance from its build position: measured exactly after a step that is not folded (a pass of
// its own), then grown by dt v_max with each folded step (whose pass finds v_max alone: reading
// the build positions there too cost as much as folding the pass saved, at 10^5 particles).
// Contact forces and uniform gravity only (no gas forces, no body-force field).
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>

#include "neighbour/neighbour_list.hpp"

namespace fluidem {

struct DriftBound {
  /// The last step's largest drift speed, m/s, and a bound on every particle's distance from its
  /// position at the list's build, m (infinite: not known, so the next step is not folded).
  double v_max = std::numeric_limits<double>::infinity();
  double d_max = std::numeric_limits<double>::infinity();

  /// Whether the next step of dt keeps every particle within half_skin of its build position:
  /// max_force2 the largest squared force of one contact in the last force evaluation (N^2),
  /// max_entries the list's most entries per particle, max_inv_mass the largest 1/m (1/kg),
  /// g_abs |g| (m/s^2). False for anything not finite. A margin of 1e-6 of the step's bound and
  /// 1e-9 of the skin covers the round-off of the positions and of the bound itself.
  bool next_step_within(double dt, double half_skin, double max_force2, std::uint32_t max_entries,
                        double max_inv_mass, double g_abs) const;

  /// After a folded step of dt whose largest squared drift speed was v2max.
  void folded_step(double dt, double v2max);

  /// v_max and d_max measured on the contact loop's view of n particles (`stride` doubles each:
  /// position at 0-2, velocity at 4-6), as the integrator's pass left it, and the list's build
  /// positions.
  void measure(const double* view, std::size_t stride, std::size_t n, const NeighbourList& nl);
};

} // namespace fluidem
