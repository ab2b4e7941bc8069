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

/// The minimum-image vector from particle i's centre to particle j's, m.
inline Vec3 centre_to_centre(const NeighbourList& nl, const ParticleStore& p, std::size_t i,
                             std::size_t j) {
  return {nl.min_image(p.x[j] - p.x[i], 0), nl.min_image(p.y[j] - p.y[i], 1),
          nl.min_image(p.z[j] - p.z[i], 2)};
}

/// Particle i and the wall of face f (0..5: x_lo, x_hi, ...): the distance of its centre from
/// the wall, m, and the unit normal from the particle towards the wall (along `axis`).
struct WallDistance {
  double centre;
  Vec3 normal;
  int axis;
};
inline WallDistance wall_distance(const BoxGeometry& box, const ParticleStore& p, std::size_t i,
                                  int face) {
  const int a = face / 2;
  const bool low = face % 2 == 0;
  const double x = a == 0 ? p.x[i] : a == 1 ? p.y[i] : p.z[i];
  WallDistance w{low ? x - box.lo[a] : box.hi[a] - x, {}, a};
  w.normal[a] = low ? -1.0 : 1.0;
  return w;
}

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
