#include "hardsphere/hard_sphere_engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/material_mixing.hpp"

namespace fluidem {

namespace {
hardsphere::CollisionLaw law_from(const MixedCoefficients& m) {
  return {m.restitution, m.friction, m.tangential_restitution};
}
} // namespace

HardSphereEngine::HardSphereEngine(const CaseSpec& spec, const BoxGeometry& box)
    : dimension_(spec.simulation.dimension), nspecies_(static_cast<int>(spec.species.size())),
      opts_(spec.hardsphere), nl_(box, 0.0, 0) {
  pair_law_.resize(nspecies_ * nspecies_);
  wall_law_.resize(nspecies_ * 6);
  for (int i = 0; i < nspecies_; ++i) {
    for (int j = 0; j < nspecies_; ++j)
      pair_law_[i * nspecies_ + j] =
          law_from(mix_pair(spec.species[i].material, spec.species[j].material));
    for (int f = 0; f < 6; ++f)
      wall_law_[i * 6 + f] = law_from(wall_coefficients(spec.domain.wall_material[f]));
  }
}

void HardSphereEngine::build_full_list(const ParticleStore& p) {
  // Both directions of every pair of the half list: a particle's events are computed with all
  // its neighbours.
  const std::size_t n = p.size();
  full_offset_.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    full_offset_[i + 1] += nl_.offset[i + 1] - nl_.offset[i];
    for (std::uint32_t e = nl_.offset[i]; e < nl_.offset[i + 1]; ++e)
      ++full_offset_[nl_.partner[e] + 1];
  }
  for (std::size_t i = 0; i < n; ++i) full_offset_[i + 1] += full_offset_[i];
  full_partner_.resize(full_offset_[n]);
  std::vector<std::uint32_t> fill(full_offset_.begin(), full_offset_.end() - 1);
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t e = nl_.offset[i]; e < nl_.offset[i + 1]; ++e) {
      const std::uint32_t j = nl_.partner[e];
      full_partner_[fill[i]++] = j;
      full_partner_[fill[j]++] = i;
    }
}

void HardSphereEngine::push(const Event& ev) {
  heap_.push_back(ev);
  std::push_heap(heap_.begin(), heap_.end(), Later{});
}

void HardSphereEngine::schedule(const ParticleStore& p, std::uint32_t i, double now) {
  const auto n = static_cast<std::uint32_t>(p.size());
  const double ai = now - clock_[i];
  const Vec3 xi{p.x[i] + p.vx[i] * ai, p.y[i] + p.vy[i] * ai, p.z[i] + p.vz[i] * ai};
  const Vec3 vi = p.velocity(i);
  double best = t_end_;
  std::uint32_t partner = std::numeric_limits<std::uint32_t>::max();
  // Pairs: [Deen07 eq. 45], written as c / (-b + sqrt(b^2 - v^2 c)) to avoid cancellation.
  for (std::uint32_t k = full_offset_[i]; k < full_offset_[i + 1]; ++k) {
    const std::uint32_t j = full_partner_[k];
    const double aj = now - clock_[j];
    const Vec3 r{nl_.min_image(xi.x - (p.x[j] + p.vx[j] * aj), 0),
                 nl_.min_image(xi.y - (p.y[j] + p.vy[j] * aj), 1),
                 nl_.min_image(xi.z - (p.z[j] + p.vz[j] * aj), 2)};
    const Vec3 v = vi - p.velocity(j);
    const double b = dot(r, v);
    if (b >= 0.0) continue; // moving apart
    const double sigma = p.radius[i] + p.radius[j];
    const double c = norm2(r) - sigma * sigma;
    double dt;
    if (c <= 0.0) {
      dt = 0.0; // touching (round-off) and approaching: collide now
    } else {
      const double disc = b * b - norm2(v) * c;
      if (disc < 0.0) continue; // miss
      dt = c / (-b + std::sqrt(disc));
    }
    if (now + dt < best) best = now + dt, partner = j;
  }
  // Walls [Hoomans96 eq. 31].
  const auto& box = nl_.box();
  for (int f = 0; f < 6; ++f) {
    if (!box.wall[f]) continue;
    const int a = f / 2;
    const double va = vi[a];
    double dt;
    if (f % 2 == 0) {
      if (va >= 0.0) continue;
      dt = (xi[a] - box.lo[a] - p.radius[i]) / -va;
    } else {
      if (va <= 0.0) continue;
      dt = (box.hi[a] - p.radius[i] - xi[a]) / va;
    }
    dt = std::max(dt, 0.0);
    if (now + dt < best) best = now + dt, partner = n + static_cast<std::uint32_t>(f);
  }
  if (partner == std::numeric_limits<std::uint32_t>::max()) return;
  push({best, i, partner, counter_[i], partner < n ? counter_[partner] : 0u});
}

