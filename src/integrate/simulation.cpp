#include "integrate/simulation.hpp"
#include "integrate/rank_sum_of.hpp"
#include "integrate/wall_clock.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "analysis/bed_height.hpp"
#include "core/gravity_axis.hpp"
#include "integrate/contact_time_limit.hpp"
#include "integrate/fluid_forces.hpp"
#include "integrate/liquid_bridge_source.hpp"
#include "integrate/memory_estimate.hpp"
#include "integrate/noncontact_source.hpp"
#include "integrate/run_recorder.hpp"
#include "integrate/time_step_rule.hpp"
#include "noncontact/pair_forces.hpp"
#include "particles/insertion.hpp"

namespace fluidem {

namespace {

/// The automatic skin (neighbour.skin = "auto") lets a neighbour list last at least this many
/// steps at the largest particle speed of its build, within its bounds (NeighbourList::AutoSkin).
constexpr double kAutoSkinSteps = 10.0;

} // namespace

Simulation::Simulation(CaseSpec spec) : Simulation(std::move(spec), nullptr) {}

Simulation::Simulation(CaseSpec spec, const ParticleStore* initial,
                       const DistributedState* restart_state)
    : case_(std::move(spec)), spec_(simulated_case(case_)),
      forces_(spec_.simulation.gravity, spec_.body_force ? &*spec_.body_force : nullptr),
      restart_state_(restart_state) {
  const bool hard = spec_.simulation.engine == Engine::HardSphere;
  // Memory first: no table, particle or grid is allocated for a case that cannot fit.
  require_memory(spec_, case_memory_shares(spec_));
  std::unique_ptr<ContactTable> table;
  if (!hard) {
    // The species with particles: those of the [[insert]] blocks (a restart's particles were
    // inserted by the same blocks).
    std::vector<bool> used(spec_.species.size(), false);
    for (const InsertSpec& ins : spec_.inserts)
      if (const int s = spec_.species_index(ins.species); s >= 0) used[s] = true;
    // The durations of each species' smallest particles (a size distribution's smallest draw).
    const CaseSpec smallest = with_smallest_diameters(spec_);
    table = std::make_unique<ContactTable>(smallest, std::move(used));
    check_contact_durations(smallest, *table, kMinStepsPerContact, kMaxSteps);
  }
  if (initial) {
    p_ = *initial;
  } else {
    insert_particles(spec_, p_);
    // Coloured layers [Hoomans96 Figs. 10, 12]: bands of the initial bed along gravity's axis.
    assign_layers(p_, gravity_axis(spec_.simulation.gravity), spec_.output.layers);
  }
  p_.shrink_to_fit(); // insertion appended particle by particle
  if (!(spec_.output.checkpoint_interval > 0.0))
    spec_.output.checkpoint_interval = 10.0 * spec_.output.frame_interval;

  double dmax = 0.0, mass = 0.0;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    dmax = std::max(dmax, 2.0 * p_.radius[i]);
    mass += p_.mass[i];
  }
  for (const auto& s : spec_.species) dmax = std::max(dmax, s.diameter);
  const double skin = spec_.neighbour.skin ? *spec_.neighbour.skin : 0.2 * dmax;
  if (table)
    for (const int s : p_.species) // (every particle's species has its contact coefficients)
      if (!table->has_particles(s))
        throw std::logic_error("a particle of species " + spec_.species[s].name +
                               ", which no [[insert]] names");
  // With the particles known (the neighbour lists' cell grids are bounded by the particle count,
  // neighbour/cell_grid.hpp, and counted in their bytes per particle).
  require_memory(spec_, case_memory_shares(spec_, static_cast<double>(p_.size())));

