// Event-driven hard-sphere engine [Hoomans96 §2-3, Fig. 3; Deen07 §2.1, §4].
// One flow step DT: the particles fly on parabolas under the uniform acceleration (gravity),
// exactly, and collide pairwise, event by event. (Hoomans96 moves them on straight lines and
// applies gravity as one velocity update per DT [Hoomans96 eq. 33]; that changes the velocity
// at each collision by up to g DT and, in a settled bed, pumps energy in at ~M g^2 DT per
// second. Particle-specific forces such as drag are applied outside, once per DT, as in the
// paper.) Pairs fall together, so their relative motion stays a straight line:
//  - neighbour lists bounded by R_a + R_max + 2 v_max DT [Deen07 eq. 44] (here with a safety
//    factor 1.5 and gravity's contribution to the velocity), built from the cell grid with a
//    skin for several steps or for one, whichever is expected to cost less
//    (hardsphere/skin_policy.hpp), and rebuilt when the displacements since the build need it;
//  - pair collision times [Deen07 eq. 45] and wall collision times [Hoomans96 eq. 31]; a fixed
//    particle (ParticleStore::fix) stays where it is, so a pair with one falls apart: its
//    collision time is the first root of a quartic (hardsphere/fixed_partner_time.hpp), and
//    the collision operator takes it as a body of infinite mass (1/m = 1/I = 0), like a wall;
//  - a priority queue holding each particle's earliest event; events made stale by a collision
//    are recognised by per-particle collision counters; lazy particle clocks move only the
//    colliding pair [Deen07 §4];
//  - against inelastic collapse, two rules that switch dissipation off (e_n = 1, smooth): the
//    TC model of Luding & McNamara (1998), for a collision of a particle within tc_time of its
//    previous one, and a low impact speed (normal speed < elastic_below), since the restitution
//    of real spheres tends to 1 at vanishing speed (McNamara & Falcon 2005). With exact gravity
//    the second keeps a bed at rest from cooling into ever faster micro-collisions: its
//    collision rate stays near g / elastic_below per contact.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/case_spec.hpp"
#include "core/nearest_integer.hpp"
#include "hardsphere/collision_operator.hpp"
#include "hardsphere/skin_policy.hpp"
#include "neighbour/cell_grid.hpp"
#include "neighbour/neighbour_list.hpp" // BoxGeometry, NeighbourList::State (checkpoints)
#include "particles/particle_store.hpp"

namespace fluidem {

/// One collision, recorded on request (HardSphereEngine::set_record_collisions) for the
/// collision statistics: particle ids (id_b = -1 - face for a wall) and the contact point.
struct HardSphereCollision {
  std::int64_t id_a = 0, id_b = -1;
  Vec3 point; ///< m (on a periodic axis it may lie one box length outside the domain)
};

struct HardSphereStats {
  long collisions = 0;                ///< cumulative, particle-particle and particle-wall
  long wall_collisions = 0;           ///< cumulative
  long tc_elastic = 0;                ///< cumulative collisions made elastic by the TC model
  long slow_elastic = 0;              ///< ... and by the low-impact-speed rule (elastic_below)
  long events_last_step = 0;          ///< events (valid collisions) in the last DT
  long pair_collisions_last_step = 0; ///< particle-particle collisions in the last DT
  long wall_collisions_last_step = 0; ///< particle-wall collisions in the last DT
  double dissipated = 0.0;            ///< cumulative kinetic energy lost in collisions, J
  double tc_energy_kept = 0.0; ///< cumulative energy both rules kept from being dissipated, J
};

class HardSphereEngine {
public:
  HardSphereEngine(const CaseSpec& spec, const BoxGeometry& box);

  /// Advance the particles over one flow step from `time` to `time + dt` under the uniform
  /// acceleration `accel` (exact parabolic flight). Throws InstabilityError when the events per
  /// particle in one step exceed hardsphere.max_events_per_particle (a stall) or a collision was
  /// missed (overlap).
  void advance(ParticleStore& p, double time, double dt, const std::array<double, 3>& accel);

