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
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "contact/contact_table.hpp"
#include "contact/ordered_contacts.hpp"
#include "core/body_force.hpp"
#include "core/noncontact_settings.hpp"
#include "integrate/particle_stepper.hpp"
#include "neighbour/box_geometry.hpp"
#include "neighbour/ordered_rows.hpp"
#include "noncontact/ordered_liquid_bridges.hpp"
#include "parallel/communicator.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/particle_exchange.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// Every particle of a distributed run in id order, with what continues it bitwise (a checkpoint's
/// content): the last contact sums, the per-particle energies and the contact histories keyed by
/// partner id.
struct DistributedState {
  ParticleStore particles;
  std::vector<double> contact;    ///< 12 per particle: f | t | f_nc | t_nc of the last step
  std::vector<double> elastic;    ///< J per particle (a pair's at its lower id)
  std::vector<double> dissipated; ///< J per particle since t = 0
  KeptHistory history;            ///< per particle; empty when not gathered
  /// 3 per particle: its position at the last neighbour-list build (the next build comes when
  /// a particle has moved half the skin from there)
  std::vector<double> x0;
  std::vector<double> held; ///< 3 per particle: the gas force held over the flow step, N
  /// 3 per particle: the torque held over the flow step, N m (Settings::held_torques)
  std::vector<double> held_torque;
  /// Settings::attached_width per particle: what a force source keeps per particle
  std::vector<double> attached;
  /// Per particle: its share of the non-contact forces' potential energy, J (0 without them)
  std::vector<double> noncontact;
  /// With liquid bridges: per particle, its bridges keyed by partner id (-1 - face: a wall),
  /// value 1 (empty when not gathered), and 3 per particle their force of the last step, N
  KeptHistory bridges;
  std::vector<double> bridge_force;
  std::int64_t builds = 0; ///< neighbour-list builds so far
};

class DistributedSoftSphere final : public ParticleStepper {
public:
  struct Settings {
    double dt = 0.0;                   ///< s
    double skin = 0.0;                 ///< m
    std::array<double, 3> gravity{};   ///< m/s^2
    DecompositionGrid cells;           ///< the index space the ranks share out
    std::array<int, 3> process_grid{}; ///< {0, 0, 0}: chosen (columns first)
    /// Load balancing: every this many list builds the cut planes move so that the ranks'
    /// measured contact-loop times even out (0: never).
    int balance_interval = 0;
    /// `[body_force]`: the field's acceleration at each particle's position, beside gravity
    /// (core/body_force.hpp); null: none. Must outlive the engine.
    const BodyForceSpec* body = nullptr;
    /// The conservative non-contact forces (van der Waals, electrostatics), evaluated every step
    /// over rows of their own reach (noncontact/ordered_noncontact.hpp); null: none. Must
    /// outlive the engine.
    const NonContactSpec* noncontact = nullptr;
    /// The liquid bridges, evaluated every step over rows of their own reach
    /// (noncontact/ordered_liquid_bridges.hpp), with the liquid fraction of each species; null:
    /// none. Must outlive the engine.
    const LiquidBridgeSpec* liquid_bridge = nullptr;
    std::vector<double> liquid_fraction;
    /// Torques held over the flow step beside the forces (the fluid torque of
    /// [coupling.forces]).
    bool held_torques = false;
    /// Numbers each particle carries with it from rank to rank for a force source (the
    /// [coupling.forces] state: the Basset history and the last step's impulses), gathered in
    /// its checkpoints; the source reads and writes them through attached().
    int attached_width = 0;
  };
  /// Every rank passes the same particles `all` (each keeps those it owns) and the same
  /// settings; the first contact forces are computed. Collective.
  DistributedSoftSphere(const Communicator& comm, std::unique_ptr<ContactTable> table,
                        const BoxGeometry& box, const Settings& settings, const ParticleStore& all);
  /// The run of a checkpoint: every rank passes the same state (its contact sums are those the
  /// next kick uses: no force is computed). Collective.
  DistributedSoftSphere(const Communicator& comm, std::unique_ptr<ContactTable> table,
                        const BoxGeometry& box, const Settings& settings,
                        const DistributedState& state);