  const TimeSteps steps = choose_time_steps(spec_, p_, table.get());
  dt_ = steps.dt;
  steps_per_flow_ = steps.steps_per_flow;
  report_.particle_count = p_.size();
  report_.total_mass = mass;
  report_.skin = skin;
  report_.chosen_time_step = dt_;
  report_.flow_time_step = steps.flow_dt;
  if (table) {
    report_.steps_per_flow_step = steps_per_flow_;
    report_.durations = table->durations();
    report_.characteristic_velocity = table->characteristic_velocity();
    report_.stable_time_step = steps.stable_dt;
    report_.time_step_forced = steps.forced;
    report_.expected_overlap_ratio = expected_overlap_ratio(spec_, p_, *table);
  }
  set_up_analyses();
  limits_ = {box_from(spec_), spec_.simulation.dimension, spec_.contact.max_overlap};
  // A new run starts sorted in space (inserted at random or read from a file in any order); a
  // restarted one continues in the order of its checkpoint.
  set_up_stepper(std::move(table), !initial && spec_.neighbour.sort_interval > 0, skin, dmax);
  restart_state_ = nullptr;
  if (spec_.noncontact.any()) set_up_noncontact(skin);
  if (spec_.gas) {
    gas_ = std::make_unique<GasCoupling>(spec_, p_);
    if (dist_) // own particles, a copy of the gas each, the pressure solve shared
      gas_->distribute(rank_sum_of(*comm_), {comm_->mpi_handle(), comm_->rank(), comm_->size()});
    spec_.coupling.drag = gas_->drag_name(); // the resolved case names the closure used
    set_up_fluid_forces();
    forces_.add(std::make_unique<GasForceSource>(*gas_));
  }
}

Simulation::~Simulation() = default;

void Simulation::set_up_fluid_forces() {
  if (!spec_.coupling.forces.any()) return;
  const coupling::FluidForceSettings& f = spec_.coupling.forces;
  // The added mass and the newest Basset interval enter the particle's inertia here, with the
  // fluid's density now (docs/coupling.md).
  if ((f.virtual_mass || f.basset) && spec_.gas->eos != gas::EquationOfState::incompressible)
    throw InputError(spec_.where("coupling.forces"), "coupling.forces",
                     std::string(f.virtual_mass ? "virtual_mass" : "basset") +
                         " = true needs gas.eos = \"incompressible\" (the added mass enters the "
                         "particle's inertia with a fixed fluid density; for a gas it is about "
                         "rho_g/rho_p ~ 1e-3 of the particle's mass)");
  gas_->set_up_fluid_forces(dt_ * static_cast<double>(steps_per_flow_), p_.size(),
                            spec_.body_force ? &*spec_.body_force : nullptr);
  // The added inertia of the virtual mass and the newest Basset interval, implicit in the
  // particle update (integrate/fluid_forces.hpp). A restart reads the particles' inverse masses
  // from its checkpoint, where they already hold it.
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (p_.inv_mass[i] > 0.0)
      p_.inv_mass[i] = 1.0 / (p_.mass[i] + gas_->added_inertia(2.0 * p_.radius[i]));
  if (dist_) dist_->add_inertia([&](double d) { return gas_->added_inertia(d); });
}

void Simulation::set_up_analyses() {
  if (spec_.output.collisions) {
    CollisionStatistics::Settings cs;
    for (const CollisionRegionSpec& r : spec_.output.collision_regions)
      cs.regions.push_back({r.name, Vec3{r.centre[0], r.centre[1], r.centre[2]}, r.radius});
    cs.dimension = spec_.simulation.dimension;
    cs.soft_spheres = spec_.simulation.engine != Engine::HardSphere;
    for (std::size_t a = 0; a < 3; ++a) {
      cs.box_length[a] = spec_.domain.hi[a] - spec_.domain.lo[a];
      cs.periodic[a] = spec_.domain.periodic[a];
    }
    collisions_ = std::make_unique<CollisionStatistics>(std::move(cs), 0.0);
    record_.enabled = true;
  }
  const auto& c = spec_.output.continuum;
  if (!c || spec_.simulation.engine == Engine::HardSphere) return;
  // Discrete-to-continuum averages [Zhu07 Tables 5-6] on cells over the whole domain.
  ContinuumGrid grid;
  grid.cells = c->cells;
  grid.lo = spec_.domain.lo;
  grid.periodic = spec_.domain.periodic;
  grid.dimension = spec_.simulation.dimension;
  for (int a = 0; a < 3; ++a)
    grid.spacing[a] = (spec_.domain.hi[a] - spec_.domain.lo[a]) / c->cells[a];
  ContinuumSettings settings;
  settings.method =
      c->method == ContinuumMethod::Weighted ? AveragingMethod::Weighted : AveragingMethod::Volume;
  settings.width = c->width;
  settings.cutoff = c->cutoff;
  try {
    continuum_ = std::make_unique<ContinuumAverager>(grid, settings);
  } catch (const std::invalid_argument& e) {
    throw InputError(spec_.where("output.continuum"), "output.continuum", e.what());
  }
  continuum_interval_ = c->interval > 0.0 ? c->interval : spec_.output.frame_interval;
}

