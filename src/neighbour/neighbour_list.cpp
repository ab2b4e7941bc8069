#include "neighbour/neighbour_list.hpp"
#include "core/parallel.hpp"
#include "neighbour/cell_walk.hpp"
#include "neighbour/spatial_order.hpp"

#include <stdexcept>
#include <string>

#include <algorithm>
#include <cmath>

namespace fluidem {

namespace {
template <class T>
void release(std::vector<T>& v) {
  std::vector<T>().swap(v);
}
} // namespace

NeighbourList::NeighbourList(const BoxGeometry& box, double skin, int history_width, double reach)
    : box_(box), skin_(skin), reach_(reach), hw_(history_width) {}

bool NeighbourList::needs_rebuild(const ParticleStore& p) const {
  const std::size_t n = p.size();
  if (!built_for(n)) return true;
  return parallel_any(n, threaded_particles(n),
                      [&](std::size_t i) { return moved_far(i, p.x[i], p.y[i], p.z[i]); });
}

double NeighbourList::AutoSkin::skin(double v_max) const {
  return std::clamp(2.0 * steps * v_max * dt, min_skin, max_skin);
}

double NeighbourList::skin_for(const ParticleStore& p) const {
  if (!auto_skin_) return skin_;
  const std::size_t n = p.size();
  const double *const vx = p.vx.data(), *const vy = p.vy.data(), *const vz = p.vz.data();
  double v2 = 0.0;
  // A maximum: the same in any order, so with any number of threads.
#pragma omp parallel for schedule(static) reduction(max : v2) if (threaded_particles(n))
  for (std::size_t i = 0; i < n; ++i) {
    const double s2 = vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i];
    v2 = s2 > v2 ? s2 : v2; // (a NaN counts as no speed)
  }
  return auto_skin_->skin(std::sqrt(v2));
}

double NeighbourList::cell_size(const ParticleStore& p) const {
  double rmax = 0.0;
  for (const double r : p.radius) rmax = std::max(rmax, r);
  return 2.0 * rmax + reach_ + skin_for(p);
}

void NeighbourList::renumber_old(const std::vector<std::uint32_t>& new_to_old) {
  const std::size_t n = new_to_old.size();
  const auto h = static_cast<std::size_t>(hw_);
  std::vector<std::uint32_t> old_to_new(n);
  for (std::size_t k = 0; k < n; ++k) old_to_new[new_to_old[k]] = static_cast<std::uint32_t>(k);
  // Pairs: row k is the old row of new_to_old[k], its partners renumbered. Within a row the
  // order is no longer ascending and an owner may now be the pair's higher index: the carry-over
  // below searches both rows of a pair, so neither matters.
  std::vector<std::uint32_t> offset_new(n + 1, 0), partner_new(old_partner_.size());
  std::vector<double> history_new(old_history_.size());
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t i = new_to_old[k];
    const std::uint32_t begin = old_offset_[i], end = old_offset_[i + 1];
    const std::uint32_t o = offset_new[k];
    offset_new[k + 1] = o + (end - begin);
    for (std::uint32_t e = begin; e < end; ++e) {
      partner_new[o + (e - begin)] = old_to_new[old_partner_[e]];
      if (h > 0) // (no history: the arrays are empty, and [0] of an empty vector is undefined)
        std::copy_n(old_history_.data() + e * h, h, history_new.data() + (o + (e - begin)) * h);
    }
  }
  old_offset_.swap(offset_new);
  old_partner_.swap(partner_new);
  old_history_.swap(history_new);
  // Walls: sorted again by (new particle, face), as the merge of the carry-over expects.
  const std::size_t nw = old_wall_particle_.size();
  std::vector<std::uint32_t> order(nw);
  for (std::size_t e = 0; e < nw; ++e) order[e] = static_cast<std::uint32_t>(e);
  auto key = [&](std::uint32_t e) {
    return static_cast<std::uint64_t>(old_to_new[old_wall_particle_[e]]) * 8 + old_wall_face_[e];
  };
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  std::vector<std::uint32_t> wall_particle_new(nw);
  std::vector<std::uint8_t> wall_face_new(nw);
  std::vector<double> wall_history_new(old_wall_history_.size());
  for (std::size_t e = 0; e < nw; ++e) {
    wall_particle_new[e] = old_to_new[old_wall_particle_[order[e]]];
    wall_face_new[e] = old_wall_face_[order[e]];
    if (h > 0)
      std::copy_n(old_wall_history_.data() + order[e] * h, h, wall_history_new.data() + e * h);
  }
  old_wall_particle_.swap(wall_particle_new);
  old_wall_face_.swap(wall_face_new);
  old_wall_history_.swap(wall_history_new);
}

