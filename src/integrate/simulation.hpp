// The scheduler of a run: it owns everything of one run (no global
// state) and reads like the design. Set-up assembles the case's parts: the particles, the force
// sources (force_sources.hpp: gravity, the body-force field, the gas, ...), the particle engine
// (soft_sphere_stepper.hpp or hard_sphere_stepper.hpp), the gas (gas_coupling.hpp), the analyses
// fed every step, and chooses the time steps (time_step_rule.hpp). A step is: a flow step when
// one is due, one particle step, the analyses. run() adds the outputs and checkpoints
// (run_recorder.hpp) and the stability guard (stability_guard.hpp).
#pragma once
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "analysis/collision_statistics.hpp"
#include "analysis/continuum_averaging.hpp"
#include "analysis/energies.hpp"
#include "contact/contact_forces.hpp"
#include "core/case_spec.hpp"
#include "integrate/coarse_graining.hpp"
#include "integrate/distributed_soft_sphere.hpp"
#include "integrate/force_sources.hpp"
#include "integrate/gas_coupling.hpp"
#include "integrate/hard_sphere_stepper.hpp"
#include "integrate/soft_sphere_stepper.hpp"
#include "integrate/stability_guard.hpp"
#include "output/output_directory.hpp"
#include "output/run_outputs.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

class LiquidBridges;

/// Quantities a user needs before a run (`fluidem check`).
struct CaseReport {
  std::size_t particle_count = 0;
  double total_mass = 0.0;                          ///< kg
  std::vector<ContactTable::DurationRow> durations; ///< contact duration per pair, s
  double characteristic_velocity = 0.0;             ///< m/s used for Hertz durations
  double stable_time_step = 0.0;                    ///< largest accepted dt, s
  double flow_time_step = 0.0;                      ///< gas step DT, s (coupled runs)
  long steps_per_flow_step = 1;                     ///< particle steps per DT (soft sphere)
  double chosen_time_step = 0.0;                    ///< s
  bool time_step_forced = false;
  double expected_overlap_ratio = 0.0; ///< under the bed's own weight, / diameter
  double skin = 0.0;                   ///< m
};

/// Status passed to the progress callback.
struct RunStatus {
  long step = 0, total_steps = 0;
  double time = 0.0, end_time = 0.0;
  std::size_t particles = 0;
};

/// Totals at the end of a run (printed in the log).
struct RunSummary {
  long steps = 0;
  double wall_seconds = 0.0;
  double particle_steps_per_second = 0.0;
  long neighbour_builds = 0;
  long spatial_sorts = 0; ///< sorts of the store in space by this process
  /// Soft spheres: steps whose integration ran inside the contact loop (their integration time
  /// is in seconds_contacts)
  long folded_steps = 0;
  double seconds_contacts = 0.0, seconds_integration = 0.0, seconds_neighbour = 0.0,
         seconds_output = 0.0, seconds_gas = 0.0;
  double seconds_gas_solver = 0.0;   ///< the part of seconds_gas in the gas solver's steps
  double seconds_gas_pressure = 0.0; ///< the part of seconds_gas_solver in its pressure solves
  double seconds_step_sources =
      0.0; ///< soft spheres: the forces evaluated every step (non-contact)
  std::size_t bytes_per_particle = 0;
  double energy_drift = 0.0;       ///< (E_total(end) - E_total(0)) / E_scale
  long collisions = 0;             ///< hard-sphere engine: collisions processed
  double pairs_per_particle = 0.0; ///< soft spheres: neighbour-list pair entries per particle
  double walls_per_particle = 0.0; ///< soft spheres: neighbour-list wall entries per particle
  long contacts = 0;               ///< soft spheres: touching pairs and walls after the last step
  int stopped_by_signal = 0; ///< SIGINT/SIGTERM that stopped the run early (0: ran to the end)
  /// Rank-independent runs (docs/parallel.md): the ranks, and the largest rank's time in the
  /// contact loop over the mean of the ranks' (1: balanced).
  int ranks = 1;
  double imbalance = 1.0;
  /// What a rank sent per step, mean over the ranks: bytes, messages (docs/parallel.md); the
  /// rebalances of the cut planes.
  double bytes_per_rank_step = 0.0, messages_per_rank_step = 0.0;
  /// Coupled: the fixed-point gas sums each rank reduced per flow step, bytes and reductions.
  double gas_sum_bytes_per_flow_step = 0.0, gas_sums_per_flow_step = 0.0;
  long rebalances = 0;
  bool rank_independent = false;
  std::string checkpoint; ///< the last checkpoint written
};

