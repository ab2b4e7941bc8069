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

NeighbourList::NeighbourList(const BoxGeometry& box, double skin, int history_width)
    : box_(box), skin_(skin), hw_(history_width) {}

bool NeighbourList::needs_rebuild(const ParticleStore& p) const {
  const std::size_t n = p.size();
  if (!built_for(n)) return true;
  return parallel_any(n, threaded_particles(n),
                      [&](std::size_t i) { return moved_far(i, p.x[i], p.y[i], p.z[i]); });
}

std::array<int, 3> grid_cells(const BoxGeometry& box, double cell_size) {
  std::array<int, 3> n{};
  for (int a = 0; a < 3; ++a) // (in double first: a tiny cell would overflow the int)
    n[a] = static_cast<int>(std::clamp(std::floor(box.length(a) / cell_size), 1.0, 1048576.0));
  return n;
}

void NeighbourList::build_cells(const ParticleStore& p, double cell_size) {
  const std::size_t n = p.size();
  ncell_ = grid_cells(box_, cell_size);
  for (int a = 0; a < 3; ++a) inv_cell_[a] = ncell_[a] / box_.length(a);
  const std::size_t ncells = static_cast<std::size_t>(ncell_[0]) * ncell_[1] * ncell_[2];
  particle_cell_.resize(n);
  const std::array<const std::vector<double>*, 3> pos{&p.x, &p.y, &p.z};
  parallel_for(n, threaded_particles(n), [&](std::size_t i) {
    std::array<int, 3> c{};
    for (int a = 0; a < 3; ++a) {
      double rel = (*pos[a])[i] - box_.lo[a];
      if (box_.periodic[a]) rel -= box_.length(a) * std::floor(rel / box_.length(a));
      c[a] = std::clamp(static_cast<int>(rel * inv_cell_[a]), 0, ncell_[a] - 1);
    }
    particle_cell_[i] = static_cast<std::uint32_t>((c[2] * ncell_[1] + c[1]) * ncell_[0] + c[0]);
  });
  // Counting sort, stable: particles of a cell in ascending index order.
  cell_start_.assign(ncells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++cell_start_[particle_cell_[i] + 1];
  for (std::size_t c = 0; c < ncells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_particles_.resize(n);
  count_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    cell_particles_[count_[particle_cell_[i]]++] = static_cast<std::uint32_t>(i);
}

double NeighbourList::cell_size(const ParticleStore& p) const {
  double rmax = 0.0;
  for (const double r : p.radius) rmax = std::max(rmax, r);
  return 2.0 * rmax + skin_;
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
  const std::size_t n = p.size();
  build_cells(p, cell_size(p));

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

  // Slabs along the axis over which the particles spread across the most cells.
  {
    std::array<std::uint32_t, 3> cmin{~0u, ~0u, ~0u}, cmax{0, 0, 0};
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t c = particle_cell_[i];
      const std::array<std::uint32_t, 3> q{c % ncell_[0], (c / ncell_[0]) % ncell_[1],
                                           c / (static_cast<std::uint32_t>(ncell_[0]) * ncell_[1])};
      for (int a = 0; a < 3; ++a)
        cmin[a] = std::min(cmin[a], q[a]), cmax[a] = std::max(cmax[a], q[a]);
    }
    slab_axis_ = n > 0 ? slab_axis(cmin, cmax) : 0; // the rule spatial_order follows too
    nslab_ = ncell_[slab_axis_];
    // A periodic axis gets an even number of slabs (the last slab neighbours slab 0): the last
    // cell then joins the slab before it. (The contact loop's even/odd slab phases needed it;
    // its groups of two or more slabs do not, but the slabs decide which particle owns a pair,
    // and a checkpoint's list is verified against the pairs rebuilt from it.)
    if (box_.periodic[slab_axis_] && nslab_ > 1 && nslab_ % 2 == 1) --nslab_;
    particle_slab_.resize(n);
    const std::uint32_t stride =
        slab_axis_ == 0 ? 1u
                        : (slab_axis_ == 1 ? static_cast<std::uint32_t>(ncell_[0])
                                           : static_cast<std::uint32_t>(ncell_[0] * ncell_[1]));
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t q = (particle_cell_[i] / stride) % ncell_[slab_axis_];
      particle_slab_[i] = std::min(q, static_cast<std::uint32_t>(nslab_ - 1));
    }
    slab_start.assign(nslab_ + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++slab_start[particle_slab_[i] + 1];
    for (int k = 0; k < nslab_; ++k) slab_start[k + 1] += slab_start[k];
    slab_particles.resize(n);
    count_.assign(slab_start.begin(), slab_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      slab_particles[count_[particle_slab_[i]]++] = static_cast<std::uint32_t>(i);
  }
  const bool periodic_slabs = box_.periodic[slab_axis_];
  // Owner of a pair: the particle whose slab is followed by the other's; within a slab the
  // lower index. (With two periodic slabs each follows the other: the lower slab owns.)
  auto owns = [&](std::uint32_t i, std::uint32_t j) {
    const std::uint32_t si = particle_slab_[i], sj = particle_slab_[j];
    if (si == sj) return i < j;
    const auto next = [&](std::uint32_t sl) {
      return periodic_slabs ? (sl + 1) % static_cast<std::uint32_t>(nslab_) : sl + 1;
    };
    if (sj == next(si) && si == next(sj)) return si < sj;
    return sj == next(si);
  };

  // Neighbour cells of each cell, deduplicated (periodic axes with fewer than 3 cells). Two
  // fixed particles (ParticleStore::fix) never interact: no pair of them.
  auto for_each_partner = [&](std::size_t i, auto&& visit) {
    const bool fixed_i = p.fixed(i);
    for_each_cell_around(particle_cell_[i], ncell_, box_.periodic, [&](std::uint32_t cell) {
      for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
        const std::uint32_t j = cell_particles_[k];
        if (j == i || !owns(static_cast<std::uint32_t>(i), j)) continue;
        if (fixed_i && p.fixed(j)) continue;
        const double dxp = min_image(p.x[j] - p.x[i], 0);
        const double dyp = min_image(p.y[j] - p.y[i], 1);
        const double dzp = min_image(p.z[j] - p.z[i], 2);
        const double cut = p.radius[i] + p.radius[j] + skin_;
        if (dxp * dxp + dyp * dyp + dzp * dzp < cut * cut) visit(j);
      }
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
        if (gap < p.radius[i] + skin_) visit(i, f);
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
  release(cell_start_);
  release(cell_particles_);
  release(particle_cell_);
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
         b(x0_) + b(y0_) + b(z0_) + b(cell_start_) + b(cell_particles_) + b(particle_cell_) +
         b(old_offset_) + b(old_partner_) + b(old_history_) + b(old_wall_particle_) +
         b(old_wall_face_) + b(old_wall_history_) + b(count_) + b(slab_start) + b(slab_particles) +
         b(particle_slab_);
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
  build(at_build);
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