void NeighbourList::build(const ParticleStore& p, const std::vector<std::uint32_t>* new_to_old) {
  skin_ = skin_for(p);
  build_with_skin(p, new_to_old);
}

void NeighbourList::build_slabs(std::size_t n) {
  // Slabs along the axis over which the particles spread across the most cells.
  std::array<std::uint32_t, 3> cmin{~0u, ~0u, ~0u}, cmax{0, 0, 0};
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      const std::uint32_t q = grid_.coordinate(i, a);
      cmin[a] = std::min(cmin[a], q), cmax[a] = std::max(cmax[a], q);
    }
  slab_axis_ = n > 0 ? slab_axis(cmin, cmax) : 0; // the rule spatial_order follows too
  // The cell layers along the axis: a particle's layer decides which particle owns a pair
  // (the lower layer, build()'s owns). A periodic axis gets an even number of layers (the last
  // layer neighbours layer 0): the last cell then joins the layer before it. (The contact
  // loop's even/odd slab phases needed it; its groups of two or more slabs do not, but the
  // layers decide which particle owns a pair, and a checkpoint's list is verified against the
  // pairs rebuilt from it.)
  nlayer_ = grid_.cells_per_axis()[slab_axis_];
  if (box_.periodic[slab_axis_] && nlayer_ > 1 && nlayer_ % 2 == 1) --nlayer_;
  const auto last = static_cast<std::uint32_t>(nlayer_ - 1);
  particle_slab_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    particle_slab_[i] = std::min(grid_.coordinate(i, slab_axis_), last);
  // The slabs: the occupied layers, numbered in order (a box much longer than its particles'
  // spread has mostly empty layers, which would cost the contact loop a visit each per step).
  // A pair lies in one layer or in two neighbouring ones, which are then neighbouring slabs
  // (no occupied layer lies between them): the rows of slab s still touch only slabs s and
  // s + 1 (and slab 0 from the last one across a periodic axis), as the contact loop needs.
  // Counted over the layers when there are not many more of them than particles, else over
  // the particles sorted by layer.
  slab_particles.resize(n);
  if (static_cast<std::size_t>(nlayer_) <= 2 * n + 64) {
    // count_[l]: the particles of layer l, then the first place of its slab (a cursor).
    count_.reserve(std::max(static_cast<std::size_t>(nlayer_), n)); // (build() reuses it for n)
    count_.assign(static_cast<std::size_t>(nlayer_), 0);
    for (std::size_t i = 0; i < n; ++i) ++count_[particle_slab_[i]];
    slab_start.assign(1, 0);
    for (int l = 0; l < nlayer_; ++l) {
      const std::uint32_t c = count_[l];
      count_[l] = slab_start.back();
      if (c > 0) slab_start.push_back(slab_start.back() + c);
    }
    for (std::size_t i = 0; i < n; ++i)
      slab_particles[count_[particle_slab_[i]]++] = static_cast<std::uint32_t>(i);
  } else {
    for (std::size_t i = 0; i < n; ++i) slab_particles[i] = static_cast<std::uint32_t>(i);
    std::stable_sort(
        slab_particles.begin(), slab_particles.end(),
        [&](std::uint32_t a, std::uint32_t b) { return particle_slab_[a] < particle_slab_[b]; });
    slab_start.assign(1, 0);
    for (std::size_t k = 0; k < n; ++k)
      if (k + 1 == n || particle_slab_[slab_particles[k + 1]] != particle_slab_[slab_particles[k]])
        slab_start.push_back(static_cast<std::uint32_t>(k + 1));
  }
  if (slab_start.size() == 1) slab_start.push_back(0); // no particles: one empty slab
  nslab_ = static_cast<int>(slab_start.size() - 1);
}