bool Simulation::choose_rank_independent() const {
  const Communicator& world = Communicator::world();
  const bool hard = spec_.simulation.engine == Engine::HardSphere;
  if (hard && world.size() > 1)
    throw InputError(spec_.where("simulation.engine"), "simulation.engine",
                     "\"hard_sphere\" runs on one rank (its collisions are processed one at a "
                     "time in one global order of events, which ranks cannot share out); run it "
                     "without mpirun, or use simulation.engine = \"soft_sphere\"");
  const bool ri =
      !hard && spec_.parallel.rank_independent.value_or(Communicator::launched_by_mpirun());
  if (!ri && world.size() > 1)
    throw InputError(spec_.where("parallel.rank_independent"), "parallel.rank_independent",
                     "false cannot run on " + std::to_string(world.size()) +
                         " ranks (the single-process engine does not share out); set it true "
                         "or \"auto\", or run without mpirun");
  return ri;
}

void Simulation::set_up_stepper(std::unique_ptr<ContactTable> table, bool sort_first, double skin,
                                double max_diameter) {
  const bool rank_independent = choose_rank_independent(); // (refuses what ranks cannot run)
  if (table && rank_independent) {
    comm_ = &Communicator::world();
    DistributedSoftSphere::Settings d;
    d.dt = dt_;
    d.skin = skin; // "auto" is the fixed default here (one skin for all ranks and builds)
    d.gravity = spec_.simulation.gravity;
    d.process_grid = spec_.parallel.process_grid;
    d.balance_interval = spec_.parallel.balance_interval;
    d.body = spec_.body_force ? &*spec_.body_force : nullptr;
    d.noncontact = spec_.noncontact.any_conservative() ? &spec_.noncontact : nullptr;
    if (const auto& b = spec_.noncontact.liquid_bridge) {
      d.liquid_bridge = &*b;
      d.liquid_fraction = liquid_fractions(spec_);
    }
    if (spec_.gas && spec_.coupling.forces.any()) { // their state travels with the particles
      d.held_torques = spec_.coupling.forces.torque != "off";
      d.attached_width = static_cast<int>(FluidForces::width(spec_.coupling.forces));
    }
    if (d.noncontact) try { // (the cut-off checked before the engine is built)
        noncontact_reach(*d.noncontact, restart_state_ ? restart_state_->particles : p_);
      } catch (const std::invalid_argument& e) {
        throw InputError(spec_.where("electrostatics"), "electrostatics", e.what());
      }
    // The index space the ranks share: cells about as wide as a list cell (the largest pair's
    // reach), so that a rank's ghosts come from its neighbours.
    d.cells.lo = spec_.domain.lo;
    d.cells.hi = spec_.domain.hi;
    d.cells.periodic = spec_.domain.periodic;
    for (std::size_t a = 0; a < 3; ++a) {
      const double n =
          std::floor((spec_.domain.hi[a] - spec_.domain.lo[a]) / (max_diameter + skin));
      d.cells.cells[a] = (a == 1 && spec_.simulation.dimension == 2) || n < 1.0
                             ? 1
                             : static_cast<int>(std::min(n, 1e6));
    }
    std::unique_ptr<DistributedSoftSphere> dist;
    try {
      dist = restart_state_ ? std::make_unique<DistributedSoftSphere>(
                                  *comm_, std::move(table), limits_.box, d, *restart_state_)
                            : std::make_unique<DistributedSoftSphere>(*comm_, std::move(table),
                                                                      limits_.box, d, p_);
    } catch (const std::invalid_argument& e) { // no process grid fits
      throw InputError(spec_.where("parallel.process_grid"), "parallel.process_grid", e.what());
    }
    dist_ = dist.get();
    stepper_ = std::move(dist);
    report_.skin = skin;
    return;
  }
  if (!table) {
    auto hard = std::make_unique<HardSphereStepper>(spec_, limits_.box, dt_, p_, forces_,
                                                    collisions_ != nullptr);
    hard_ = hard.get();
    stepper_ = std::move(hard);
    return;
  }
  SoftSphereStepper::Settings s;
  s.dt = dt_;
  s.skin = skin;
  s.auto_skin = !spec_.neighbour.skin;
  s.max_diameter = max_diameter;
  s.sort_interval = spec_.neighbour.sort_interval;
  s.sort_first = sort_first;
  s.auto_skin_steps = kAutoSkinSteps;
  // The contacts are recorded when an analysis uses them: the collision statistics every step,
  // the continuum averages on their sampled steps (StepNeeds::record_contacts).
  ContactRecord* record = collisions_ || continuum_ ? &record_ : nullptr;
  auto soft =
      std::make_unique<SoftSphereStepper>(std::move(table), limits_.box, s, p_, forces_, record);
  soft_ = soft.get();
  stepper_ = std::move(soft);
  report_.skin = soft_->list().skin(); // the first build's
}

