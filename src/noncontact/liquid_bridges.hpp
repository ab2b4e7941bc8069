// Pendular liquid bridges between wet particles and between particles and walls [Zhu07 §2.2,
// Table 2]: the capillary force of Willett et al. (2000) and the viscous force of the bridge
// liquid (noncontact/kernels/liquid_bridge.hpp), with the liquid rule of Yang et al. (2003):
// each particle's liquid is shared evenly among its bridges, not transferred.
// A bridge forms when two particles (or a particle and a wall) touch, and ruptures once their
// gap reaches the rupture distance S_c of its volume (Lian et al. 1993): the bridges are state,
// kept as one value per entry of a neighbour list of their own (its reach: the longest rupture
// distance) and carried over its rebuilds and in checkpoints.
// Each step: bridges form (touching entries), every particle counts its bridges, bridges whose
// gap reached their S_c (with those counts) rupture, the particles count again, and each
// particle sums the forces of its bridges over its partners in ascending index, then its walls:
// the same with any number of threads.
#pragma once
#include <array>
#include <cstdint>
#include <numbers>
#include <vector>

#include "core/noncontact_settings.hpp"
#include "neighbour/neighbour_list.hpp"
#include "noncontact/pair_rows.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

class LiquidBridges {
public:
  /// liquid_fraction: per species, liquid volume / particle volume. `skin`: the list's, m.
  LiquidBridges(const BoxGeometry& box, const LiquidBridgeSpec& spec,
                std::vector<double> liquid_fraction, const ParticleStore& p, double skin);

  /// Forms and ruptures the bridges at p's positions, then their forces on the particles, N,
  /// into f (resized; overwritten). Velocities: p's (the viscous force).
  void compute(const ParticleStore& p, std::array<std::vector<double>, 3>& f);
  void permute(const std::vector<std::uint32_t>& new_to_old) { order_.add(new_to_old); }
  /// The bridges as they stand: pairs and wall bridges.
  long bridge_count() const;
  /// The list whose history holds the bridges (1: a bridge; checkpoints save and restore it).
  NeighbourList& list() { return nl_; }
  const NeighbourList& list() const { return nl_; }
  /// Particle i's liquid, m^3.
  double liquid(const ParticleStore& p, std::size_t i) const;

private:
  /// The bridge between i and entry e's partner j (pair) at gap `gap`: its volume.
  double pair_volume(const ParticleStore& p, std::size_t i, std::size_t j) const;
  void count_bridges(std::size_t n);

  LiquidBridgeSpec spec_;
  std::vector<double> liquid_fraction_;
  BoxGeometry box_;
  NeighbourList nl_;
  PairRows rows_;
  PendingOrder order_;
  std::vector<int> count_; ///< bridges per particle
};

/// Particle i's liquid, m^3: its species' liquid fraction (liquid volume / particle volume) of
/// its volume.
inline double particle_liquid(const std::vector<double>& liquid_fraction, const ParticleStore& p,
                              std::size_t i) {
  const double r = p.radius[i];
  return liquid_fraction[static_cast<std::size_t>(p.species[i])] *
         (4.0 / 3.0 * std::numbers::pi * r * r * r);
}

/// The longest rupture distance a bridge of these particles can reach, m (both partners' whole
/// liquid in one bridge): the bridges' list reach.
double longest_rupture_distance(const LiquidBridgeSpec& spec,
                                const std::vector<double>& liquid_fraction, const ParticleStore& p);

/// The shortest time scale of the bridges among p, s: the half-period pi sqrt(m*/k) of the
/// capillary force's stiffness at contact and the viscous relaxation m*/c
/// (c = 6 pi mu R*^2 / S_min), for the time-step rule. Infinity without liquid.
double shortest_bridge_time(const LiquidBridgeSpec& spec,
                            const std::vector<double>& liquid_fraction, const ParticleStore& p);

} // namespace fluidem
