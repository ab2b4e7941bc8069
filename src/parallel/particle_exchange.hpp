// Particles between ranks (docs/parallel.md): at a neighbour-list build, each own particle moves
// to the rank whose cells hold its centre (migration), with its contact histories (keyed by
// partner id) and its per-particle accumulators; then every rank receives copies (ghosts) of
// the other ranks' particles within the halo of its box. Between builds the ghosts' positions
// and velocities are refreshed from their owners in the same order. No physics: records of
// numbers, moved.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "neighbour/ordered_rows.hpp"
#include "parallel/communicator.hpp"
#include "parallel/decomposition.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// A particle's owner is not a neighbour of the rank that held it: it moved farther than the
/// halo in one list's life (an unstable run); names the particle.
struct ParticleTooFar {
  std::int64_t id = -1;
  double x = 0.0, y = 0.0, z = 0.0;
};

/// The first n particles of p, each with `width` doubles of `extra`, as bytes; and back
/// (appended to p and extra).
std::vector<char> pack_particles(const ParticleStore& p, std::size_t n,
                                 std::span<const double> extra, int width);
void unpack_particles(const std::vector<char>& bytes, ParticleStore& p, std::vector<double>& extra,
                      int width);

/// Contact histories as bytes (and back, appended as further particles' entries to `kept`).
std::vector<char> pack_history(const KeptHistory& kept);
void unpack_history(const std::vector<char>& bytes, KeptHistory& kept);

class ParticleExchange {
public:
  /// halo: the ghosts' reach beyond a box, m (the list's cut-off for the largest pair).
  ParticleExchange(const Communicator& comm, const Decomposition& map, double halo);

  /// Moves each particle of p (own particles only: no ghosts) to the rank that owns its centre,
  /// with its histories (kept: one entry list per particle of p) and `width` doubles per particle
  /// of `extra`. The rank keeps its staying particles in their order, then appends the arrivals
  /// (by source rank, in the sender's order). Returns the particles that went to a rank that is
  /// not a neighbour (they are not moved; empty on success).
  /// Several histories (`kept`, each one entry list per particle of p: the contacts', the liquid
  /// bridges') travel alike.
  std::vector<ParticleTooFar> migrate(ParticleStore& p, std::span<KeptHistory* const> kept,
                                      std::vector<double>& extra, int width);
  /// Appends to p (own particles only) the ghosts of the neighbours within the halo of this
  /// rank's box, remembering what went where for update_ghosts.
  void fill_ghosts(ParticleStore& p);
  /// The ghosts' positions and velocities from their owners (p: own particles, then the ghosts of
  /// the last fill_ghosts).
  void update_ghosts(ParticleStore& p, std::size_t owned);
  /// One number per particle of the store (own particles, then the ghosts of the last
  /// fill_ghosts): the ghosts' from their owners.
  void update_ghost_values(std::vector<double>& values, std::size_t owned);

  /// Bytes and messages this rank sent since it was made (migrations, ghost fills and updates).
  double bytes_sent() const { return bytes_total_; }
  double messages_sent() const { return messages_total_; }
  const std::vector<int>& neighbours() const { return neighbours_; }
  double halo() const { return halo_; }

private:
  const Communicator& comm_;
  const Decomposition& map_;
  double halo_;
  std::vector<int> neighbours_;
  /// Per neighbour: the own particles sent as ghosts at the last fill (indices into p).
  std::vector<std::vector<std::uint32_t>> sent_;
  /// Per neighbour: how many ghosts came from it (in neighbour order after the own particles).
  std::vector<std::size_t> received_;
  double bytes_total_ = 0.0, messages_total_ = 0.0;
  /// Counts what out_ holds (the payloads of one exchange) as sent.
  void count_sent();
  std::vector<std::vector<char>> out_;
};

} // namespace fluidem