  /// One time step. Collective. Throws InstabilityError (on every rank alike) when a particle
  /// moved farther than the halo or the particle count changed.
  void step();
  void advance(long steps);

  // ParticleStepper (collective: every rank calls them alike).
  /// StepNeeds::record_contacts: the step's touching contacts are recorded, keyed by ids
  /// (gather_contacts()).
  void step(double, const StepNeeds& needs) override {
    record_ = needs.record_contacts;
    step();
  }
  void finish_kick() override {}
  /// As of the last observe().
  double dissipated_energy() const override { return observed_dissipated_; }
  /// The non-contact forces' potential energy at the last observe(), J (root).
  double noncontact_potential() const { return observed_noncontact_; }
  /// As of the last observe(), but max_overlap_ratio as of the last step (every rank's).
  const ContactStats& contact_stats() const override { return observed_stats_; }
  Seconds seconds() const override { return seconds_; }
  std::size_t bytes() const override;

  /// Every particle, sorted by id, on the root (empty elsewhere); their contact histories too
  /// when `with_history`. Collective.
  DistributedState gather(bool with_history = false) const;
  /// The touching contacts of the last step (when it recorded them) of all ranks, each
  /// once (a pair from its lower id's row), on the root in no particular order (empty
  /// elsewhere). Collective.
  std::vector<KeyedContact> gather_contacts() const;
  /// The particles whose positions `keep` accepts, on the root in id order (empty elsewhere).
  /// Collective.
  ParticleStore gather_where(const std::function<bool(const Vec3&)>& keep) const;
  /// This rank's contacts of the last step: its deepest overlap (and the lower id of that
  /// contact), its largest force.
  ContactStats local_stats() const {
    ContactStats s;
    s.n_contacts = stats_.contacts;
    s.max_overlap_ratio = stats_.max_overlap_ratio;
    s.max_overlap_particle = stats_.deepest_id;
    s.max_force2 = stats_.max_force2;
    return s;
  }
  /// Gathers the particles into `all` on the root (in id order; elsewhere emptied) and the
  /// totals of dissipated_energy() and contact_stats() on every rank. Collective.
  void observe(ParticleStore& all);

  /// This rank's own particles (no ghosts), in its local order: what the gas coupling of a
  /// flow step reads (docs/parallel.md).
  void own_particles(ParticleStore& out) const;
  /// The force on each own particle held over the coming flow step, f[axis][i] for the own
  /// particle i (the order of own_particles()), N.
  void hold_own_forces(const std::array<const double*, 3>& f);
  /// The force on each own particle held over the coming flow step (the gas's), from the
  /// forces f[axis][k] on the particles `all` (in id order: a checkpoint's), N.
  void hold_forces(const ParticleStore& all, const std::array<const double*, 3>& f);

  /// The torques held over the coming flow step (Settings::held_torques), as the forces.
  void hold_own_torques(const std::array<const double*, 3>& t);
  void hold_torques(const ParticleStore& all, const std::array<const double*, 3>& t);
  /// The own particles' attached numbers (Settings::attached_width each, in the order of
  /// own_particles()); they travel with their particles.
  std::span<double> attached() { return attached_; }
  /// The attached numbers of the particles `all` (in id order: a checkpoint's), width each.
  void set_attached(const ParticleStore& all, std::span<const double> values);
  /// Adds inertia to every moving particle, own and ghost: 1/m becomes 1/(m + added(d)) (the
  /// added mass of [coupling.forces]; m the particle's mass, d its diameter).
  void add_inertia(const std::function<double(double)>& added);

  /// Moves the cut planes of every cut axis so that each rank's part of the cost is as near the
  /// mean as the cells allow, and migrates the particles to their new owners; the cost of a
  /// particle is 1 + its row's length, times its rank's measured contact time per unit of that
  /// (`measured`), or not (a deterministic balance, for tests). Collective. The results do not
  /// depend on it.
  void rebalance(bool measured);
  /// Rebalances done so far.
  long rebalances() const { return rebalances_; }
  /// Bytes and messages this rank sent to the others since the run (or its restart) started:
  /// particles that changed rank, ghosts, the ghosts' updates (not the gathers for the outputs).
  double bytes_sent() const { return exchange_->bytes_sent() + sent_before_[0]; }
  double messages_sent() const { return exchange_->messages_sent() + sent_before_[1]; }