  const HardSphereStats& stats() const { return stats_; }
  /// Record every collision of the following advance() calls (off by default: nothing stored).
  void set_record_collisions(bool on) { record_ = on; }
  /// The collisions of the last advance() (in event order) when recording is on.
  const std::vector<HardSphereCollision>& last_step_collisions() const { return log_; }
  std::size_t bytes() const;
  long list_builds() const { return list_builds_; }
  /// The skin policy's last probe (hardsphere/skin_policy.hpp).
  const hardsphere::SkinProbe& skin_probe() const { return probe_; }
  /// Fix the skin at `steps` maximal one-step displacements for every following build (0: the
  /// policy chooses, the default). For tests and benchmarks: the particles do not depend on it.
  void set_skin_steps(double steps) { fixed_skin_steps_ = steps; }
  /// The particles were reordered (ParticleStore::permute with the same new_to_old, between
  /// flow steps): the engine's per-particle state and its neighbour list follow them.
  void permute(const std::vector<std::uint32_t>& new_to_old);
  /// Whether the last advance() built the neighbour list.
  bool built_last_step() const { return list_steps_ == 1; }
  /// The side of the cells of the last list build, m (2 R_max + skin).
  double cell_size() const { return cell_size_; }

  /// What a checkpoint keeps between flow steps: the time of each particle's last collision
  /// (TC model), the collision counters, the neighbour list and its build positions, the
  /// statistics.
  struct State {
    std::vector<double> last_collision, built_x, built_y, built_z;
    std::vector<std::uint32_t> counter;
    std::int64_t list_builds = 0;
    HardSphereStats stats;
    NeighbourList::State list;
    hardsphere::SkinProbe skin_probe; ///< the skin policy's last probe (none: build = -1)
    std::int64_t list_steps = 0;      ///< flow steps the current list has served
  };
  State state() const;
  void restore(const ParticleStore& p, const State& s);

private:
  struct Event {
    double t;
    std::uint32_t a, b;   ///< b >= n: wall face b - n
    std::uint32_t ca, cb; ///< collision counters of a and b when scheduled
  };
  static constexpr std::uint32_t kNone = 0xffffffffu; ///< no partner, no calendar slot