/// How run() starts and when it stops early.
struct RunOptions {
  /// Continue the output files of the run this simulation was restarted from (restart()):
  /// frames and rows after the checkpoint are dropped, new ones appended.
  bool resume = false;
  /// Checked after every step: a nonzero value (the signal number) makes the run finish the
  /// step, write a checkpoint, flush the outputs and return with stopped_by_signal set.
  const std::atomic<int>* stop = nullptr;
  /// The output directory, locked and checked by the caller (the command line: its contents,
  /// the disk space). nullptr: run() locks it itself, and a new run replaces any results there.
  const OutputDirectory* directory = nullptr;
  /// False on the ranks of a distributed run other than the root: they compute with the root
  /// and write nothing (no directory is touched).
  bool write_outputs = true;
};

/// The output schedule and energy reference of a run (kept in checkpoints so that a restarted
/// run writes its next frame, row and checkpoint when the original would have).
struct OutputClock {
  double next_frame = 0.0, next_series = 0.0, next_checkpoint = 0.0;
  double next_continuum = 0.0; ///< end of the current continuum averaging interval
  double e0 = 0.0, escale = 0.0;
  bool started = false; ///< e0, escale and the first "next" times are set
};

class RunRecorder;

class Simulation {
public:
  /// Builds the contact table, inserts the particles and chooses the time step.
  /// Throws InputError for anything wrong with the case.
  explicit Simulation(CaseSpec spec);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// The simulation saved in a checkpoint (write_checkpoint), ready to continue. `overrides`
  /// ("section.key=value") may change only simulation.end_time and output.* intervals.
  /// Throws CheckpointError (unreadable file) or InputError (bad override).
  static std::unique_ptr<Simulation> restart(const std::string& checkpoint,
                                             const std::vector<std::string>& overrides = {});
  /// Writes the complete state atomically (output/checkpoint_file.hpp). The gas solver's
  /// reused multigrid set-ups are dropped afterwards, so that this run and one restarted from
  /// the checkpoint take the same (bitwise) path.
  void write_checkpoint(const std::string& path);

  const CaseReport& report() const { return report_; }
  /// The case as simulated (a coarse-grained run's parcels: integrate/coarse_graining.hpp).
  const CaseSpec& spec() const { return spec_; }
  /// The case a run writes (case.resolved.toml, checkpoints): what the set-up resolved, in the
  /// terms of the case as given.
  CaseSpec resolved_case() const { return user_values(spec_, case_); }
  ParticleStore& particles() { return p_; }
  const ParticleStore& particles() const { return p_; }
  double time() const { return time_; }
  long step_count() const { return step_; }
  double time_step() const { return dt_; }

  /// Advance to end_time writing OUT/particles.h5, particles.xmf, series.csv and
  /// case.resolved.toml (output/run_outputs.hpp). Throws InstabilityError (after flushing the
  /// outputs) if the run goes unstable, InputError if the outputs of a continued run do not
  /// match its checkpoint (nothing is touched then), OutputError if an output cannot be written.
  RunSummary run(const std::string& out_dir,
                 const std::function<void(const RunStatus&)>& progress = {},
                 const RunOptions& options = {});

  /// Advance n steps without output (tests, benchmarks).
  void advance(long n);

  /// Adds a force on the particles (force_sources.hpp) before the first step; a source
  /// evaluated every step is evaluated at once. Soft spheres take every kind, hard spheres the
  /// held ones (std::logic_error otherwise). (For tests and embedding programs: a source added
  /// here is not part of the case, so checkpoints do not hold it and a restart lacks it.)
  void add_force_source(std::unique_ptr<ForceSource> source);

  /// The files run() writes, and their shapes.
  OutputLayout output_layout() const;
  /// About how many bytes the rest of the run writes (with a margin of 2), for the disk check.
  double output_bytes_needed() const;
  /// What the run had written when its checkpoint was taken (restart()); empty otherwise.
  const OutputMarks& output_marks() const { return marks_; }

