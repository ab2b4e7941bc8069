#include "neighbour/ordered_rows.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/nearest_integer.hpp"
#include "core/parallel.hpp"

namespace fluidem {

KeptHistory reorder(const KeptHistory& kept, const std::vector<std::uint32_t>& order) {
  KeptHistory out;
  out.width = kept.width;
  out.offset.assign(1, 0);
  const auto hw = static_cast<std::size_t>(kept.width);
  for (const std::uint32_t i : order) {
    for (std::uint32_t m = kept.offset[i]; m < kept.offset[i + 1]; ++m) {
      out.key.push_back(kept.key[m]);
      out.values.insert(out.values.end(), kept.values.begin() + static_cast<std::ptrdiff_t>(m * hw),
                        kept.values.begin() + static_cast<std::ptrdiff_t>((m + 1) * hw));
    }
    out.offset.push_back(static_cast<std::uint32_t>(out.key.size()));
  }
  return out;
}

OrderedRows::OrderedRows(const BoxGeometry& box, int history_width, double reach)
    : box_(box), hw_(history_width), reach_(reach) {}

void OrderedRows::build(const ParticleStore& p, std::size_t owned, double skin,
                        const KeptHistory& kept) {
  if (!kept.offset.empty() && kept.particles() != owned)
    throw std::logic_error("OrderedRows::build: the kept histories are not the own particles'");
  if (!kept.offset.empty() && kept.width != hw_)
    throw std::logic_error("OrderedRows::build: kept histories of another width");
  skin_ = skin;
  const std::size_t n = p.size();
  double r_max = 0.0;
  for (const double r : p.radius) r_max = std::max(r_max, r);
  grid_.bin(box_, 2.0 * r_max + reach_ + skin_, p.x.data(), p.y.data(), p.z.data(), n, false);
  const bool threaded = threaded_particles(owned);

  // Row i: the partners within reach + skin of contact, ascending id (one order whatever the
  // store's order and whatever else the store holds).
  std::vector<std::vector<std::uint32_t>> rows(owned);
  parallel_for(owned, threaded, [&](std::size_t i) {
    std::vector<std::uint32_t>& row = rows[i];
    const bool fixed_i = p.fixed(i);
    grid_.for_each_near(i, box_.periodic, [&](std::uint32_t j) {
      if (j == i || (fixed_i && p.fixed(j))) return;
      const double dx = min_image(p.x[j] - p.x[i], 0);
      const double dy = min_image(p.y[j] - p.y[i], 1);
      const double dz = min_image(p.z[j] - p.z[i], 2);
      const double cut = p.radius[i] + p.radius[j] + reach_ + skin_;
      if (dx * dx + dy * dy + dz * dz < cut * cut) row.push_back(j);
    });
    std::sort(row.begin(), row.end(),
              [&](std::uint32_t a, std::uint32_t b) { return p.id[a] < p.id[b]; });
  });
  offset.assign(owned + 1, 0);
  for (std::size_t i = 0; i < owned; ++i)
    offset[i + 1] = offset[i] + static_cast<std::uint32_t>(rows[i].size());
  partner.resize(offset[owned]);
  history.assign(static_cast<std::size_t>(offset[owned]) * static_cast<std::size_t>(hw_), 0.0);
  const auto hw = static_cast<std::size_t>(hw_);
  parallel_for(owned, threaded, [&](std::size_t i) {
    std::copy(rows[i].begin(), rows[i].end(), partner.begin() + offset[i]);
    if (kept.offset.empty() || hw == 0) return;
    // Both sorted by id: one merge.
    std::uint32_t k = kept.offset[i];
    const std::uint32_t k_end = kept.offset[i + 1];
    for (std::uint32_t e = offset[i]; e < offset[i + 1] && k < k_end; ++e) {
      const std::int64_t id = p.id[partner[e]];
      while (k < k_end && kept.key[k] < id) ++k;
      if (k < k_end && kept.key[k] == id)
        std::copy_n(&kept.values[k * hw], hw, &history[static_cast<std::size_t>(e) * hw]);
    }
  });

  // Walls: the faces within reach + skin, ascending; none for a fixed particle.
  const std::array<const std::vector<double>*, 3> pos{&p.x, &p.y, &p.z};
  wall_offset.assign(owned + 1, 0);
  wall_face.clear();
  for (std::size_t i = 0; i < owned; ++i) {
    if (!p.fixed(i))
      for (int f = 0; f < 6; ++f) {
        if (!box_.wall[f]) continue;
        const int a = f / 2;
        const double gap = (f % 2 == 0) ? (*pos[a])[i] - box_.lo[a] : box_.hi[a] - (*pos[a])[i];
        if (gap < p.radius[i] + reach_ + skin_) wall_face.push_back(static_cast<std::uint8_t>(f));
      }
    wall_offset[i + 1] = static_cast<std::uint32_t>(wall_face.size());
  }
  wall_history.assign(wall_face.size() * hw, 0.0);
  if (kept.offset.empty() || hw == 0) return;
  for (std::size_t i = 0; i < owned; ++i)
    for (std::uint32_t e = wall_offset[i]; e < wall_offset[i + 1]; ++e)
      for (std::uint32_t k = kept.offset[i]; k < kept.offset[i + 1]; ++k)
        if (kept.key[k] == -1 - static_cast<std::int64_t>(wall_face[e]))
          std::copy_n(&kept.values[k * hw], hw, &wall_history[static_cast<std::size_t>(e) * hw]);
}

KeptHistory OrderedRows::keep(const ParticleStore& p) const {
  KeptHistory k;
  k.width = hw_;
  const std::size_t n = owned();
  const auto hw = static_cast<std::size_t>(hw_);
  k.offset.assign(n + 1, 0);
  const auto loaded = [&](const double* h) {
    for (std::size_t m = 0; m < hw; ++m)
      if (h[m] != 0.0) return true;
    return false;
  };
  // Walls (keys -6 .. -1, in descending face) first, then pairs (ids >= 0): ascending keys.
  for (std::size_t i = 0; i < n; ++i) {
    for (std::uint32_t e = wall_offset[i + 1]; e-- > wall_offset[i];) {
      const double* h = &wall_history[e * hw];
      if (hw == 0 || !loaded(h)) continue;
      k.key.push_back(-1 - static_cast<std::int64_t>(wall_face[e]));
      k.values.insert(k.values.end(), h, h + hw);
    }
    for (std::uint32_t e = offset[i]; e < offset[i + 1]; ++e) {
      const double* h = &history[e * hw];
      if (hw == 0 || !loaded(h)) continue;
      k.key.push_back(p.id[partner[e]]);
      k.values.insert(k.values.end(), h, h + hw);
    }
    k.offset[i + 1] = static_cast<std::uint32_t>(k.key.size());
  }
  return k;
}

} // namespace fluidem