// One function of about 180 lines on purpose: the list build is a hot loop of the soft-sphere
// step (bench/compare_dem.sh), its pair and wall passes share the cell walk's locals.
void NeighbourList::build_with_skin(const ParticleStore& p,
                                    const std::vector<std::uint32_t>* new_to_old) {
  const std::size_t n = p.size();
  double rmax = 0.0;
  for (const double r : p.radius) rmax = std::max(rmax, r);
  grid_.bin(box_, 2.0 * rmax + reach_ + skin_, p.x.data(), p.y.data(), p.z.data(), n,
            threaded_particles(n));
  stored_cells_ = grid_.stored_cells();
  grid_bytes_ = grid_.bytes();

  std::swap(old_offset_, offset);
  std::swap(old_partner_, partner);
  std::swap(old_history_, history);
  std::swap(old_wall_particle_, wall_particle);
  std::swap(old_wall_face_, wall_face);
  std::swap(old_wall_history_, wall_history);
  const bool carry = builds_ > 0 && old_offset_.size() == n + 1;
  if (new_to_old) {
    if (new_to_old->size() != n)
      throw std::invalid_argument("NeighbourList::build: the new order has " +
                                  std::to_string(new_to_old->size()) + " entries for " +
                                  std::to_string(n) + " particles");
    if (carry) renumber_old(*new_to_old);
  }

  build_slabs(n);
  const bool periodic_slabs = box_.periodic[slab_axis_];
  // Owner of a pair: the particle whose layer is followed by the other's; within a layer the
  // lower index. (With two periodic layers each follows the other: the lower layer owns.)
  auto owns = [&](std::uint32_t i, std::uint32_t j) {
    const std::uint32_t si = particle_slab_[i], sj = particle_slab_[j];
    if (si == sj) return i < j;
    const auto next = [&](std::uint32_t sl) {
      return periodic_slabs ? (sl + 1) % static_cast<std::uint32_t>(nlayer_) : sl + 1;
    };
    if (sj == next(si) && si == next(sj)) return si < sj;
    return sj == next(si);
  };

  // Neighbour cells of each cell, deduplicated (periodic axes with fewer than 3 cells). Two
  // fixed particles (ParticleStore::fix) never interact: no pair of them.
  auto for_each_partner = [&](std::size_t i, auto&& visit) {
    const bool fixed_i = p.fixed(i);
    grid_.for_each_near(i, box_.periodic, [&](std::uint32_t j) {
      if (j == i || !owns(static_cast<std::uint32_t>(i), j)) return;
      if (fixed_i && p.fixed(j)) return;
      const double dxp = min_image(p.x[j] - p.x[i], 0);
      const double dyp = min_image(p.y[j] - p.y[i], 1);
      const double dzp = min_image(p.z[j] - p.z[i], 2);
      const double cut = p.radius[i] + p.radius[j] + reach_ + skin_;
      if (dxp * dxp + dyp * dyp + dzp * dzp < cut * cut) visit(j);
    });
  };

  offset.assign(n + 1, 0);
  const bool threaded = threaded_particles(n);
  // The history of row i's pairs from the previous list.
  const auto carry_row = [&](std::size_t i) {
    if (!carry || hw_ == 0) return;
    // The pair may have been owned by either particle: the history is antisymmetric (it is
    // seen from the owner), so a pair found under its partner's old row is negated.
    for (std::uint32_t e = offset[i]; e < offset[i + 1]; ++e) {
      const std::uint32_t j = partner[e];
      double* dst = &history[static_cast<std::size_t>(e) * hw_];
      bool found = false;
      for (std::uint32_t o = old_offset_[i]; o < old_offset_[i + 1] && !found; ++o) {
        if (old_partner_[o] != j) continue;
        std::copy_n(&old_history_[static_cast<std::size_t>(o) * hw_], hw_, dst);
        found = true;
      }
      for (std::uint32_t o = old_offset_[j]; o < old_offset_[j + 1] && !found; ++o) {
        if (old_partner_[o] != i) continue;
        const double* src = &old_history_[static_cast<std::size_t>(o) * hw_];
        for (int h = 0; h < hw_; ++h) dst[h] = -src[h];
        found = true;
      }
    }
  };
  // Deterministic order within a row: ascending partner index.
  const auto sort_row = [&](std::size_t i) {
    std::sort(partner.begin() + offset[i], partner.begin() + offset[i + 1]);
  };
  if (threaded) {
    // Rows counted, then filled, each in parallel.
    const auto count_row = [&](std::size_t i) {
      std::uint32_t count = 0;
      for_each_partner(i, [&](std::uint32_t) { ++count; });
      offset[i + 1] = count;
    };
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) count_row(i);
    for (std::size_t i = 0; i < n; ++i) offset[i + 1] += offset[i];
    partner.resize(offset[n]);
    history.assign(static_cast<std::size_t>(offset[n]) * hw_, 0.0);
    const auto fill_row = [&](std::size_t i) {
      std::uint32_t k = offset[i];
      for_each_partner(i, [&](std::uint32_t j) { partner[k++] = j; });
      sort_row(i);
      carry_row(i);
    };
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) fill_row(i);
  } else {
    // One thread: one walk over the cells, the rows appended in order (the same list).
    partner.clear();
    partner.reserve(old_partner_.size() + old_partner_.size() / 8 + 64);
    for (std::size_t i = 0; i < n; ++i) {
      offset[i] = static_cast<std::uint32_t>(partner.size());
      for_each_partner(i, [&](std::uint32_t j) { partner.push_back(j); });
    }
    offset[n] = static_cast<std::uint32_t>(partner.size());
    // Without a previous list (the first build) the appends doubled the capacity up to twice
    // the size: trimmed to it (later builds reserve from the previous size).
    if (partner.capacity() > partner.size() + partner.size() / 8 + 64) partner.shrink_to_fit();
    history.assign(static_cast<std::size_t>(offset[n]) * hw_, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      sort_row(i);
      carry_row(i);
    }
  }

  // Wall entries: counted, then filled (the arrays get their exact size). None for a fixed
  // particle: it does not touch a wall (insertion refuses that) and could not move off one.
  const std::array<const std::vector<double>*, 3> pos{&p.x, &p.y, &p.z};
  auto for_each_wall = [&](auto&& visit) {
    for (std::size_t i = 0; i < n; ++i) {
      if (p.fixed(i)) continue;
      for (int f = 0; f < 6; ++f) {
        if (!box_.wall[f]) continue;
        const int a = f / 2;
        const double gap = (f % 2 == 0) ? (*pos[a])[i] - box_.lo[a] : box_.hi[a] - (*pos[a])[i];
        if (gap < p.radius[i] + reach_ + skin_) visit(i, f);
      }
    }
  };
  std::size_t n_wall = 0;
  for_each_wall([&](std::size_t, int) { ++n_wall; });
  wall_particle.resize(n_wall);
  wall_face.resize(n_wall);
  n_wall = 0;
  for_each_wall([&](std::size_t i, int f) {
    wall_particle[n_wall] = static_cast<std::uint32_t>(i);
    wall_face[n_wall++] = static_cast<std::uint8_t>(f);
  });
  wall_history.assign(wall_particle.size() * hw_, 0.0);
  if (carry && hw_ > 0) {
    std::size_t o = 0;
    for (std::size_t e = 0; e < wall_particle.size(); ++e) {
      const auto key = static_cast<std::uint64_t>(wall_particle[e]) * 8 + wall_face[e];
      while (o < old_wall_particle_.size() &&
             static_cast<std::uint64_t>(old_wall_particle_[o]) * 8 + old_wall_face_[o] < key)
        ++o;
      if (o < old_wall_particle_.size() &&
          static_cast<std::uint64_t>(old_wall_particle_[o]) * 8 + old_wall_face_[o] == key)
        std::copy_n(&old_wall_history_[o * hw_], hw_, &wall_history[e * hw_]);
    }
  }

  // Each particle's entries: its row, its appearances as a partner, its walls.
  count_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) count_[i] = offset[i + 1] - offset[i];
  for (const std::uint32_t j : partner) ++count_[j];
  for (const std::uint32_t i : wall_particle) ++count_[i];
  max_entries_ = n > 0 ? *std::max_element(count_.begin(), count_.end()) : 0;

  x0_ = p.x;
  y0_ = p.y;
  z0_ = p.z;
  ++builds_;
  ++generation_;
  // The previous list is needed only while its history is carried over: released here, so that
  // a run holds one list, not two (the next build allocates its arrays again; builds are rare
  // next to steps, and the history carried over is ~100 bytes per particle). So is the cell
  // grid (~18 bytes per particle), which only the build reads.
  grid_.release();
  release(particle_slab_);
  release(count_);
  release(old_offset_);
  release(old_partner_);
  release(old_history_);
  release(old_wall_particle_);
  release(old_wall_face_);
  release(old_wall_history_);
}

