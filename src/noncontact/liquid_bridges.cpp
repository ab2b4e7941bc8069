#include "noncontact/liquid_bridges.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/parallel.hpp"
#include "noncontact/bridge_separation.hpp"
#include "noncontact/kernels/liquid_bridge.hpp"

namespace fluidem {

double longest_rupture_distance(const LiquidBridgeSpec& spec,
                                const std::vector<double>& liquid_fraction,
                                const ParticleStore& p) {
  double v_max = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    v_max = std::max(v_max, particle_liquid(liquid_fraction, p, i));
  return v_max > 0.0 ? kernels::liquid_bridge_rupture_distance(2.0 * v_max, spec.contact_angle())
                     : 0.0;
}

double shortest_bridge_time(const LiquidBridgeSpec& spec,
                            const std::vector<double>& liquid_fraction, const ParticleStore& p) {
  double t = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double v = particle_liquid(liquid_fraction, p, i);
    if (v <= 0.0 || p.fixed(i)) continue;
    const double r = p.radius[i], m_eff = 0.5 * p.mass[i];
    // Between two such particles, the bridge volumes of one to twelve bridges each: the stiffness
    // just off contact (the force is steepest there).
    for (const double volume : {2.0 * v, v / 6.0}) {
      const double gap =
          1e-6 * kernels::liquid_bridge_rupture_distance(volume, spec.contact_angle());
      const double k = kernels::liquid_bridge_capillary(r, r, volume, spec.contact_angle(),
                                                        spec.surface_tension, gap)
                           .stiffness;
      if (k > 0.0) t = std::min(t, std::numbers::pi * std::sqrt(m_eff / k));
    }
    if (spec.viscosity > 0.0) {
      const double c = 6.0 * std::numbers::pi * spec.viscosity * 0.25 * r * r / spec.min_gap;
      t = std::min(t, m_eff / c);
    }
  }
  return t;
}

LiquidBridges::LiquidBridges(const BoxGeometry& box, const LiquidBridgeSpec& spec,
                             std::vector<double> liquid_fraction, const ParticleStore& p,
                             double skin)
    : spec_(spec), liquid_fraction_(std::move(liquid_fraction)), box_(box),
      nl_(box, skin, 1, longest_rupture_distance(spec, liquid_fraction_, p)) {}

double LiquidBridges::liquid(const ParticleStore& p, std::size_t i) const {
  return particle_liquid(liquid_fraction_, p, i);
}

double LiquidBridges::pair_volume(const ParticleStore& p, std::size_t i, std::size_t j) const {
  return kernels::liquid_bridge_volume(liquid(p, i), count_[i], liquid(p, j), count_[j]);
}

void LiquidBridges::count_bridges(std::size_t n) {
  count_.assign(n, 0);
  parallel_for(n, threaded_particles(n), [&](std::size_t i) {
    int c = 0;
    for (std::uint32_t k = rows_.begin(i); k < rows_.end(i); ++k)
      c += nl_.history[rows_.entry(k)] != 0.0 ? 1 : 0;
    for (std::uint32_t k = rows_.wall_begin(i); k < rows_.wall_end(i); ++k)
      c += nl_.wall_history[k] != 0.0 ? 1 : 0;
    count_[i] = c;
  });
}

long LiquidBridges::bridge_count() const {
  long c = 0;
  for (const double h : nl_.history) c += h != 0.0 ? 1 : 0;
  for (const double h : nl_.wall_history) c += h != 0.0 ? 1 : 0;
  return c;
}

void LiquidBridges::compute(const ParticleStore& p, std::array<std::vector<double>, 3>& f) {
  const std::size_t n = p.size();
  order_.update(nl_, p);
  if (!rows_.current(nl_)) rows_.build(nl_, n);
  const bool threaded = threaded_particles(n);
  const auto& off = nl_.offset;
  // Bridges form where wet particles touch (each entry written by its owner's row only).
  parallel_for(n, threaded, [&](std::size_t i) {
    for (std::uint32_t e = off[i]; e < off[i + 1]; ++e) {
      const std::uint32_t j = nl_.partner[e];
      if (nl_.history[e] == 0.0 && (liquid(p, i) > 0.0 || liquid(p, j) > 0.0) &&
          bridge_separation(nl_, p, i, j).gap <= 0.0)
        nl_.history[e] = 1.0;
    }
    for (std::uint32_t k = rows_.wall_begin(i); k < rows_.wall_end(i); ++k)
      if (spec_.walls && nl_.wall_history[k] == 0.0 && liquid(p, i) > 0.0 &&
          wall_bridge_separation(box_, p, i, nl_.wall_face[k]).gap <= 0.0)
        nl_.wall_history[k] = 1.0;
  });
  count_bridges(n);
  // Bridges rupture at their rupture distance (volumes from the counts with the new ones).
  const double theta = spec_.contact_angle();
  parallel_for(n, threaded, [&](std::size_t i) {
    for (std::uint32_t e = off[i]; e < off[i + 1]; ++e) {
      if (nl_.history[e] == 0.0) continue;
      const std::uint32_t j = nl_.partner[e];
      const double s_c = kernels::liquid_bridge_rupture_distance(pair_volume(p, i, j), theta);
      if (bridge_separation(nl_, p, i, j).gap >= s_c) nl_.history[e] = 0.0;
    }
    for (std::uint32_t k = rows_.wall_begin(i); k < rows_.wall_end(i); ++k) {
      if (nl_.wall_history[k] == 0.0) continue;
      const double volume = kernels::liquid_bridge_volume(liquid(p, i), count_[i], 0.0, 1);
      const double s_c = kernels::liquid_bridge_rupture_distance(volume, theta);
      if (wall_bridge_separation(box_, p, i, nl_.wall_face[k]).gap >= s_c)
        nl_.wall_history[k] = 0.0;
    }
  });
  count_bridges(n);
  for (auto& a : f) a.resize(n);
  const double inf = std::numeric_limits<double>::infinity();
  // The force of a bridge along n (from i towards the partner), > 0 repelling.
  auto bridge_force = [&](double r_i, double r_j, double volume, const BridgeSeparation& s) {
    double fn = kernels::liquid_bridge_capillary_force(r_i, r_j, volume, theta,
                                                       spec_.surface_tension, s.gap);
    if (spec_.viscosity > 0.0)
      fn += kernels::liquid_bridge_viscous(spec_.viscosity, r_i, r_j, s.rate, s.gap, spec_.min_gap);
    return fn;
  };
  parallel_for(n, threaded, [&](std::size_t i) {
    Vec3 sum;
    for (std::uint32_t k = rows_.begin(i); k < rows_.end(i); ++k) {
      if (nl_.history[rows_.entry(k)] == 0.0) continue;
      const std::uint32_t j = rows_.partner(k);
      const BridgeSeparation s = bridge_separation(nl_, p, i, j);
      sum += s.n * (-bridge_force(p.radius[i], p.radius[j], pair_volume(p, i, j), s));
    }
    for (std::uint32_t k = rows_.wall_begin(i); k < rows_.wall_end(i); ++k) {
      if (nl_.wall_history[k] == 0.0) continue;
      const BridgeSeparation s = wall_bridge_separation(box_, p, i, nl_.wall_face[k]);
      const double volume = kernels::liquid_bridge_volume(liquid(p, i), count_[i], 0.0, 1);
      sum += s.n * (-bridge_force(p.radius[i], inf, volume, s));
    }
    f[0][i] = sum.x, f[1][i] = sum.y, f[2][i] = sum.z;
  });
}

} // namespace fluidem
