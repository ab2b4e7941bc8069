// The soft-sphere DEM's time step: velocity Verlet (second order in translation and rotation,
// unlike the first-order scheme of [Deen07 eq. 40]):
//   v += F/m dt/2, w += T/I dt/2;  x += v dt;  [rebuild list];  F, T <- contacts + sources + g;
//   v += F/m dt/2, w += T/I dt/2.
// Damping forces are evaluated with the half-step velocities. The last step's second half kick
// is done with the next step's first (the same increment), in one pass over the particles with
// the drift; on most steps of a run whose only forces are the contacts and gravity that pass runs
// slab by slab inside the contact loop (the folded step, drift_bound.hpp), bitwise the same.
#pragma once
#include <memory>
#include <vector>

#include "contact/contact_forces.hpp"
#include "contact/contact_table.hpp"
#include "integrate/drift_bound.hpp"
#include "integrate/force_sources.hpp"
#include "integrate/particle_stepper.hpp"
#include "neighbour/neighbour_list.hpp"
#include "particles/contact_record.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

class SoftSphereStepper final : public ParticleStepper {
public:
  struct Settings {
    double dt = 0.0;            ///< s
    double skin = 0.0;          ///< m (the first build's with an automatic skin)
    bool auto_skin = false;     ///< neighbour.skin = "auto" (NeighbourList::AutoSkin)
    double max_diameter = 0.0;  ///< m, the automatic skin's upper bound
    int sort_interval = 0;      ///< neighbour.sort_interval: sort every this many list builds
    bool sort_first = false;    ///< a new run starts sorted in space
    double auto_skin_steps = 0; ///< steps an automatic skin lets a list last
  };
  /// Builds the neighbour list (sorting the particles first if asked) and computes the first
  /// contact forces. `record` (nullptr: no analysis reads contacts) is filled on the steps that
  /// ask for it; p and forces outlive the stepper.
  SoftSphereStepper(std::unique_ptr<ContactTable> table, const BoxGeometry& box,
                    const Settings& settings, ParticleStore& p, ForceSources& forces,
                    ContactRecord* record);

  void step(double t, const StepNeeds& needs) override;
  void finish_kick() override;
  double dissipated_energy() const override { return e_dsp_; }
  const ContactStats& contact_stats() const override { return stats_; }
  Seconds seconds() const override {
    return {t_contacts_, t_integration_, t_neighbour_, t_sources_};
  }
  std::size_t bytes() const override;

  /// Brings the particle store's positions and velocities up to date from the contact view,
  /// which holds them after a step's first pass, for whatever reads the store.
  void sync_particles();

  /// The step sources (ForceSources::any_step_sources) at the state of the particle store
  /// (the end of a step: new positions, half-step velocities), time t.
  void evaluate_step_sources(double t);

  const ContactTable& table() const { return *table_; }
  const NeighbourList& list() const { return *nl_; }
  NeighbourList& list() { return *nl_; }
  const ContactScratch& scratch() const { return nc_; }
  ContactScratch& scratch() { return nc_; }
  ContactStats& stats() { return stats_; }
  void set_dissipated_energy(double e) { e_dsp_ = e; }
  /// Spatial sorts of the store done by this stepper; steps folded into the contact loop.
  long sorts() const { return sorts_; }
  long folded_steps() const { return folded_steps_; }
  /// Whether steps may be folded (default true); see Simulation::set_folded_integration.
  void set_folded_integration(bool on) {
    fold_enabled_ = on;
    drift_bound_ = DriftBound{}; // not kept up to date while off: the next step measures it
  }
  /// Steps fold only while the list holds at least this many pairs per particle (for all
  /// steppers of the process).
  static double fold_pairs_per_particle();
  static void set_fold_pairs_per_particle(double pairs);
  double pairs_per_particle() const {
    return p_.size() ? static_cast<double>(nl_->partner.size()) / static_cast<double>(p_.size())
                     : 0.0;
  }

private:
  struct Kick;
  void compute_forces(ScratchState scratch = ScratchState::Stale);
  /// The contact forces of a folded step: the step's pass over the particles runs slab by slab
  /// inside the contact loop (compute_contact_forces' before_slab).
  void compute_forces_folded(const SlabHook& slab_pass);
  /// Sort the particles in space (neighbour/spatial_order.hpp) and rebuild the list in the new
  /// order, keeping the histories and the sources' forces with their particles.
  void sort_and_rebuild();
  /// Whether this step may run folded: its second half kick pending, plain forces (contacts
  /// and gravity), and the last step bounding its drift within half the skin.
  bool may_fold(bool fused, bool tracked, bool plain) const;
  /// A folded step: the pass kick_kick_drift(i) of each particle runs slab by slab inside the
  /// contact loop.
  void folded_step(const auto& kick_kick_drift, bool any_periodic, const StepNeeds& needs);
  /// A step whose pass (kick_drift(), true if a particle moved beyond half the skin) runs on
  /// its own before the rebuild and the contacts.
  void separate_step(const auto& kick_drift, bool tracked, bool plain, const StepNeeds& needs);

  ParticleStore& p_;
  ForceSources& forces_;
  ContactRecord* record_;
  std::unique_ptr<ContactTable> table_;
  std::unique_ptr<NeighbourList> nl_;
  ContactScratch nc_;
  ContactStats stats_;
  double dt_ = 0.0, e_dsp_ = 0.0;
  int sort_interval_ = 0;
  bool kick_pending_ = false; ///< the last step's second half kick is still to do
  /// p_'s positions and velocities are current (else the contact view holds them: after a
  /// step's first pass, until sync_particles()).
  bool particles_current_ = true;
  /// The folded step: whether it may run, the bound that decides it from the last step, the
  /// particles' largest 1/m, its per-slab sums (dissipation, largest squared speed), the steps
  /// it ran.
  bool fold_enabled_ = true;
  DriftBound drift_bound_;
  double max_inv_mass_ = 0.0;
  std::vector<double> slab_sums_;
  long folded_steps_ = 0, sorts_ = 0;
  double t_contacts_ = 0.0, t_integration_ = 0.0, t_neighbour_ = 0.0, t_sources_ = 0.0;
};

} // namespace fluidem
