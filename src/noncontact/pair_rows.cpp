#include "noncontact/pair_rows.hpp"

#include <algorithm>
#include <numeric>

#include "core/parallel.hpp"

namespace fluidem {

void PairRows::build(const NeighbourList& nl, std::size_t n) {
  const auto& off = nl.offset;
  const auto& partner = nl.partner;
  offset_.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t e = off[i]; e < off[i + 1]; ++e) ++offset_[i + 1], ++offset_[partner[e] + 1];
  for (std::size_t i = 0; i < n; ++i) offset_[i + 1] += offset_[i];
  partner_.resize(offset_[n]);
  entry_.resize(offset_[n]);
  std::vector<std::uint32_t> fill(offset_.begin(), offset_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t e = off[i]; e < off[i + 1]; ++e) {
      const std::uint32_t j = partner[e];
      partner_[fill[i]] = j, entry_[fill[i]++] = e;
      partner_[fill[j]] = static_cast<std::uint32_t>(i), entry_[fill[j]++] = e;
    }
  // Ascending partner index (a pair is in a row once): the order of a particle's sum.
  parallel_for(n, threaded_particles(n), [&](std::size_t i) {
    const std::uint32_t b = offset_[i], e = offset_[i + 1];
    std::vector<std::uint32_t> order(e - b);
    std::iota(order.begin(), order.end(), b);
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t x, std::uint32_t y) { return partner_[x] < partner_[y]; });
    std::vector<std::uint32_t> p(e - b), en(e - b);
    for (std::size_t k = 0; k < order.size(); ++k)
      p[k] = partner_[order[k]], en[k] = entry_[order[k]];
    std::copy(p.begin(), p.end(), partner_.begin() + b);
    std::copy(en.begin(), en.end(), entry_.begin() + b);
  });
  wall_offset_.assign(n + 1, 0);
  for (const std::uint32_t i : nl.wall_particle) ++wall_offset_[i + 1];
  for (std::size_t i = 0; i < n; ++i) wall_offset_[i + 1] += wall_offset_[i];
  generation_ = nl.generation();
}

void PendingOrder::add(const std::vector<std::uint32_t>& new_to_old) {
  if (pending_) { // two reorders before a build: compose them
    std::vector<std::uint32_t> composed(new_to_old.size());
    for (std::size_t k = 0; k < new_to_old.size(); ++k) composed[k] = new_to_old_[new_to_old[k]];
    new_to_old_ = std::move(composed);
  } else {
    new_to_old_ = new_to_old;
  }
  pending_ = true;
}

bool PendingOrder::update(NeighbourList& nl, const ParticleStore& p) {
  const bool reorder = pending_;
  pending_ = false;
  if (reorder && nl.built_for(p.size())) {
    nl.build(p, &new_to_old_);
    return true;
  }
  if (reorder || nl.needs_rebuild(p)) {
    nl.build(p);
    return true;
  }
  return false;
}

} // namespace fluidem
