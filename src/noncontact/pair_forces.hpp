// The conservative non-contact forces between particles, and between particles and walls: van der
// Waals (noncontact/kernels/van_der_waals.hpp) and Coulomb with image charges at conducting walls
// (noncontact/kernels/coulomb.hpp) [Zhu07 §2.2, Table 2]. Evaluated at every particle step over a
// neighbour list of its own, whose reach is the longest range of these forces (so the contact
// loop's list stays as short as contacts need).
// Each particle's force is summed over all its partners in ascending partner index, then its
// walls in face order, skipping the pairs out of range: a function of the positions and the
// particle order alone, so the same with any number of threads, any neighbour-list history (a
// restarted run rebuilds its list at other moments) and any ownership of the pairs. The two
// particles of a pair compute the same magnitude along opposite directions: Newton's third law
// holds exactly.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/noncontact_settings.hpp"
#include "neighbour/neighbour_list.hpp"
#include "noncontact/pair_rows.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

/// What particle i feels from a partner or a wall: the force on i, N, and the pair's potential,
/// J (a wall's: all of it is i's).
struct NonContactTerm {
  Vec3 force;
  double potential = 0.0;
  bool in_range = false;
};
/// Particle i and particle j of p (minimum image along the box's periodic axes, as the neighbour
/// lists compute it): the two of a pair get the same magnitude along opposite directions.
NonContactTerm noncontact_pair(const NonContactSpec& spec, const BoxGeometry& box,
                               const ParticleStore& p, std::size_t i, std::size_t j);
/// Particle i and the wall of face f (0..5).
NonContactTerm noncontact_wall(const NonContactSpec& spec, const BoxGeometry& box,
                               const ParticleStore& p, std::size_t i, int face);
/// A particle's sum: the pairs in range (half the potential each), then the walls in range.
inline void add_pair_term(NonContactTerm& sum, const NonContactTerm& t) {
  if (!t.in_range) return;
  sum.force += t.force;
  sum.potential += 0.5 * t.potential;
}
inline void add_wall_term(NonContactTerm& sum, const NonContactTerm& t) {
  if (!t.in_range) return;
  sum.force += t.force;
  sum.potential += t.potential;
}
/// The range beyond contact a list must cover for `spec` among p: van der Waals to its range;
/// Coulomb (centre distance r_c) to r_c - 2 r_min, which also covers a particle's own image
/// (2 z < r_c). std::invalid_argument when the cut-off cannot reach past contact.
double noncontact_reach(const NonContactSpec& spec, const ParticleStore& p);

class ConservativePairForces {
public:
  /// The forces `spec` turns on, for the particles p (their radii and charges) in `box`; `skin`:
  /// the list's skin, m. std::invalid_argument when the cut-off cannot reach past contact.
  ConservativePairForces(const BoxGeometry& box, const NonContactSpec& spec, const ParticleStore& p,
                         double skin);

  /// The forces on the particles of p, N, into f, and each particle's share of the potential
  /// energy, J, into u (half of each of its pairs', its walls' whole): sum_i u_i, in index order,
  /// is the potential energy of the configuration (each pair once). Resized; overwritten.
  void compute(const ParticleStore& p, std::array<std::vector<double>, 3>& f,
               std::vector<double>& u);
  /// The particles were reordered (ParticleStore::permute): the list is renumbered at the next
  /// evaluation.
  void permute(const std::vector<std::uint32_t>& new_to_old);
  /// The range beyond contact the list covers, m.
  double reach() const { return nl_.reach(); }
  const NeighbourList& list() const { return nl_; }

private:
  /// Rebuild the list when a particle moved far or the particles were reordered, then the rows.
  void update(const ParticleStore& p);
  /// Force on particle i and its share of the potential (pairs halved).
  NonContactTerm particle(const ParticleStore& p, std::size_t i) const;

  NonContactSpec spec_;
  BoxGeometry box_;
  NeighbourList nl_;
  PairRows rows_;
  PendingOrder order_;
};

/// The shortest half-period pi sqrt(m*/k) of the non-contact forces of `spec` among p, s, with k
/// their largest stiffness |dF/d(gap)| (van der Waals at h0, Coulomb at contact): the time-step
/// rule treats it as a contact duration. Infinity when no such force acts.
double shortest_noncontact_period(const NonContactSpec& spec, const ParticleStore& p);

} // namespace fluidem