void Simulation::set_up_noncontact(double skin) {
  const NonContactSpec& nc = spec_.noncontact;
  const std::string key = nc.van_der_waals    ? "van_der_waals"
                          : nc.electrostatics ? "electrostatics"
                                              : "liquid_bridge";
  if (hard_)
    throw InputError(spec_.where(key), key,
                     "the hard-sphere engine has no non-contact forces (its particles meet only "
                     "in instantaneous collisions, so a force across a gap cannot act); use "
                     "simulation.engine = \"soft_sphere\"");
  try {
    if (nc.any_conservative() && !dist_) // (the rank-independent engine evaluates them itself)
      add_force_source(std::make_unique<NonContactForceSource>(limits_.box, nc, p_, skin));
  } catch (const std::invalid_argument& e) {
    throw InputError(spec_.where(key), key, e.what());
  }
  if (nc.liquid_bridge && !dist_) { // (the rank-independent engine evaluates them itself)
    auto source = std::make_unique<LiquidBridgeSource>(limits_.box, *nc.liquid_bridge,
                                                       liquid_fractions(spec_), p_, skin);
    bridges_ = &source->bridges();
    add_force_source(std::move(source));
  }
}

void Simulation::add_force_source(std::unique_ptr<ForceSource> source) {
  if (dist_)
    throw std::logic_error("Simulation::add_force_source: the rank-independent engine takes no "
                           "force sources yet");
  if (hard_ && dynamic_cast<const StepForceSource*>(source.get()) != nullptr)
    throw std::logic_error("Simulation::add_force_source: hard spheres take held forces only");
  forces_.add(std::move(source));
  forces_.refresh(p_.size());
  if (soft_ && forces_.any_step_sources()) soft_->evaluate_step_sources(time_);
}

void Simulation::step(bool defer_second_kick) {
  if (gas_ && step_ % steps_per_flow_ == 0) flow_step(); // its forces act over the next DT
  const bool sample_continuum = continuum_samples_next_step();
  stepper_->step(time_,
                 {defer_second_kick, collisions_ != nullptr || sample_continuum, sample_continuum});
  ++step_;
  time_ = static_cast<double>(step_) * dt_;
  feed_analyses(sample_continuum);
}