void HardSphereEngine::process(ParticleStore& p, const Event& ev) {
  const auto n = static_cast<std::uint32_t>(p.size());
  const std::uint32_t a = ev.a, b = ev.b;
  const bool wall = b >= n;
  auto move_to = [&](std::uint32_t i) {
    const double dt = ev.t - clock_[i];
    p.x[i] += p.vx[i] * dt, p.y[i] += p.vy[i] * dt, p.z[i] += p.vz[i] * dt;
    clock_[i] = ev.t;
  };
  auto body = [&](std::uint32_t i) {
    return hardsphere::Body{p.velocity(i), p.angular_velocity(i), p.radius[i], p.inv_mass[i],
                            p.inv_inertia[i]};
  };
  auto kinetic = [&](const hardsphere::Body& x, std::uint32_t i) {
    return x.inv_m > 0.0 ? 0.5 * p.mass[i] * norm2(x.v) + 0.5 / x.inv_i * norm2(x.w) : 0.0;
  };
  move_to(a);
  hardsphere::Body ba = body(a), bb;
  Vec3 normal;
  hardsphere::CollisionLaw law;
  bool recent = ev.t - last_collision_[a] < opts_.tc_time;
  if (!wall) {
    move_to(b);
    bb = body(b);
    const Vec3 r{nl_.min_image(p.x[a] - p.x[b], 0), nl_.min_image(p.y[a] - p.y[b], 1),
                 nl_.min_image(p.z[a] - p.z[b], 2)};
    normal = r / norm(r);
    law = pair_law_[p.species[a] * nspecies_ + p.species[b]];
    recent = recent || ev.t - last_collision_[b] < opts_.tc_time;
  } else {
    const int f = static_cast<int>(b - n);
    normal[f / 2] = (f % 2 == 0) ? 1.0 : -1.0; // from the wall into the particle
    law = wall_law_[p.species[a] * 6 + f];
  }
  const double e_before = kinetic(ba, a) + (wall ? 0.0 : kinetic(bb, b));
  hardsphere::CollisionLaw used = law;
  if (recent && law.e_n < 1.0) used.e_n = 1.0; // TC model
  const auto res = hardsphere::collide(ba, bb, normal, used);
  if (!res.approaching) { // grazing after round-off: nothing to do, look again
    schedule(p, a, ev.t);
    return;
  }
  auto store = [&](std::uint32_t i, const hardsphere::Body& x) {
    p.vx[i] = x.v.x, p.vy[i] = x.v.y, p.vz[i] = x.v.z;
    p.wx[i] = x.w.x, p.wy[i] = x.w.y, p.wz[i] = x.w.z;
  };
  store(a, ba);
  if (!wall) store(b, bb);
  const double e_after = kinetic(ba, a) + (wall ? 0.0 : kinetic(bb, b));
  stats_.dissipated += e_before - e_after;
  if (used.e_n != law.e_n) {
    ++stats_.tc_elastic;
    // What the inelastic collision would have removed: (1 - e^2) of the normal relative energy.
    const double inv_mn = ba.inv_m + bb.inv_m;
    const double jn = dot(res.impulse, normal); // = 2 m_n |v_n| for e_n = 1
    const double vn = 0.5 * jn * inv_mn;
    stats_.tc_energy_kept += 0.5 / inv_mn * vn * vn * (1.0 - law.e_n * law.e_n);
  }
  ++stats_.collisions;
  ++stats_.events_last_step;
  ++counter_[a];
  last_collision_[a] = ev.t;
  if (wall) {
    ++stats_.wall_collisions;
  } else {
    ++counter_[b];
    last_collision_[b] = ev.t;
  }
  schedule(p, a, ev.t);
  if (!wall) schedule(p, b, ev.t);
}