  /// Totals over all particles, the same bits on every rank and for every P: sums in id order.
  struct Totals {
    double kinetic = 0.0, rotational = 0.0, potential = 0.0; ///< J (potential: gravity's)
    double elastic = 0.0, dissipated = 0.0;                  ///< J
    double noncontact = 0.0; ///< J: the non-contact forces' potential energy
    std::int64_t contacts = 0, particles = 0;
    std::int64_t bridges = 0; ///< liquid bridges (pairs and walls)
    double max_overlap_ratio = 0.0;
  };
  /// Collective.
  Totals totals() const;

  const Decomposition& decomposition() const { return map_; }
  const ParticleStore& local() const { return p_; }
  std::size_t owned() const { return owned_; }
  long builds() const { return builds_; }
  double halo() const { return exchange_->halo(); }

private:
  DistributedSoftSphere(const Communicator& comm, std::unique_ptr<ContactTable> table,
                        const BoxGeometry& box, const Settings& settings, const ParticleStore& all,
                        const DistributedState* state);
  void kick();
  /// A list build: the particles to their owners (through `migration`, or the ghost exchange's
  /// neighbours), then the ghosts and the rows.
  void rebuild(ParticleExchange* migration = nullptr);
  /// The totals of a gathered state (sums on the root, broadcast). Collective.
  Totals totals_of(const DistributedState& g) const;

  const Communicator& comm_;
  std::unique_ptr<ContactTable> table_;
  BoxGeometry box_;
  Settings s_;
  Decomposition map_;
  std::unique_ptr<ParticleExchange> exchange_;
  std::unique_ptr<OrderedRows> rows_;
  std::unique_ptr<OrderedRows> nc_rows_; ///< Settings::noncontact: rows of their reach
  std::vector<double> nc_force_;         ///< 3 per own particle: the non-contact force, N
  std::vector<double> nc_potential_;     ///< per own particle: its share of their potential, J
  /// The non-contact forces of the own particles at their current positions.
  void compute_noncontact();
  std::unique_ptr<OrderedLiquidBridges> bridges_; ///< Settings::liquid_bridge
  std::vector<double> bridge_force_;              ///< 3 per own particle: the bridges' force, N
  /// The liquid bridges of the own particles at their current positions and velocities.
  void compute_bridges();
  /// The own particles' histories: the contacts', then (with bridges) the bridges'.
  std::vector<KeptHistory> keep_histories() const;
  ParticleStore p_; ///< own particles [0, owned_), then ghosts
  std::size_t owned_ = 0;
  std::int64_t total_ = 0;          ///< particles on all ranks
  std::vector<double> dissipated_;  ///< per own particle, J
  std::vector<double> held_;        ///< 3 per own particle: the held (gas) force, N
  std::vector<double> held_torque_; ///< 3 per own particle (Settings::held_torques), N m
  std::vector<double> attached_;    ///< Settings::attached_width per own particle
  /// The per-particle arrays of the own particles that travel with them (migration, gather,
  /// restart), with their widths, in the one order in which their numbers are packed (Self:
  /// this class, const or not).
  template <class Self>
  static auto carried_fields(Self& self);
  /// The same arrays in a gathered state, in that order (null: not kept there, recomputed).
  template <class State>
  static auto state_fields(State& g);
  /// The index k of each own particle in `all` (sorted by id); logic_error if one is missing.
  std::vector<std::size_t> index_in(const ParticleStore& all, const char* what) const;
  std::vector<double> x0_; ///< own particles' positions at the last build (x y z)
  OrderedContactSums sums_;
  OrderedContactStats stats_;
  std::vector<KeyedContact> contacts_; ///< the last step's, when it recorded them
  bool record_ = false;                ///< the next step records its contacts
  long builds_ = 0;
  double observed_dissipated_ = 0.0;
  double observed_noncontact_ = 0.0;
  long rebalances_ = 0;
  std::array<double, 2> sent_before_{}; ///< by the exchanges a rebalance replaced
  double balance_seconds0_ = 0.0;       ///< seconds_.contacts at the last balance
  ContactStats observed_stats_;
  Seconds seconds_;
};

} // namespace fluidem