void Simulation::flow_step() {
  if (dist_) {
    // Every rank steps its copy of the gas from the sums over all ranks' particles (fixed
    // point: the same bits on every rank count, GasCoupling::distribute), and holds the forces
    // on its own particles over the flow step.
    const auto t0 = WallClock::now();
    ++flow_steps_;
    dist_->own_particles(coupled_);
    const bool fluid = gas_->fluid_state_width() > 0; // [coupling.forces]: their state travels
    if (fluid) gas_->load_fluid_state(dist_->attached(), coupled_.size());
    gas_->step(coupled_, time_, dt_ * static_cast<double>(steps_per_flow_));
    dist_->hold_own_forces({gas_->force(0).data(), gas_->force(1).data(), gas_->force(2).data()});
    if (fluid && gas_->torque(0))
      dist_->hold_own_torques({gas_->torque(0), gas_->torque(1), gas_->torque(2)});
    if (fluid) gas_->save_fluid_state(dist_->attached());
    t_gas_ += seconds_since(t0);
    return;
  }
  stepper_->finish_kick(); // the gas step reads the particles' full-step velocities
  const auto t0 = WallClock::now();
  gas_->step(p_, time_, dt_ * static_cast<double>(steps_per_flow_));
  forces_.refresh(p_.size());
  t_gas_ += seconds_since(t0);
}

void Simulation::feed_analyses(bool sampled_continuum) {
  if (dist_) {
    feed_analyses_on_ranks(sampled_continuum);
    return;
  }
  if (sampled_continuum) // positions and contacts of the step, full-step velocities
    continuum_->accumulate(p_, record_.samples);
  if (!collisions_) return;
  if (hard_) {
    instant_.clear();
    for (const HardSphereCollision& c : hard_->engine().last_step_collisions())
      instant_.push_back({c.id_a, c.id_b, c.point});
    collisions_->add_instant_step(instant_, p_, time_);
  } else {
    collisions_->add_step(record_, p_, time_);
  }
}

// The ranks' contacts (each pair once, from its lower id's row), the particles in the
// collision regions and, on the continuum averages' sampled steps, all particles go to the root,
// which keeps both analyses: contacts sorted by ids and particles in id order there, so the same
// bits on any number of ranks (docs/parallel.md).
void Simulation::feed_analyses_on_ranks(bool sampled_continuum) {
  if (!collisions_ && !sampled_continuum) return;
  std::vector<KeyedContact> contacts = dist_->gather_contacts();
  if (comm_->root())
    std::sort(contacts.begin(), contacts.end(), [](const KeyedContact& x, const KeyedContact& y) {
      return x.a != y.a ? x.a < y.a : x.b < y.b;
    });
  if (sampled_continuum) { // positions and contacts of the step, full-step velocities
    const DistributedState all = dist_->gather();
    if (comm_->root()) {
      const ParticleStore& q = all.particles;
      const auto index_of = [&](std::int64_t id) {
        return static_cast<std::int32_t>(std::lower_bound(q.id.begin(), q.id.end(), id) -
                                         q.id.begin());
      };
      record_.samples.clear();
      for (const KeyedContact& k : contacts) {
        ContactSample& c = record_.samples.emplace_back();
        c.id_i = k.a, c.id_j = k.b;
        c.i = index_of(k.a), c.j = k.b >= 0 ? index_of(k.b) : -1;
        c.overlap = k.overlap, c.normal = k.normal, c.force = k.force;
        c.torque_roll = k.torque_roll, c.contact_point = k.contact_point;
      }
      continuum_->accumulate(q, record_.samples);
    }
  }
  if (!collisions_) return;
  const ParticleStore in_regions =
      collisions_->settings().regions.empty()
          ? ParticleStore{}
          : dist_->gather_where([&](const Vec3& x) { return collisions_->in_a_region(x); });
  if (comm_->root()) collisions_->add_keyed_step(contacts, in_regions, time_);
}

bool Simulation::continuum_samples_next_step() const {
  return continuum_ && (step_ + 1) % spec_.output.continuum->stride == 0;
}

Energies Simulation::energies() const {
  Energies e = particle_energies(p_, spec_.simulation.gravity);
  if (forces_.any_particle_forces()) e.potential += forces_.potential_energy(p_);
  if (dist_) e.potential += dist_->noncontact_potential();
  return e;
}