  /// The engine's own cell list: every pair (both directions, CSR by particle) closer than
  /// R_i + R_j + skin_ at the positions of `p`. Returns how many of its entries are closer
  /// than R_i + R_j + short_skin, short_skin <= skin_ (for the skin policy's probe).
  std::size_t build_list(const ParticleStore& p, double short_skin = 0.0);
  /// split_ and mirror_ of the rows in full_offset_ / full_partner_, on one thread.
  void link_rows();
  void update_neighbour_list(const ParticleStore& p, double time, double dt);
  /// Minimum-image separation along axis a.
  double min_image(double d, int a) const {
    if (!box_.periodic[a]) return d;
    const double l = box_.length(a);
    return d - l * nearest_integer(d / l);
  }
  /// Kinematics of the hot loops, one cache line per particle: position and velocity at the
  /// particle's clock t (its lazy time, [Deen07 §4]), radius.
  struct alignas(64) Kin {
    double x, y, z, t, vx, vy, vz, r;
  };
  void advance_particle(Kin& k, double a) const;
  /// Time until a particle at distance `gap` from a wall, moving towards it at `u` and
  /// accelerated towards it at `gn`, touches it (infinity if never).
  double wall_time(double gap, double u, double gn) const;
  /// The shortest flight before a particle at rest on a wall (or a fixed particle), pushed
  /// against it, touches it again, s.
  double min_flight() const;
  /// The time at which moving particle a (kinematics ka, at `now` at position xa with velocity
  /// va) meets fixed particle b, on a's parabola (hardsphere/fixed_partner_time.hpp); infinity
  /// if not before the end of the step.
  double fixed_pair_time(const Kin& ka, const Vec3& xa, const Vec3& va, const Kin& kb,
                         double now) const;
  /// The earliest event of particle i after `now` (before the end of the step); partner
  /// kNone if none. Reads only, so it may run for many particles at once.
  Event predict(const ParticleStore& p, std::uint32_t i, double now) const;
  void schedule(const ParticleStore& p, std::uint32_t i, double now);
  /// The earliest wall event of a particle at xi, vi (time `now`) if before `best`.
  void wall_event(const Kin& ki, const Vec3& xi, const Vec3& vi, double now, double& best,
                  std::uint32_t& partner) const;
  /// Every particle's first event at the start of a step (all clocks at `now`), into next_.
  void first_events(double now);
  void process(ParticleStore& p, const Event& ev);
  /// The calendar: a binary heap of particles by the time of their current event.
  struct QueueEntry {
    double t;        ///< next_[i].t
    std::uint32_t i; ///< the particle
  };
  static constexpr std::uint32_t kArity = 2;
  static bool earlier(const QueueEntry& a, const QueueEntry& b);
  void sift_up(std::uint32_t k);
  void sift_down(std::uint32_t k);
  /// Make ev the current event of particle ev.a (ev.b == kNone: it has none).
  void set_event(const Event& ev);
  /// Flight to the end of the step, copy out, overlap check (InstabilityError on an overlap).
  void finish_step(ParticleStore& p);

  int dimension_;
  int nspecies_;
  std::vector<hardsphere::CollisionLaw> pair_law_, wall_law_;
  HardSphereSpec opts_;
  BoxGeometry box_;
  double skin_ = 0.0;
  double cell_size_ = 0.0;        ///< of the last build
  hardsphere::SkinProbe probe_;   ///< the list sizes of the last build with the long skin
  std::int64_t list_steps_ = 0;   ///< flow steps the current list has served
  double fixed_skin_steps_ = 0.0; ///< set_skin_steps (0: the policy)
  // Cell grid of the last build and the full list (CSR: the partners of i are
  // full_partner_[full_offset_[i] .. full_offset_[i + 1])).
  CellGrid grid_;
  std::vector<std::uint32_t> full_offset_, full_partner_;
  std::vector<std::uint32_t> split_, mirror_; ///< first entry above i; the entry (j, i) of (i, j)
  std::vector<std::uint32_t> mirror_cursor_;  ///< build_list, link_rows: per row, its next
                                              ///< entry below the split to fill
  std::vector<double> pair_time_;             ///< per entry above the split: the pair's time
  std::vector<std::vector<std::uint32_t>> thread_rows_; ///< per thread during a build: the
                                                        ///< rows' parts above their particles
  std::vector<Kin> kin_; ///< copied in at the start of a step, out at its end
  /// Per particle: fixed (ParticleStore::fix: never moves, infinite mass); whether any is, and
  /// how many are not (copied in with kin_).
  std::vector<unsigned char> fixed_;
  bool any_fixed_ = false;
  std::size_t moving_ = 0;
  std::vector<double> last_collision_;
  std::vector<std::uint32_t> counter_;
  std::vector<Event> next_;         ///< per particle: its current event
  std::vector<QueueEntry> queue_;   ///< the calendar: particles with an event, a heap
  std::vector<std::uint32_t> slot_; ///< per particle: its place in queue_, or kNone
  std::vector<double> built_x_, built_y_, built_z_; ///< positions at the last list build
  long list_builds_ = 0;
  Vec3 g_;
  double t_end_ = 0.0, step_dt_ = 0.0, elastic_below_ = 0.0, rmin_ = 0.0;
  HardSphereStats stats_;
  bool record_ = false;
  std::vector<HardSphereCollision> log_;
};

} // namespace fluidem
