// Every partner of each particle, from a half neighbour list (each pair once, under its owner):
// the rows the non-contact forces sum over, each in ascending partner index, so that a
// particle's sum does not depend on which particle owned a pair in the list nor on when the
// list was built; and each particle's wall entries. Rebuilt when the list is.
#pragma once
#include <cstdint>
#include <vector>

#include "neighbour/neighbour_list.hpp"

namespace fluidem {

class PairRows {
public:
  /// Whether the rows belong to the list's current build.
  bool current(const NeighbourList& nl) const { return generation_ == nl.generation(); }
  /// The rows of nl's pairs among n particles.
  void build(const NeighbourList& nl, std::size_t n);
  /// Row i: partner(k) and entry(k) (the pair's index in nl.partner / nl.history) for
  /// k in [begin(i), end(i)).
  std::uint32_t begin(std::size_t i) const { return offset_[i]; }
  std::uint32_t end(std::size_t i) const { return offset_[i + 1]; }
  std::uint32_t partner(std::uint32_t k) const { return partner_[k]; }
  std::uint32_t entry(std::uint32_t k) const { return entry_[k]; }
  /// Particle i's wall entries: [wall_begin(i), wall_end(i)) of nl.wall_particle.
  std::uint32_t wall_begin(std::size_t i) const { return wall_offset_[i]; }
  std::uint32_t wall_end(std::size_t i) const { return wall_offset_[i + 1]; }

private:
  std::vector<std::uint32_t> offset_, partner_, entry_, wall_offset_;
  std::uint64_t generation_ = ~std::uint64_t{0};
};

/// A reorder of the particles (ParticleStore::permute) that the list has not seen yet: several
/// compose into one, applied at the list's next build.
class PendingOrder {
public:
  void add(const std::vector<std::uint32_t>& new_to_old);
  /// Rebuilds nl for p when a particle moved far or the particles were reordered (renumbering
  /// the list, its history carried over); returns whether it did.
  bool update(NeighbourList& nl, const ParticleStore& p);

private:
  bool pending_ = false;
  std::vector<std::uint32_t> new_to_old_;
};

} // namespace fluidem