double Simulation::bed_height() const {
  const auto& g = spec_.simulation.gravity;
  const int axis = gravity_axis(g);
  const bool upward = g[static_cast<std::size_t>(axis)] <= 0.0;
  const double floor = upward ? spec_.domain.lo[static_cast<std::size_t>(axis)]
                              : spec_.domain.hi[static_cast<std::size_t>(axis)];
  return fluidem::bed_height(p_, axis, floor, upward, spec_.simulation.dimension == 2);
}

void Simulation::check_stability() {
  stepper_->finish_kick();
  if (!dist_) {
    fluidem::check_stability(p_, contact_stats(), limits_, time_, step_);
    return;
  }
  // Each rank checks its own particles and contacts; the first rank's message (in rank order)
  // stops every rank alike.
  std::string error;
  try {
    fluidem::check_stability(dist_->local(), dist_->local_stats(), limits_, time_, step_,
                             dist_->owned());
  } catch (const InstabilityError& e) {
    error = e.what();
  }
  if (comm_->any(!error.empty())) {
    std::string first;
    for (const auto& m : comm_->gather(std::span<const char>(error.data(), error.size())))
      if (first.empty()) first.assign(m.begin(), m.end());
    throw InstabilityError(comm_->broadcast(first));
  }
}

void Simulation::advance(long n) {
  for (long k = 0; k < n; ++k) {
    step(k + 1 < n); // the last step's second kick not deferred
    if (contact_stats().max_overlap_ratio > spec_.contact.max_overlap) check_stability();
  }
}

long Simulation::spatial_sorts() const {
  return soft_ ? soft_->sorts() : hard_ ? hard_->sorts() : 0;
}

long Simulation::total_steps() const {
  return static_cast<long>(std::ceil(spec_.simulation.end_time / dt_ - 1e-9));
}

OutputLayout Simulation::output_layout() const {
  return RunRecorder::layout(*this);
}

double Simulation::output_bytes_needed() const {
  return RunRecorder::bytes_needed(*this);
}

