// Neighbour search: a cell grid and a half Verlet list with skin [Deen07 §4], rebuilt when a
// particle has moved more than half the skin since the last build. Each pair is stored once,
// under its owner, in CSR form. For race-free, thread-count-independent parallel force loops the
// domain is cut into slabs one cell thick along one axis: a pair is owned by the particle in the
// lower slab (by the lower index within a slab), so the rows of slab s touch only particles of
// slabs s and s+1, and slabs that are not neighbours can be processed at once (the contact loop
// runs them in two phases over groups of consecutive slabs, contact_forces.cpp); each entry
// carries the contact history (tangential displacement, rolling rotation), which is carried over to
// the rebuilt list for pairs that are in both. Particles near a closed wall get wall entries with
// their own history. Fixed particles (ParticleStore::fix) get no wall entries and no pairs with
// each other. No physics here: the contact module interprets the history.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/nearest_integer.hpp"
#include "neighbour/box_geometry.hpp"
#include "neighbour/cell_grid.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

class NeighbourList {
public:
  /// history_width: doubles of history per contact. reach: the range of an interaction beyond
  /// contact, m (0 for contacts; the non-contact forces' range): the list holds every pair whose
  /// surface gap is below reach + skin at its build, so every pair whose gap is below `reach`
  /// until the next build (a rebuild is due once a particle moved skin/2); wall entries alike.
  NeighbourList(const BoxGeometry& box, double skin, int history_width, double reach = 0.0);

  /// True if some particle moved more than skin/2 since the last build (or never built).
  bool needs_rebuild(const ParticleStore& p) const;
  /// Whether the list was built for a store of n particles: then needs_rebuild is the OR of
  /// moved_far over the particles (which the integrator tests right after each drift).
  bool built_for(std::size_t n) const { return builds_ > 0 && x0_.size() == n; }
  /// Whether particle i, now at (x, y, z), moved more than skin/2 since the last build.
  bool moved_far(std::size_t i, double x, double y, double z) const {
    return moved_far_by(displacement2(i, x, y, z));
  }
  /// Whether a squared displacement (displacement2) is beyond skin/2.
  bool moved_far_by(double displacement2) const { return displacement2 > 0.25 * skin_ * skin_; }
  /// The squared distance of particle i, now at (x, y, z), from where the last build saw it, m^2.
  double displacement2(std::size_t i, double x, double y, double z) const {
    const double dx = min_image(x - x0_[i], 0);
    const double dy = min_image(y - y0_[i], 1);
    const double dz = min_image(z - z0_[i], 2);
    return dx * dx + dy * dy + dz * dz;
  }
  /// The most entries (pairs, as owner or partner, and walls) any one particle has in the list
  /// of the last build: no particle has more contacts than this until the next build.
  std::uint32_t max_entries_per_particle() const { return max_entries_; }
  /// Rebuild pair and wall lists; history of surviving contacts is kept. `new_to_old`: the
  /// store was reordered since the last build (new index k holds the particle that was at
  /// new_to_old[k], ParticleStore::permute); the previous list is renumbered through it before
  /// its history is carried over.
  void build(const ParticleStore& p, const std::vector<std::uint32_t>* new_to_old = nullptr);

  // Pair list (CSR by owner i): partners of i are partner[offset[i] .. offset[i+1]).
  std::vector<std::uint32_t> offset;
  std::vector<std::uint32_t> partner;
  std::vector<double> history; ///< history_width doubles per pair entry

  // Wall entries: particle index and face (0..5), sorted by particle.
  std::vector<std::uint32_t> wall_particle;
  std::vector<std::uint8_t> wall_face;
  std::vector<double> wall_history; ///< history_width doubles per wall entry

  // Slabs: the particles of slab s (whose rows are processed together) are
  // slab_particles[slab_start[s] .. slab_start[s+1]), in ascending index order.
  std::vector<std::uint32_t> slab_start, slab_particles;
  int slab_count() const { return nslab_; }
  /// Whether the slabs' axis is periodic: then the last slab's rows also write into slab 0.
  bool slabs_wrap() const { return box_.periodic[slab_axis_]; }

  int history_width() const { return hw_; }
  /// The interaction range beyond contact the list covers, m (constructor).
  double reach() const { return reach_; }
  /// The skin of the list as last built (restored), m.
  double skin() const { return skin_; }
  /// Change the skin for the next build (a fixed skin: ends an automatic one).
  void set_skin(double skin) {
    skin_ = skin;
    auto_skin_.reset();
  }

