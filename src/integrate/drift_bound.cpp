#include "integrate/drift_bound.hpp"

#include <cmath>

#include "core/parallel.hpp"

namespace fluidem {

bool DriftBound::next_step_within(double dt, double half_skin, double max_force2,
                                  std::uint32_t max_entries, double max_inv_mass,
                                  double g_abs) const {
  const double acceleration =
      static_cast<double>(max_entries) * std::sqrt(max_force2) * max_inv_mass + g_abs;
  const double step = dt * (v_max + dt * acceleration);
  const double reach = d_max + step * (1.0 + 1e-6);
  return reach <= half_skin * (1.0 - 1e-9); // false for NaN and infinity
}

void DriftBound::folded_step(double dt, double v2max) {
  v_max = std::sqrt(v2max);
  d_max += dt * v_max * (1.0 + 1e-12); // (the margin: the product's round-off)
}

void DriftBound::measure(const double* view, std::size_t stride, std::size_t n,
                         const NeighbourList& nl) {
  double v2 = 0.0, d2 = 0.0;
  // Maxima: the same in any order, so with any number of threads.
  const bool threaded = threaded_particles(n);
#pragma omp parallel for schedule(static) reduction(max : v2, d2) if (threaded)
  for (std::size_t i = 0; i < n; ++i) {
    const double* vi = view + stride * i;
    const double s2 = vi[4] * vi[4] + vi[5] * vi[5] + vi[6] * vi[6];
    const double r2 = nl.displacement2(i, vi[0], vi[1], vi[2]);
    // (a NaN counts as no speed and no displacement, as in NeighbourList::moved_far)
    v2 = s2 > v2 ? s2 : v2;
    d2 = r2 > d2 ? r2 : d2;
  }
  v_max = std::sqrt(v2);
  d_max = std::sqrt(d2);
}

} // namespace fluidem