  /// Current energies (e_pot: gravity's and the conservative sources') and contact statistics.
  Energies energies() const;
  const ContactStats& contact_stats() const { return stepper_->contact_stats(); }
  /// Contact force (N) and torque (N m) on particle i from the last force evaluation (soft
  /// spheres; the particle store keeps no forces).
  Vec3 contact_force(std::size_t i) const { return soft_->scratch().force(i); }
  Vec3 contact_torque(std::size_t i) const { return soft_->scratch().torque(i); }
  /// The contact loop's per-particle sums: force, torque and their non-conservative parts
  /// (ContactScratch::acc, kAcc doubles per particle; empty for hard spheres).
  const std::vector<double>& contact_sums() const {
    static const std::vector<double> none;
    return soft_ ? soft_->scratch().acc : none;
  }
  /// Whether the soft-sphere engine runs rank-independently, on this run's MPI ranks
  /// ([parallel], docs/parallel.md); the ranks' communicator (one rank otherwise).
  bool rank_independent() const { return dist_ != nullptr; }
  const Communicator& communicator() const { return *comm_; }
  /// A rank-independent run: gathers the particles (in id order) into particles() on the root
  /// and the totals behind energies(), contact_stats() and dissipated_energy(), for the outputs.
  /// Collective; nothing to do otherwise.
  void observe() {
    if (dist_) dist_->observe(p_);
  }
  /// The distributed engine (rank_independent()), or nullptr.
  const DistributedSoftSphere* distributed() const { return dist_; }
  /// The hard-sphere engine, or nullptr for the soft-sphere DEM.
  const HardSphereEngine* hard_sphere() const { return hard_ ? &hard_->engine() : nullptr; }
  HardSphereEngine* hard_sphere() { return hard_ ? &hard_->engine() : nullptr; }
  double dissipated_energy() const { return stepper_->dissipated_energy(); }
  /// The gas phase and coupling, or nullptr for a granular run.
  const GasCoupling* gas() const { return gas_.get(); }
  /// The liquid bridges (nullptr without [liquid_bridge]).
  const LiquidBridges* liquid_bridges() const { return bridges_; }
  /// The collision statistics (output.collisions = true), or nullptr. Fed after every step,
  /// also by advance(); run() takes a row of collisions.csv every series interval.
  const CollisionStatistics* collisions() const { return collisions_.get(); }
  /// Bed height (analysis/bed_height.hpp) along the axis of gravity, m.
  double bed_height() const;
  /// The continuum averager of [output.continuum] (its sums since the last written interval),
  /// or nullptr when the case has none.
  const ContinuumAverager* continuum() const { return continuum_.get(); }
  /// Spatial sorts of the store done by this process (neighbour.sort_interval).
  long spatial_sorts() const;
  /// Builds of the soft-sphere neighbour list so far (checkpointed; 0 for hard spheres).
  long neighbour_builds() const {
    return soft_ ? soft_->list().builds() : dist_ ? dist_->builds() : 0;
  }
  /// Particle-wall entries in the neighbour list of the last build.
  std::size_t neighbour_wall_entries() const {
    return soft_ ? soft_->list().wall_particle.size() : 0;
  }
  /// Steps whose integration pass ran inside the contact loop, slab by slab (step()), in this
  /// process (not checkpointed: a log figure).
  long folded_steps() const { return soft_ ? soft_->folded_steps() : 0; }
  /// Whether steps may be folded (default true). The folded and the separate pass give bitwise
  /// the same particles; the dissipated energy is summed per slab instead of per chunk of
  /// particles (the same round-off with any thread count). For tests and benchmarks.
  void set_folded_integration(bool on) {
    if (soft_) soft_->set_folded_integration(on);
  }
  /// Steps fold only while the neighbour list holds at least this many pairs per particle
  /// (default 3: sparser beds ran slower folded, bench/RESULTS.md). For all simulations of the
  /// process; tests set 0 to fold sparse beds.
  static double fold_pairs_per_particle() { return SoftSphereStepper::fold_pairs_per_particle(); }
  static void set_fold_pairs_per_particle(double pairs) {
    SoftSphereStepper::set_fold_pairs_per_particle(pairs);
  }
  /// Neighbour-list pair entries per particle (soft spheres; 0 without particles).
  double neighbour_pairs_per_particle() const { return soft_ ? soft_->pairs_per_particle() : 0.0; }
  /// The contacts of the last step, when that step recorded them (else empty).
  const ContactRecord& contact_record() const { return record_; }

private:
  friend class RunRecorder;
  Simulation(CaseSpec spec, const ParticleStore* initial,
             const DistributedState* restart_state = nullptr);
  /// Whether the case runs on the rank-independent engine (and checks what that engine takes:
  /// InputError naming the key otherwise).
  bool choose_rank_independent() const;
  /// The set-up of the analyses that read every step (collision statistics, continuum
  /// averages).
  void set_up_analyses();
  /// The set-up of the particle engine, after the time steps are chosen.
  void set_up_stepper(std::unique_ptr<ContactTable> table, bool sort_first, double skin,
                      double max_diameter);
  /// The non-contact forces of the case as a force source (soft spheres; refused for hard
  /// spheres with an InputError), after the stepper; skin: the contact list's.
  void set_up_noncontact(double skin);
  /// One step. defer_second_kick: see StepNeeds.
  void step(bool defer_second_kick = false);
  /// The gas step and the new held forces, at the start of a flow step of DT.
  void flow_step();
  /// [coupling.forces]: their state in the gas coupling, the added inertia in p_.inv_mass.
  void set_up_fluid_forces();
  /// The analyses fed by the step just taken.
  void feed_analyses(bool sampled_continuum);
  /// feed_analyses of the rank-independent engine: the contacts and particles gathered on the
  /// root.
  void feed_analyses_on_ranks(bool sampled_continuum);
  /// Finishes a pending half kick, then the stability guard (InstabilityError).
  void check_stability();
  /// The step at which the run ends: the first at or after simulation.end_time.
  long total_steps() const;
  /// True when the step about to be taken (number step_ + 1) is averaged by [output.continuum].
  bool continuum_samples_next_step() const;
  RunSummary summary(long steps, double seconds, double seconds_output, long folded) const;