RunSummary Simulation::run(const std::string& out_dir,
                           const std::function<void(const RunStatus&)>& progress,
                           const RunOptions& options) {
  // The directory, locked for the run: the caller's (which checked it), or taken here (a new
  // run then replaces whatever results were there).
  std::optional<OutputDirectory> own_dir;
  if (options.directory == nullptr && options.write_outputs) {
    own_dir.emplace(out_dir, "this run");
    own_dir->refuse_links();
    if (!options.resume) own_dir->remove_results();
  }
  // The outputs are opened (or checked for a continued run) by the root alone: a refusal
  // there stops every rank alike.
  std::optional<RunRecorder> opened;
  std::string refused;
  try {
    opened.emplace(*this,
                   !options.write_outputs ? nullptr
                   : options.directory    ? options.directory
                                          : &*own_dir,
                   options.resume);
  } catch (const InputError& e) {
    if (!dist_) throw;
    refused = e.what();
  }
  if (dist_ && comm_->any(!refused.empty())) throw InputError(comm_->broadcast(refused));
  RunRecorder& recorder = *opened;
  const long total = total_steps();
  const long check_every = 100;
  const long progress_every = std::max(1L, std::min(200L, 2000000L / std::max<long>(1, p_.size())));
  const auto report_progress = [&] {
    if (progress) progress({step_, total, time_, spec_.simulation.end_time, p_.size()});
  };
  const auto start = WallClock::now();
  const long step0 = step_, folded0 = folded_steps();
  int stopped_by = 0;
  // A continued run's checkpoint was taken after its step's outputs were written: they are in the
  // files already (writing them again would repeat the last row and frame).
  if (!options.resume) recorder.write_due();
  report_progress();
  try {
    check_stability();
    while (step_ < total) {
      step(true); // its second half kick done by the next step, or by check_stability()
      if (step_ % check_every == 0 || contact_stats().max_overlap_ratio > spec_.contact.max_overlap)
        check_stability();
      recorder.write_due();
      if (step_ % progress_every == 0 || step_ == total) report_progress();
      if (options.stop) stopped_by = options.stop->load();
      if (dist_) // every rank stops at the same step
        stopped_by = static_cast<int>(comm_->max(static_cast<double>(stopped_by)));
      if (stopped_by != 0) break;
      if (recorder.checkpoint_due()) recorder.checkpoint();
    }
    recorder.checkpoint(); // at the end, or where a signal stopped the run
  } catch (...) {
    recorder.close_quietly(); // what was written is flushed; the error says what went wrong
    throw;
  }
  recorder.close();
  RunSummary s =
      summary(step_ - step0, seconds_since(start), recorder.seconds(), folded_steps() - folded0);
  s.stopped_by_signal = stopped_by;
  if (dist_) {
    s.rank_independent = true;
    s.ranks = comm_->size();
    const double mine = stepper_->seconds().contacts;
    const double mean =
        static_cast<double>(comm_->sum(static_cast<std::int64_t>(mine * 1e9))) / 1e9 / s.ranks;
    s.imbalance = mean > 0.0 ? comm_->max(mine) / mean : 1.0;
    s.particle_steps_per_second = static_cast<double>(s.steps) *
                                  static_cast<double>(report_.particle_count) /
                                  std::max(comm_->max(s.wall_seconds), 1e-9);
    const double steps = std::max(1.0, static_cast<double>(s.steps));
    const auto mean_of = [&](double v) {
      return static_cast<double>(comm_->sum(static_cast<std::int64_t>(v))) / s.ranks / steps;
    };
    s.bytes_per_rank_step = mean_of(dist_->bytes_sent());
    s.messages_per_rank_step = mean_of(dist_->messages_sent());
    s.rebalances = dist_->rebalances();
    if (gas_ && flow_steps_ > 0) {
      s.gas_sum_bytes_per_flow_step =
          gas_->bytes_summed_over_ranks() / static_cast<double>(flow_steps_);
      s.gas_sums_per_flow_step =
          static_cast<double>(gas_->sums_over_ranks()) / static_cast<double>(flow_steps_);
    }
  }
  s.checkpoint = recorder.last_checkpoint();
  return s;
}

RunSummary Simulation::summary(long steps, double seconds, double seconds_output,
                               long folded) const {
  RunSummary s;
  const double n = static_cast<double>(p_.size());
  s.steps = steps;
  s.wall_seconds = seconds;
  s.particle_steps_per_second = static_cast<double>(steps) * n / std::max(seconds, 1e-9);
  s.neighbour_builds = hard_ ? hard_->engine().list_builds() : neighbour_builds();
  s.spatial_sorts = spatial_sorts();
  s.folded_steps = folded;
  const ParticleStepper::Seconds t = stepper_->seconds();
  s.seconds_contacts = t.contacts;
  s.seconds_integration = t.integration;
  s.seconds_neighbour = t.neighbour;
  s.seconds_step_sources = t.step_sources;
  s.seconds_output = seconds_output;
  s.seconds_gas = t_gas_;
  s.seconds_gas_solver = gas_ ? gas_->solver_seconds() : 0.0;
  s.seconds_gas_pressure = gas_ ? gas_->pressure_seconds() : 0.0;
  s.bytes_per_particle = dist_       ? stepper_->bytes() / std::max<std::size_t>(1, dist_->owned())
                         : p_.size() ? (p_.bytes() + stepper_->bytes()) / p_.size()
                                     : 0;
  if (hard_) {
    s.collisions = hard_->engine().stats().collisions;
  } else {
    s.pairs_per_particle = neighbour_pairs_per_particle();
    s.walls_per_particle = n > 0 ? static_cast<double>(neighbour_wall_entries()) / n : 0.0;
    s.contacts = contact_stats().n_contacts;
  }
  const Energies e = energies();
  s.energy_drift = (e.kinetic + e.rotational + e.potential + contact_stats().elastic_energy +
                    dissipated_energy() - clock_.e0) /
                   clock_.escale;
  return s;
}

} // namespace fluidem
