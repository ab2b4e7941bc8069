// Neighbour rows for the rank-independent contact loop (contact/ordered_contacts.hpp): a full
// list (each pair in the rows of both its particles) of a rank's own particles, each row in
// ascending partner id, its history kept per (particle, partner id). A particle's row and its
// history are then the same whichever rank holds it, and whatever else that rank holds
// (docs/parallel.md). The store's first `owned` particles are the rank's own, the others
// ghosts (copies of other ranks' particles near its cells): rows are built for the own ones.
#pragma once
#include <cstdint>
#include <vector>

#include "core/nearest_integer.hpp"
#include "neighbour/box_geometry.hpp"
#include "neighbour/cell_grid.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// The contact histories a rank's own particles hold, detached from the rows (to travel with
/// their particles to another rank, or into a checkpoint): per particle, its loaded (nonzero)
/// entries in ascending key, the key a partner's id or -1 - face for a wall.
struct KeptHistory {
  int width = 0;                     ///< doubles per entry
  std::vector<std::uint32_t> offset; ///< per particle, into key (size particles + 1)
  std::vector<std::int64_t> key;
  std::vector<double> values; ///< width per entry
  std::size_t particles() const { return offset.empty() ? 0 : offset.size() - 1; }
};

/// The histories of particles order[0], order[1], ... of `kept`, in that order.
KeptHistory reorder(const KeptHistory& kept, const std::vector<std::uint32_t>& order);

class OrderedRows {
public:
  /// history_width: doubles per contact; reach: the interaction's range beyond contact, m.
  OrderedRows(const BoxGeometry& box, int history_width, double reach);

  /// Rows of the first `owned` particles of p: every particle j != i of p (own or ghost) whose
  /// surface gap is below reach + skin (min image on periodic axes), no pair of two fixed
  /// particles; wall entries for the faces with a wall within reach + skin. Their histories from
  /// `kept` (particle k of kept is own particle k; empty: none).
  void build(const ParticleStore& p, std::size_t owned, double skin, const KeptHistory& kept);
  /// The loaded histories of the rows, per own particle (p: the store the rows were built on).
  KeptHistory keep(const ParticleStore& p) const;

  /// Minimum-image separation component along axis a (the same formula everywhere; odd in d).
  double min_image(double d, int a) const {
    if (!box_.periodic[a]) return d;
    const double l = box_.length(a);
    return d - l * nearest_integer(d / l);
  }
  const BoxGeometry& box() const { return box_; }
  int history_width() const { return hw_; }
  double reach() const { return reach_; }
  double skin() const { return skin_; }
  std::size_t owned() const { return offset.empty() ? 0 : offset.size() - 1; }

  // Pair rows (CSR by own particle), partners as indices into the store, ascending id.
  std::vector<std::uint32_t> offset, partner;
  std::vector<double> history; ///< width per entry, seen from the lower id of the pair
  // Wall rows (CSR by own particle), faces ascending.
  std::vector<std::uint32_t> wall_offset;
  std::vector<std::uint8_t> wall_face;
  std::vector<double> wall_history;

private:
  BoxGeometry box_;
  int hw_ = 0;
  double reach_ = 0.0, skin_ = 0.0;
  CellGrid grid_;
};

} // namespace fluidem