  /// The case as given (the real particles of a coarse-grained run), then the case simulated
  /// (integrate/coarse_graining.hpp; the same without [coarse_graining]).
  CaseSpec case_;
  CaseSpec spec_;
  ParticleStore p_;
  ForceSources forces_;
  std::unique_ptr<GasCoupling> gas_; ///< set when the case has [gas]
  LiquidBridges* bridges_ = nullptr; ///< the liquid bridges' source's (in forces_), [liquid_bridge]
  std::unique_ptr<ParticleStepper> stepper_;
  SoftSphereStepper* soft_ = nullptr;     ///< stepper_ when engine = "soft_sphere"
  DistributedSoftSphere* dist_ = nullptr; ///< stepper_ when rank-independent
  const Communicator* comm_ = &Communicator::self();
  const DistributedState* restart_state_ = nullptr; ///< during a restart's construction
  /// Rank-independent coupled runs: this rank's own particles, copied for the flow step (each
  /// rank couples them to its copy of the gas; GasCoupling::distribute).
  ParticleStore coupled_;
  HardSphereStepper* hard_ = nullptr; ///< stepper_ when engine = "hard_sphere"
  long steps_per_flow_ = 1;           ///< particle steps per gas step
  double flow_dt_ = 0.0;              ///< s
  CaseReport report_;
  StabilityLimits limits_;
  double dt_ = 0.0, time_ = 0.0;
  long step_ = 0;
  OutputClock clock_;
  /// The outputs of run() while it goes (their marks go into checkpoints), and the marks a
  /// restarted simulation read from its checkpoint (run() with resume continues those files).
  const RunOutputs* outputs_ = nullptr;
  OutputMarks marks_;
  std::unique_ptr<CollisionStatistics> collisions_; ///< set when output.collisions = true
  /// The last step's contacts, recorded for the collision statistics (every step) and the
  /// continuum averages (their sampled steps).
  ContactRecord record_;
  std::vector<InstantCollision> instant_;        ///< hard spheres: scratch
  std::unique_ptr<ContinuumAverager> continuum_; ///< set with [output.continuum]
  double continuum_interval_ = 0.0;              ///< s
  double t_gas_ = 0.0;
  long flow_steps_ = 0; ///< flow steps of this process (the log's gas sums per flow step)
};

} // namespace fluidem
