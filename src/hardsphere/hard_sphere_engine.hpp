// Event-driven hard-sphere engine [Hoomans96 §2-3, Fig. 3; Deen07 §2.1, §4].
// One flow step DT: external accelerations (gravity, later drag) change the velocities in two
// half kicks around the collision sequence (kick-drift-kick, so that free flight under gravity
// is exact at the DT boundaries; [Hoomans96 eq. 33] applies the whole kick at once); between the
// kicks the particles fly straight and collide pairwise, event by event:
//  - neighbour lists bounded by R_a + R_max + 2 v_max DT [Deen07 eq. 44] (here with a safety
//    factor 1.5 on the velocity term), rebuilt from the cell grid every DT;
//  - pair collision times [Deen07 eq. 45] and wall collision times [Hoomans96 eq. 31];
//  - a priority queue holding each particle's earliest event; events made stale by a collision
//    are recognised by per-particle collision counters; lazy particle clocks move only the
//    colliding pair [Deen07 §4];
//  - the TC model of Luding & McNamara (1998) against inelastic collapse: a collision of a
//    particle within tc_time of its previous one is elastic in the normal direction.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/case_spec.hpp"
#include "hardsphere/collision_operator.hpp"
#include "neighbour/neighbour_list.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

struct HardSphereStats {
  long collisions = 0;         ///< cumulative, particle-particle and particle-wall
  long wall_collisions = 0;    ///< cumulative
  long tc_elastic = 0;         ///< cumulative collisions made elastic by the TC model
  long events_last_step = 0;   ///< events (valid collisions) in the last DT
  double dissipated = 0.0;     ///< cumulative kinetic energy lost in collisions, J
  double tc_energy_kept = 0.0; ///< cumulative energy the TC model kept from being dissipated, J
};

class HardSphereEngine {
public:
  HardSphereEngine(const CaseSpec& spec, const BoxGeometry& box);

  /// Advance the particles over one flow step from `time` to `time + dt` under the uniform
  /// acceleration `accel`. Throws InstabilityError when the events per particle in one step
  /// exceed hardsphere.max_events_per_particle (a stall) or a collision was missed (overlap).
  void advance(ParticleStore& p, double time, double dt, const std::array<double, 3>& accel);

  const HardSphereStats& stats() const { return stats_; }
  std::size_t bytes() const;

private:
  struct Event {
    double t;
    std::uint32_t a, b;   ///< b >= n: wall face b - n
    std::uint32_t ca, cb; ///< collision counters of a and b when scheduled
  };
  struct Later {
    bool operator()(const Event& x, const Event& y) const { return x.t > y.t; }
  };

  void build_full_list(const ParticleStore& p);
  void schedule(const ParticleStore& p, std::uint32_t i, double now);
  void process(ParticleStore& p, const Event& ev);
  void push(const Event& ev);
  void check_no_overlap(const ParticleStore& p, double time) const;

  int dimension_;
  int nspecies_;
  std::vector<hardsphere::CollisionLaw> pair_law_, wall_law_;
  HardSphereSpec opts_;
  NeighbourList nl_;
  std::vector<std::uint32_t> full_offset_, full_partner_;
  std::vector<double> clock_, last_collision_;
  std::vector<std::uint32_t> counter_;
  std::vector<Event> heap_;
  double t_end_ = 0.0;
  HardSphereStats stats_;
};

} // namespace fluidem
