#include "particles/particle_store.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fluidem {

double sphere_mass(double r, double rho) {
  return rho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

void ParticleStore::reserve(std::size_t n) {
  for_each_array([n](auto& a) { a.reserve(n); });
}

void ParticleStore::shrink_to_fit() {
  for_each_array([](auto& a) { a.shrink_to_fit(); });
}

void ParticleStore::resize(std::size_t n) {
  for_each_array([n](auto& a) { a.resize(n); });
}

void ParticleStore::add(const Vec3& p, const Vec3& v, double r, double rho, std::int32_t s,
                        std::int64_t pid) {
  const double m = sphere_mass(r, rho);
  x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
  vx.push_back(v.x), vy.push_back(v.y), vz.push_back(v.z);
  wx.push_back(0), wy.push_back(0), wz.push_back(0);
  radius.push_back(r);
  mass.push_back(m);
  inv_mass.push_back(1.0 / m);
  inv_inertia.push_back(1.0 / (0.4 * m * r * r)); // solid sphere I = 2/5 m r^2
  species.push_back(s);
  id.push_back(pid);
  layer.push_back(0);
  charge.push_back(0.0);
}

void ParticleStore::fix(std::size_t i) {
  inv_mass[i] = 0.0;
  inv_inertia[i] = 0.0;
  vx[i] = vy[i] = vz[i] = 0.0;
  wx[i] = wy[i] = wz[i] = 0.0;
}

void assign_layers(ParticleStore& p, int axis, int n_layers) {
  const std::vector<double>& h = axis == 0 ? p.x : axis == 1 ? p.y : p.z;
  p.layer.assign(p.size(), 0);
  if (n_layers <= 1 || p.size() == 0) return;
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  const double bottom = *lo, range = *hi - *lo;
  if (!(range > 0.0)) return;
  for (std::size_t i = 0; i < p.size(); ++i) {
    // + 1e-9 slice: a lattice row meant to lie on a boundary is not lost to rounding
    const double k = std::floor((h[i] - bottom) / range * n_layers + 1e-9);
    p.layer[i] = static_cast<std::int32_t>(std::clamp(k, 0.0, static_cast<double>(n_layers - 1)));
  }
}

void ParticleStore::permute(const std::vector<std::uint32_t>& new_to_old) {
  for_each_array([&](auto& a) {
    auto copy = a;
    for (std::size_t k = 0; k < new_to_old.size(); ++k) a[k] = copy[new_to_old[k]];
  });
}

std::size_t ParticleStore::bytes() const {
  std::size_t b = 0;
  for_each_array([&b](const auto& a) { b += a.capacity() * sizeof(a[0]); });
  return b;
}

} // namespace fluidem
