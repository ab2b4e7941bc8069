// The soft-sphere DEM on P MPI ranks (one rank included), with results that do not depend on P,
// on the decomposition or on the thread count, bitwise (docs/parallel.md). Each rank steps the
// particles whose centres lie in its cells (Decomposition) with velocity Verlet; the contact
// forces come from the rank-independent loop (contact/ordered_contacts.hpp) over its own
// particles and the ghosts of its neighbours. At each neighbour-list build (a particle moved
// half the skin) the particles migrate to their owners with their contact histories (keyed by
// partner id) and accumulators, and the ghosts are sent again; between builds only the ghosts'
// positions and velocities travel. Quantities summed over particles (energies) are summed in
// particle-id order on the root, from per-particle values.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "contact/contact_table.hpp"
#include "contact/ordered_contacts.hpp"
#include "neighbour/box_geometry.hpp"
#include "neighbour/ordered_rows.hpp"
#include "parallel/communicator.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/particle_exchange.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

class DistributedSoftSphere {
public:
  struct Settings {
    double dt = 0.0;                   ///< s
    double skin = 0.0;                 ///< m
    std::array<double, 3> gravity{};   ///< m/s^2
    DecompositionGrid cells;           ///< the index space the ranks share out
    std::array<int, 3> process_grid{}; ///< {0, 0, 0}: chosen (columns first)
  };
  /// Every rank passes the same particles `all` (each keeps those it owns) and the same
  /// settings. Collective.
  DistributedSoftSphere(const Communicator& comm, std::unique_ptr<ContactTable> table,
                        const BoxGeometry& box, const Settings& settings, const ParticleStore& all);

  /// One time step. Collective. Throws InstabilityError (on every rank alike) when a particle
  /// moved farther than the halo or the particle count changed.
  void step();
  void advance(long steps);

  /// Every particle, sorted by id, on the root (empty elsewhere), with their accumulators.
  struct Gathered {
    ParticleStore particles;
    std::vector<double> dissipated, elastic; ///< J per particle (a pair's elastic: lower id)
  };
  Gathered gather() const;

  /// Totals over all particles, the same bits on every rank and for every P: sums in id order.
  struct Totals {
    double kinetic = 0.0, rotational = 0.0, potential = 0.0; ///< J (potential: gravity's)
    double elastic = 0.0, dissipated = 0.0;                  ///< J
    std::int64_t contacts = 0, particles = 0;
    double max_overlap_ratio = 0.0;
  };
  Totals totals() const;

  const Decomposition& decomposition() const { return map_; }
  const ParticleStore& local() const { return p_; }
  std::size_t owned() const { return owned_; }
  long builds() const { return builds_; }
  double halo() const { return exchange_->halo(); }

private:
  void kick();
  void rebuild();

  const Communicator& comm_;
  std::unique_ptr<ContactTable> table_;
  BoxGeometry box_;
  Settings s_;
  Decomposition map_;
  std::unique_ptr<ParticleExchange> exchange_;
  std::unique_ptr<OrderedRows> rows_;
  ParticleStore p_; ///< own particles [0, owned_), then ghosts
  std::size_t owned_ = 0;
  std::int64_t total_ = 0;         ///< particles on all ranks
  std::vector<double> dissipated_; ///< per own particle, J
  std::vector<double> x0_;         ///< own particles' positions at the last build (x y z)
  OrderedContactSums sums_;
  OrderedContactStats stats_;
  long builds_ = 0;
  bool moved_far_ = false;
  std::int64_t too_far_ = -1; ///< a particle that moved beyond the halo since the build
};

} // namespace fluidem
