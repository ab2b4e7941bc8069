// Pendular liquid bridges [Zhu07 §2.2, Table 2] over rank-independent rows
// (neighbour/ordered_rows.hpp): the model of noncontact/liquid_bridges.hpp (Willett's capillary
// force, the viscous force of the bridge liquid, Yang's rule of liquid shared evenly among a
// particle's bridges, rupture at Lian's S_c) on a rank's own particles, whatever rank holds them
// (docs/parallel.md).
// A bridge is a history value of 1 in the rows of both its particles. Every test of a pair
// (touching, rupture) and its force are evaluated from the pair's lower id, so the two rows agree
// bit for bit and the forces are exactly opposite. A rupture needs both particles' bridge
// counts: a ghost's count comes from its owner (`share`), once after the bridges formed and once
// after they ruptured. Each particle sums its bridges' forces in ascending partner id, then its
// walls by face: a function of its own row alone.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "core/noncontact_settings.hpp"
#include "neighbour/ordered_rows.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

class OrderedLiquidBridges {
public:
  /// liquid_fraction: per species, liquid volume / particle volume. reach: the rows' reach, the
  /// longest rupture distance of the run's particles (longest_rupture_distance).
  OrderedLiquidBridges(const BoxGeometry& box, const LiquidBridgeSpec& spec,
                       std::vector<double> liquid_fraction, double reach);

  /// The rows whose history holds the bridges (built by the engine with its other rows).
  OrderedRows& rows() { return rows_; }
  const OrderedRows& rows() const { return rows_; }

  /// Fills the ghosts' entries of a per-particle array (one number per particle of the store:
  /// own particles set, ghosts from their owners).
  using ShareWithGhosts = std::function<void(std::vector<double>&)>;
  /// Forms and ruptures the bridges of the own particles (the first rows().owned() of p, the
  /// rows built on p) at p's positions, then their forces with p's velocities, N, 3 per own
  /// particle into f (resized; overwritten). Collective when `share` is.
  void compute(const ParticleStore& p, const ShareWithGhosts& share, std::vector<double>& f);

  /// The own particles' bridges: pairs at their lower id (so that a sum over ranks counts each
  /// once), and wall bridges.
  std::int64_t bridges(const ParticleStore& p) const;

private:
  double liquid(const ParticleStore& p, std::size_t i) const;
  /// Sets counts_ of the own particles from the rows, then the ghosts' through `share`.
  void count(const ParticleStore& p, const ShareWithGhosts& share);

  LiquidBridgeSpec spec_;
  std::vector<double> liquid_fraction_;
  OrderedRows rows_;
  std::vector<double> counts_; ///< bridges per particle of the store (own and ghost)
};

} // namespace fluidem