  /// The automatic skin (neighbour.skin = "auto"): each build() chooses its skin from the
  /// largest particle speed v_max at that moment, so that the list lasts at least `steps` time
  /// steps dt while the particles keep their speeds (a rebuild is due after a move of skin/2):
  ///   skin = clamp(2 steps v_max dt, min_skin, max_skin).
  /// The lower bound keeps slow beds at the fixed default (0.2 d_max); the upper bound (d_max)
  /// limits the pairs a dense region holds (their number grows with (d + skin)^3). The choice
  /// depends on the velocities alone (a maximum: the same with any number of threads), so a
  /// restarted run, which rebuilds its list with the checkpoint's skin, chooses the same skins
  /// after it as the run it continues. docs/case-file.md, [neighbour].
  struct AutoSkin {
    double dt = 0.0;       ///< the time step, s
    double steps = 10.0;   ///< steps the list should last at the largest speed
    double min_skin = 0.0; ///< m
    double max_skin = 0.0; ///< m
    double skin(double v_max) const;
  };
  void set_auto_skin(const AutoSkin& a) { auto_skin_ = a; }
  /// The skin the next build() of the particles p uses: the automatic one for their speeds, or
  /// the fixed one.
  double skin_for(const ParticleStore& p) const;
  /// The cells of the last build() (its grid is released after it; kept for inspection).
  std::array<int, 3> cells_per_axis() const { return grid_.cells_per_axis(); }
  /// The cells the last build() stored (all of a dense grid, the occupied ones of a sparse one)
  /// and the most bytes its grid held: bounded by the particle count, not the box.
  std::size_t stored_cells() const { return stored_cells_; }
  std::size_t grid_bytes() const { return grid_bytes_; }
  long builds() const { return builds_; }
  /// Changes with every build() and restore() of this object (and is not saved): whoever
  /// derives data from the pairs (the contact loop's entry owners) rebuilds them when it does.
  std::uint64_t generation() const { return generation_; }
  /// Side of the cells the next build() bins the particles p in: their largest diameter plus
  /// the reach and the skin it uses (skin_for).
  double cell_size(const ParticleStore& p) const;
  std::size_t bytes() const;

  /// Minimum-image separation vector component along axis a.
  double min_image(double d, int a) const {
    if (!box_.periodic[a]) return d;
    const double l = box_.length(a);
    return d - l * nearest_integer(d / l);
  }
  const BoxGeometry& box() const { return box_; }

  /// What a checkpoint keeps of the list: the positions and skin of the last build (from which
  /// the same pairs are rebuilt), the pairs themselves (to verify that) and their history.
  struct State {
    double skin = 0.0;
    std::int64_t builds = 0;
    std::vector<double> x0, y0, z0;
    std::vector<std::uint32_t> offset, partner, wall_particle;
    std::vector<std::uint8_t> wall_face;
    std::vector<double> history, wall_history;
  };
  State state() const;
  /// The same arrays as State, without copying them: valid while the list is neither rebuilt
  /// nor restored (a checkpoint writes them from here).
  struct StateView {
    double skin = 0.0;
    std::int64_t builds = 0;
    const std::vector<double>& x0;
    const std::vector<double>& y0;
    const std::vector<double>& z0;
    const std::vector<std::uint32_t>& offset;
    const std::vector<std::uint32_t>& partner;
    const std::vector<std::uint32_t>& wall_particle;
    const std::vector<std::uint8_t>& wall_face;
    const std::vector<double>& history;
    const std::vector<double>& wall_history;
  };
  StateView state_view() const {
    return {skin_,   builds_,       x0_,       y0_,     z0_,         offset,
            partner, wall_particle, wall_face, history, wall_history};
  }
  /// Rebuilds the list of `s` from its build positions (the other particle data from p) and
  /// restores its history and build count. std::runtime_error if the rebuilt pairs differ.
  void restore(const ParticleStore& p, const State& s);

private:
  /// build() with the skin as it is (restore() rebuilds with the checkpoint's skin).
  void build_with_skin(const ParticleStore& p, const std::vector<std::uint32_t>* new_to_old);
  /// The slabs of the particles from the cell grid of the build.
  void build_slabs(std::size_t n);
  /// Renumber the previous list (old_* arrays) into the new particle order.
  void renumber_old(const std::vector<std::uint32_t>& new_to_old);

  BoxGeometry box_;
  double skin_;
  double reach_;
  std::optional<AutoSkin> auto_skin_;
  int hw_;
  long builds_ = 0;
  std::uint64_t generation_ = 0;
  std::uint32_t max_entries_ = 0;
  std::size_t stored_cells_ = 0, grid_bytes_ = 0;
  std::vector<double> x0_, y0_, z0_; ///< positions at the last build
  // Cell grid (its arrays are scratch of build(), released at its end)
  CellGrid grid_;
  /// The slabs' axis; the slab count (occupied slabs only); the cell layers along the axis that
  /// the slabs are cut from (a particle's layer decides which particle owns a pair).
  int slab_axis_ = 0, nslab_ = 1, nlayer_ = 1;
  std::vector<std::uint32_t> particle_slab_; ///< each particle's layer
  // Scratch for history carry-over
  std::vector<std::uint32_t> old_offset_, old_partner_, old_wall_particle_;
  std::vector<std::uint8_t> old_wall_face_;
  std::vector<double> old_history_, old_wall_history_;
  std::vector<std::uint32_t> count_;
};

} // namespace fluidem