std::size_t NeighbourList::bytes() const {
  auto b = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return b(offset) + b(partner) + b(history) + b(wall_particle) + b(wall_face) + b(wall_history) +
         b(x0_) + b(y0_) + b(z0_) + grid_.bytes() + b(old_offset_) + b(old_partner_) +
         b(old_history_) + b(old_wall_particle_) + b(old_wall_face_) + b(old_wall_history_) +
         b(count_) + b(slab_start) + b(slab_particles) + b(particle_slab_);
}

} // namespace fluidem

namespace fluidem {

NeighbourList::State NeighbourList::state() const {
  State s;
  s.skin = skin_;
  s.builds = builds_;
  s.x0 = x0_;
  s.y0 = y0_;
  s.z0 = z0_;
  s.offset = offset;
  s.partner = partner;
  s.wall_particle = wall_particle;
  s.wall_face = wall_face;
  s.history = history;
  s.wall_history = wall_history;
  return s;
}

void NeighbourList::restore(const ParticleStore& p, const State& s) {
  skin_ = s.skin;
  ++generation_;
  if (s.x0.empty()) { // never built
    builds_ = s.builds;
    return;
  }
  if (s.x0.size() != p.size() || s.y0.size() != p.size() || s.z0.size() != p.size())
    throw std::runtime_error("neighbour list: the restored build positions are for " +
                             std::to_string(s.x0.size()) + " particles, not " +
                             std::to_string(p.size()));
  ParticleStore at_build = p;
  at_build.x = s.x0;
  at_build.y = s.y0;
  at_build.z = s.z0;
  build_with_skin(at_build, nullptr); // the checkpoint's skin, not one chosen again
  if (offset != s.offset || partner != s.partner || wall_particle != s.wall_particle ||
      wall_face != s.wall_face || s.history.size() != history.size() ||
      s.wall_history.size() != wall_history.size())
    throw std::runtime_error("neighbour list: the list rebuilt from the checkpoint's build "
                             "positions differs from the saved one");
  history = s.history;
  wall_history = s.wall_history;
  builds_ = s.builds;
}

} // namespace fluidem