void HardSphereEngine::check_no_overlap(const ParticleStore& p, double time) const {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t e = nl_.offset[i]; e < nl_.offset[i + 1]; ++e) {
      const std::uint32_t j = nl_.partner[e];
      const double dx = nl_.min_image(p.x[j] - p.x[i], 0);
      const double dy = nl_.min_image(p.y[j] - p.y[i], 1);
      const double dz = nl_.min_image(p.z[j] - p.z[i], 2);
      const double sigma = p.radius[i] + p.radius[j];
      if (dx * dx + dy * dy + dz * dz < sigma * sigma * (1.0 - 1e-6)) {
        throw InstabilityError(fmt::format(
            "hard-sphere run failed at t = {:.6g} s: particles {} and {} overlap (a collision "
            "was missed); reduce simulation.time_step",
            time, p.id[i], p.id[j]));
      }
    }
}

void HardSphereEngine::advance(ParticleStore& p, double time, double dt,
                               const std::array<double, 3>& accel) {
  const std::size_t n = p.size();
  const double h = 0.5 * dt;
  auto kick = [&]() {
    for (std::size_t i = 0; i < n; ++i) {
      p.vx[i] += h * accel[0];
      p.vy[i] += h * accel[1];
      p.vz[i] += h * accel[2];
    }
  };
  kick();
  // Neighbour list bounded by [Deen07 eq. 44] with a 1.5 safety factor on the velocity term
  // (collisions can speed a particle up within the step).
  double vmax = 0.0, rmin = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    vmax = std::max(vmax, std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]));
    rmin = std::min(rmin, p.radius[i]);
  }
  nl_.set_skin(3.0 * vmax * dt + 1e-3 * rmin);
  nl_.build(p);
  build_full_list(p);

  clock_.assign(n, time);
  counter_.resize(n, 0);
  last_collision_.resize(n, -std::numeric_limits<double>::infinity());
  t_end_ = time + dt;
  heap_.clear();
  stats_.events_last_step = 0;
  for (std::uint32_t i = 0; i < n; ++i) schedule(p, i, time);
  const auto limit = static_cast<long>(opts_.max_events_per_particle * static_cast<double>(n));
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), Later{});
    const Event ev = heap_.back();
    heap_.pop_back();
    if (ev.t > t_end_) break;
    if (counter_[ev.a] != ev.ca) continue;     // the owner collided since: a newer event exists
    if (ev.b < n && counter_[ev.b] != ev.cb) { // the partner changed course: look again
      schedule(p, ev.a, ev.t);
      continue;
    }
    process(p, ev);
    if (stats_.events_last_step > limit) {
      throw InstabilityError(fmt::format(
          "hard-sphere run stalled at t = {:.9g} s: more than {} collisions per particle in one "
          "flow step (inelastic collapse); raise hardsphere.tc_time or reduce the time step",
          ev.t, opts_.max_events_per_particle));
    }
  }
  // Everybody to the end of the step; periodic axes wrapped.
  const auto& box = nl_.box();
  for (std::size_t i = 0; i < n; ++i) {
    const double a = t_end_ - clock_[i];
    p.x[i] += p.vx[i] * a, p.y[i] += p.vy[i] * a, p.z[i] += p.vz[i] * a;
    double* q[3] = {&p.x[i], &p.y[i], &p.z[i]};
    for (int ax = 0; ax < 3; ++ax)
      if (box.periodic[ax])
        *q[ax] -= box.length(ax) * std::floor((*q[ax] - box.lo[ax]) / box.length(ax));
  }
  kick();
  check_no_overlap(p, t_end_);
}

std::size_t HardSphereEngine::bytes() const {
  auto b = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return nl_.bytes() + b(full_offset_) + b(full_partner_) + b(clock_) + b(last_collision_) +
         b(counter_) + b(heap_);
}

} // namespace fluidem
