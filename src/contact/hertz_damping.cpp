#include "contact/hertz_damping.hpp"

#include <cmath>
#include <map>
#include <mutex>

namespace fluidem {

HertzImpact scaled_hertz_impact(double alpha) {
  // State (X, V); X^{1/4} and X^{3/2} use max(X, 0) so the right-hand side stays defined at the
  // very end of the contact. Step chosen so T_c is resolved by ~20000 steps (T_c ~ 3.2).
  const double h = 1.5e-4;
  auto rhs = [alpha](double x, double v) {
    const double xp = x > 0.0 ? x : 0.0;
    return -alpha * std::sqrt(std::sqrt(xp)) * v - xp * std::sqrt(xp);
  };
  double x = 0.0, v = 1.0, t = 0.0, xmax = 0.0;
  for (int step = 0; step < 10000000; ++step) {
    const double k1x = v, k1v = rhs(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = rhs(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = rhs(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = rhs(x + h * k3x, v + h * k3v);
    const double xn = x + h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double vn = v + h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (xn <= 0.0 && step > 0) {
      // Linear interpolation of the crossing X = 0 inside the last step.
      const double f = x / (x - xn);
      return {-(v + f * (vn - v)), t + f * h, xmax};
    }
    x = xn, v = vn, t += h;
    if (x > xmax) xmax = x;
    if (v <= 0.0 && x <= 0.0) break;
  }
  return {0.0, t, xmax}; // overdamped: the particles never separate
}

double hertz_damping_alpha(double e) {
  static std::mutex mutex;
  static std::map<double, double> cache;
  std::lock_guard lock(mutex);
  if (auto it = cache.find(e); it != cache.end()) return it->second;
  double alpha = 0.0;
  if (e < 1.0) {
    double lo = 0.0, hi = 1.0;
    while (scaled_hertz_impact(hi).restitution > e && hi < 64.0) hi *= 2.0;
    for (int it = 0; it < 60 && hi - lo > 1e-12 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (scaled_hertz_impact(mid).restitution > e ? lo : hi) = mid;
    }
    alpha = 0.5 * (lo + hi);
  }
  cache.emplace(e, alpha);
  return alpha;
}

namespace {
double time_scale(double m_eff, double k_hertz, double speed) {
  return std::pow(m_eff / k_hertz, 0.4) * std::pow(speed, -0.2);
}
} // namespace

double hertz_contact_duration(double m_eff, double k_hertz, double alpha, double speed) {
  return scaled_hertz_impact(alpha).duration * time_scale(m_eff, k_hertz, speed);
}

double hertz_max_overlap(double m_eff, double k_hertz, double alpha, double speed) {
  return speed * scaled_hertz_impact(alpha).max_overlap * time_scale(m_eff, k_hertz, speed);
}

} // namespace fluidem
