// When a sphere in free flight under a uniform acceleration meets a fixed sphere (a partner that
// never moves, ParticleStore::fix). Two free spheres fall together, so their relative motion is
// a straight line [Deen07 eq. 45]; against a fixed partner it is a parabola,
//   r(t) = r + v t + g t^2 / 2,
// and the spheres touch where the quartic f(t) = |r(t)|^2 - sigma^2 vanishes. Its roots in
// [0, horizon] are isolated by the turning points of f (the roots of the cubic f' = 2 r(t).r'(t),
// themselves isolated by the roots of the quadratic f'' = 2 (|r'|^2 + r.g), which are closed
// form), and each sign change on a monotone piece is bisected to the last bit: no root is
// missed, however the parabola grazes the sphere. Used by the event-driven engine
// (hard_sphere_engine.cpp); derivation in docs/fixed_particles.md.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/vec3.hpp"

namespace fluidem::hardsphere {

/// Time from now until a sphere at separation r from a fixed sphere (r: its centre minus the
/// fixed one's), moving at v with acceleration g, first touches it approaching; sigma = sum of
/// the radii. Infinity if not within `horizon`. Touching now (|r| <= sigma, round-off): 0 if
/// approaching (r.v < 0, the collision operator's test), else the next touch after moving off;
/// a sphere at rest on the fixed one, pushed in by g, touches again after `min_flight` (as at a
/// wall, HardSphereEngine::wall_time), so that it meets it approaching.
inline double time_to_fixed_contact(const Vec3& r, const Vec3& v, const Vec3& g, double sigma,
                                    double horizon, double min_flight) {
  constexpr double never = std::numeric_limits<double>::infinity();
  if (!(horizon > 0.0)) return never;
  // Out of reach: the distance covered in a time T is at most |v| T + |g| T^2 / 2 (margin for
  // the round-off of the roots, as in the engine's tests).
  const double dist = std::sqrt(norm2(r));
  if (dist - sigma >
      (std::sqrt(norm2(v)) + 0.5 * std::sqrt(norm2(g)) * horizon) * horizon * (1.0 + 1e-9))
    return never;
  const auto pos = [&](double t) { return r + v * t + g * (0.5 * t * t); };
  const auto f = [&](double t) { return norm2(pos(t)) - sigma * sigma; };
  const auto df = [&](double t) { return dot(pos(t), v + g * t); }; // f'/2
  // Turning points of f' in (0, horizon): 3/2 |g|^2 t^2 + 3 v.g t + |v|^2 + r.g = 0 (f''/2).
  std::array<double, 4> knots2{0.0};
  int n2 = 1;
  {
    const double a = 1.5 * norm2(g), b = 3.0 * dot(v, g), c = norm2(v) + dot(r, g);
    if (a > 0.0) {
      const double disc = b * b - 4.0 * a * c;
      if (disc > 0.0) {
        const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
        std::array<double, 2> t{q / a, q != 0.0 ? c / q : 0.0};
        std::sort(t.begin(), t.end());
        for (const double ti : t)
          if (ti > knots2[n2 - 1] && ti < horizon) knots2[n2++] = ti;
      }
    } else if (b != 0.0) {
      const double ti = -c / b;
      if (ti > 0.0 && ti < horizon) knots2[n2++] = ti;
    }
  }
  knots2[n2++] = horizon;
  // The first point in (lo, hi] where `fn` reaches `side`'s opposite, fn monotone there and
  // fn(lo) on `side` (> 0 when above is true): bisection to adjacent doubles; returns the last
  // point still on `side`, and its neighbour in `past`.
  const auto bisect = [](auto&& fn, double lo, double hi, bool above, double& past) {
    for (int k = 0; k < 2000; ++k) {
      const double mid = 0.5 * (lo + hi);
      if (!(mid > lo && mid < hi)) break;
      ((fn(mid) > 0.0) == above ? lo : hi) = mid;
    }
    past = hi;
    return lo;
  };
  // Turning points of f in (0, horizon): the roots of f' on f''s monotone pieces.
  std::array<double, 5> knots{0.0};
  int n1 = 1;
  for (int k = 0; k + 1 < n2; ++k) {
    const double lo = knots2[k], hi = knots2[k + 1];
    const double dlo = df(lo), dhi = df(hi);
    if ((dlo > 0.0) == (dhi > 0.0) || dlo == 0.0) continue;
    double past;
    const double t = bisect(df, lo, hi, dlo > 0.0, past);
    if (t > knots[n1 - 1] && t < horizon) knots[n1++] = t;
  }
  knots[n1++] = horizon;
  // The monotone pieces of f in order: the first where it falls to zero from above.
  for (int k = 0; k + 1 < n1; ++k) {
    const double lo = knots[k], hi = knots[k + 1];
    const double flo = f(lo), fhi = f(hi);
    if (!(fhi < flo)) continue; // rising (or flat): moving apart
    if (flo > 0.0) {
      if (fhi > 0.0) continue; // falls, but not to contact
      double past;
      const double t = bisect(f, lo, hi, true, past);
      // Not approaching now: the touch comes after the flight turns back, never sooner than a
      // minimal flight (a root closer than that is round-off of a sphere grazing or at rest).
      const double at = dot(r, v) >= 0.0 ? std::max(t, min_flight) : t;
      return at <= horizon ? at : never;
    }
    // Touching (or within round-off) where f starts to fall: now, if approaching now; else
    // (at rest on the sphere, or turning back towards it) after a minimal flight.
    if (k == 0 && dot(r, v) < 0.0) return 0.0;
    const double t = lo + min_flight;
    return t <= horizon ? t : never;
  }
  return never;
}

} // namespace fluidem::hardsphere
