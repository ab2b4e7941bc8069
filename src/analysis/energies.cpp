#include "analysis/energies.hpp"

#include <algorithm>
#include <numbers>
#include <vector>

namespace fluidem {

Energies particle_energies(const ParticleStore& p, const std::array<double, 3>& g) {
  double ek = 0.0, er = 0.0, ep = 0.0;
  const std::size_t n = p.size();
  // Fixed-order serial sums: results independent of the thread count.
  for (std::size_t i = 0; i < n; ++i) {
    if (p.fixed(i)) continue; // held in place: part of the walls, not of the moving bed
    const double m = p.mass[i];
    ek += 0.5 * m * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    er += 0.5 / p.inv_inertia[i] * (p.wx[i] * p.wx[i] + p.wy[i] * p.wy[i] + p.wz[i] * p.wz[i]);
    ep -= m * (g[0] * p.x[i] + g[1] * p.y[i] + g[2] * p.z[i]);
  }
  return {ek, er, ep};
}

double bed_surface_height(const ParticleStore& p, double x_lo, double x_hi, double z_lo,
                          double column_width) {
  const auto ncol = static_cast<std::size_t>(std::max(1.0, (x_hi - x_lo) / column_width));
  std::vector<double> top(ncol, z_lo);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double rel = (p.x[i] - x_lo) / (x_hi - x_lo);
    const auto c = std::min(
        ncol - 1, static_cast<std::size_t>(std::max(0.0, rel) * static_cast<double>(ncol)));
    top[c] = std::max(top[c], p.z[i] + p.radius[i]);
  }
  double sum = 0.0;
  for (double t : top) sum += t - z_lo;
  return sum / static_cast<double>(ncol);
}

double settled_area_fraction(const ParticleStore& p, double x_lo, double x_hi, double z_lo) {
  double area = 0.0, dmean = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    area += std::numbers::pi * p.radius[i] * p.radius[i];
    dmean += 2.0 * p.radius[i];
  }
  dmean /= static_cast<double>(std::max<std::size_t>(1, p.size()));
  return area / ((x_hi - x_lo) * bed_surface_height(p, x_lo, x_hi, z_lo, dmean));
}

} // namespace fluidem
