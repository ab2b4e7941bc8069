#include "noncontact/ordered_liquid_bridges.hpp"

#include <cmath>
#include <limits>

#include "core/parallel.hpp"
#include "noncontact/bridge_separation.hpp"
#include "noncontact/kernels/liquid_bridge.hpp"
#include "noncontact/liquid_bridges.hpp"

namespace fluidem {

namespace {

/// The pair (i, j) seen from its lower id: that particle first.
struct Oriented {
  std::size_t lo, hi;
};
Oriented oriented(const ParticleStore& p, std::size_t i, std::size_t j) {
  return p.id[i] < p.id[j] ? Oriented{i, j} : Oriented{j, i};
}

} // namespace

OrderedLiquidBridges::OrderedLiquidBridges(const BoxGeometry& box, const LiquidBridgeSpec& spec,
                                           std::vector<double> liquid_fraction, double reach)
    : spec_(spec), liquid_fraction_(std::move(liquid_fraction)), rows_(box, 1, reach) {}

double OrderedLiquidBridges::liquid(const ParticleStore& p, std::size_t i) const {
  return particle_liquid(liquid_fraction_, p, i);
}

void OrderedLiquidBridges::count(const ParticleStore& p, const ShareWithGhosts& share) {
  const std::size_t n = rows_.owned();
  counts_.assign(p.size(), 0.0);
  parallel_for(n, threaded_particles(n), [&](std::size_t i) {
    int c = 0;
    for (std::uint32_t k = rows_.offset[i]; k < rows_.offset[i + 1]; ++k)
      c += rows_.history[k] != 0.0 ? 1 : 0;
    for (std::uint32_t k = rows_.wall_offset[i]; k < rows_.wall_offset[i + 1]; ++k)
      c += rows_.wall_history[k] != 0.0 ? 1 : 0;
    counts_[i] = c;
  });
  share(counts_);
}

void OrderedLiquidBridges::compute(const ParticleStore& p, const ShareWithGhosts& share,
                                   std::vector<double>& f) {
  const std::size_t n = rows_.owned();
  const bool threaded = threaded_particles(n);
  const BoxGeometry& box = rows_.box();
  const double theta = spec_.contact_angle();
  // Bridges form where wet particles touch.
  parallel_for(n, threaded, [&](std::size_t i) {
    for (std::uint32_t k = rows_.offset[i]; k < rows_.offset[i + 1]; ++k) {
      if (rows_.history[k] != 0.0) continue;
      const auto [lo, hi] = oriented(p, i, rows_.partner[k]);
      if ((liquid(p, lo) > 0.0 || liquid(p, hi) > 0.0) &&
          bridge_separation(rows_, p, lo, hi).gap <= 0.0)
        rows_.history[k] = 1.0;
    }
    for (std::uint32_t k = rows_.wall_offset[i]; k < rows_.wall_offset[i + 1]; ++k)
      if (spec_.walls && rows_.wall_history[k] == 0.0 && liquid(p, i) > 0.0 &&
          wall_bridge_separation(box, p, i, rows_.wall_face[k]).gap <= 0.0)
        rows_.wall_history[k] = 1.0;
  });
  count(p, share);
  // The bridge's volume from both particles' counts (Yang's rule), seen from the lower id.
  const auto volume = [&](const Oriented& o) {
    return kernels::liquid_bridge_volume(liquid(p, o.lo), static_cast<int>(counts_[o.lo]),
                                         liquid(p, o.hi), static_cast<int>(counts_[o.hi]));
  };
  const auto wall_volume = [&](std::size_t i) {
    return kernels::liquid_bridge_volume(liquid(p, i), static_cast<int>(counts_[i]), 0.0, 1);
  };
  // Bridges rupture at their rupture distance (volumes from the counts with the new ones).
  parallel_for(n, threaded, [&](std::size_t i) {
    for (std::uint32_t k = rows_.offset[i]; k < rows_.offset[i + 1]; ++k) {
      if (rows_.history[k] == 0.0) continue;
      const Oriented o = oriented(p, i, rows_.partner[k]);
      const double s_c = kernels::liquid_bridge_rupture_distance(volume(o), theta);
      if (bridge_separation(rows_, p, o.lo, o.hi).gap >= s_c) rows_.history[k] = 0.0;
    }
    for (std::uint32_t k = rows_.wall_offset[i]; k < rows_.wall_offset[i + 1]; ++k) {
      if (rows_.wall_history[k] == 0.0) continue;
      const double s_c = kernels::liquid_bridge_rupture_distance(wall_volume(i), theta);
      if (wall_bridge_separation(box, p, i, rows_.wall_face[k]).gap >= s_c)
        rows_.wall_history[k] = 0.0;
    }
  });
  count(p, share);
  // The force of a bridge along n (from the first particle towards the second), > 0 repelling.
  const auto bridge_force = [&](double r_a, double r_b, double v, const BridgeSeparation& s) {
    double fn =
        kernels::liquid_bridge_capillary_force(r_a, r_b, v, theta, spec_.surface_tension, s.gap);
    if (spec_.viscosity > 0.0)
      fn += kernels::liquid_bridge_viscous(spec_.viscosity, r_a, r_b, s.rate, s.gap, spec_.min_gap);
    return fn;
  };
  const double inf = std::numeric_limits<double>::infinity();
  f.resize(3 * n);
  parallel_for(n, threaded, [&](std::size_t i) {
    Vec3 sum;
    for (std::uint32_t k = rows_.offset[i]; k < rows_.offset[i + 1]; ++k) {
      if (rows_.history[k] == 0.0) continue;
      const Oriented o = oriented(p, i, rows_.partner[k]);
      const BridgeSeparation s = bridge_separation(rows_, p, o.lo, o.hi);
      const double fn = bridge_force(p.radius[o.lo], p.radius[o.hi], volume(o), s);
      sum += s.n * (o.lo == i ? -fn : fn); // the lower id pushed along -n, the other along n
    }
    for (std::uint32_t k = rows_.wall_offset[i]; k < rows_.wall_offset[i + 1]; ++k) {
      if (rows_.wall_history[k] == 0.0) continue;
      const BridgeSeparation s = wall_bridge_separation(box, p, i, rows_.wall_face[k]);
      sum += s.n * (-bridge_force(p.radius[i], inf, wall_volume(i), s));
    }
    f[3 * i] = sum.x, f[3 * i + 1] = sum.y, f[3 * i + 2] = sum.z;
  });
}

std::int64_t OrderedLiquidBridges::bridges(const ParticleStore& p) const {
  std::int64_t c = 0;
  for (std::size_t i = 0; i < rows_.owned(); ++i) {
    for (std::uint32_t k = rows_.offset[i]; k < rows_.offset[i + 1]; ++k)
      c += rows_.history[k] != 0.0 && p.id[i] < p.id[rows_.partner[k]] ? 1 : 0;
    for (std::uint32_t k = rows_.wall_offset[i]; k < rows_.wall_offset[i + 1]; ++k)
      c += rows_.wall_history[k] != 0.0 ? 1 : 0;
  }
  return c;
}

} // namespace fluidem
