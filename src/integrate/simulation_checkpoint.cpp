// Checkpoint and restart of a Simulation (simulation.hpp): what the state of a run is, written
// to and read from the checkpoint file (output/checkpoint_file.hpp).
//
// The state: the resolved case (so the restart needs no case file), the step counter, the
// particle arrays (positions, velocities, angular velocities, forces and torques of the last
// step, radii, masses, inverse masses and inertias, species, ids, layers), the contact statistics
// and dissipated energy, the neighbour list (its build positions and skin, from which the same
// pairs are rebuilt, and the contact histories of every pair and wall entry), the hard-sphere
// engine's state (last-collision times of the TC model, counters, list), the gas fields
// (velocity, pressure, porosity new and old, density) and the gas force on each particle, and
// the output schedule, and the collision statistics when they are on (ongoing contacts and
// accumulators, so that collisions.csv continues exactly). There is no random-number generator in a
// running simulation (random insertion happens before step 0), so none is stored. What is NOT
// stored is rebuilt from it: cell grids, the event calendar (rebuilt every flow step), and the gas
// solver's multigrid set-ups, which the run writing the checkpoint drops too
// (GasSolver::reset_solver_history), so both continue bitwise alike.
#include <fmt/format.h>

#include <optional>

#include "core/error.hpp"
#include "fluidem_version.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"
#include "io/case_writer.hpp"
#include "noncontact/liquid_bridges.hpp"
#include "output/checkpoint_file.hpp"

namespace fluidem {

namespace {

/// A neighbour list's State or StateView.
template <class ListState>
void put_list(CheckpointWriter& w, const std::string& prefix, const ListState& s) {
  w.put_scalar(prefix + "/skin", s.skin);
  w.put_scalar(prefix + "/builds", s.builds);
  // views: `s` outlives the writer's commit (write_checkpoint)
  w.put_view(prefix + "/x0", s.x0);
  w.put_view(prefix + "/y0", s.y0);
  w.put_view(prefix + "/z0", s.z0);
  w.put_view(prefix + "/offset", s.offset);
  w.put_view(prefix + "/partner", s.partner);
  w.put_view(prefix + "/wall_particle", s.wall_particle);
  w.put_view(prefix + "/wall_face", s.wall_face);
  w.put_view(prefix + "/history", s.history);
  w.put_view(prefix + "/wall_history", s.wall_history);
}

NeighbourList::State get_list(const CheckpointReader& r, const std::string& prefix) {
  NeighbourList::State s;
  s.skin = r.scalar(prefix + "/skin");
  s.builds = r.integer(prefix + "/builds");
  s.x0 = r.doubles(prefix + "/x0");
  s.y0 = r.doubles(prefix + "/y0");
  s.z0 = r.doubles(prefix + "/z0");
  s.offset = r.uint32s(prefix + "/offset");
  s.partner = r.uint32s(prefix + "/partner");
  s.wall_particle = r.uint32s(prefix + "/wall_particle");
  s.wall_face = r.bytes(prefix + "/wall_face");
  s.history = r.doubles(prefix + "/history");
  s.wall_history = r.doubles(prefix + "/wall_history");
  return s;
}

/// The particle arrays of type double, by name.
template <class Store>
auto double_arrays(Store& p) {
  return std::array<std::pair<const char*, decltype(&p.x)>, 13>{{{"x", &p.x},
                                                                 {"y", &p.y},
                                                                 {"z", &p.z},
                                                                 {"vx", &p.vx},
                                                                 {"vy", &p.vy},
                                                                 {"vz", &p.vz},
                                                                 {"wx", &p.wx},
                                                                 {"wy", &p.wy},
                                                                 {"wz", &p.wz},
                                                                 {"radius", &p.radius},
                                                                 {"mass", &p.mass},
                                                                 {"inv_mass", &p.inv_mass},
                                                                 {"inv_inertia", &p.inv_inertia}}};
}

/// The contact forces and torques the next kick uses (ContactScratch::acc entries 0..5), as
/// particle arrays of the checkpoint.
const char* const kContactForce[6] = {"fx", "fy", "fz", "tx", "ty", "tz"};

const char* const kGasVelocity[3] = {"gas/u_x", "gas/u_y", "gas/u_z"};
const char* const kGasForce[3] = {"gas/force_x", "gas/force_y", "gas/force_z"};

/// Only simulation.end_time and output.* may change at a restart (InputError otherwise).
void check_restart_overrides(const std::vector<std::string>& overrides) {
  for (const std::string& o : overrides) {
    const std::string key = o.substr(0, o.find('='));
    if (key != "simulation.end_time" && key.rfind("output.", 0) != 0 &&
        key.rfind("parallel.", 0) != 0)
      throw InputError(fmt::format("--set {}: a restarted run continues the checkpointed one; "
                                   "only simulation.end_time, output.* and parallel.* may change",
                                   o));
    if (key.rfind("output.continuum", 0) == 0) // its grid and sums are in the checkpoint
      throw InputError(fmt::format("--set {}: the continuum averaging of a restarted run is the "
                                   "checkpointed one (its sums are in the checkpoint)",
                                   o));
    if (key == "output.layers") // the layers are those of t = 0, kept in the checkpoint
      throw InputError(fmt::format("--set {}: the layers are assigned at t = 0; a restarted run "
                                   "keeps those of the checkpointed one",
                                   o));
  }
}

/// The particle store of the checkpoint, and the contact forces and torques of its last step.
ParticleStore read_particles(const CheckpointReader& r, const std::string& checkpoint,
                             std::array<std::vector<double>, 6>& contact_force) {
  ParticleStore p;
  for (const auto& [name, v] : double_arrays(p)) *v = r.doubles(std::string("particles/") + name);
  p.species = r.int32s("particles/species");
  p.id = r.int64s("particles/id");
  // Checkpoints written before layers existed hold none: every particle in layer 0.
  p.layer = r.has("particles/layer") ? r.int32s("particles/layer")
                                     : std::vector<std::int32_t>(p.id.size(), 0);
  // Checkpoints written before charges existed hold none: every particle uncharged.
  p.charge = r.has("particles/charge") ? r.doubles("particles/charge")
                                       : std::vector<double>(p.id.size(), 0.0);
  for (std::size_t a = 0; a < 6; ++a) {
    contact_force[a] = r.doubles(std::string("particles/") + kContactForce[a]);
    if (contact_force[a].size() != p.id.size())
      throw CheckpointError(fmt::format("checkpoint '{}': particle array '{}' has {} entries for "
                                        "{} particles",
                                        checkpoint, kContactForce[a], contact_force[a].size(),
                                        p.id.size()));
  }
  for (const auto& [name, v] : double_arrays(p))
    if (v->size() != p.id.size() || p.species.size() != p.id.size() ||
        p.layer.size() != p.id.size() || p.charge.size() != p.id.size())
      throw CheckpointError(fmt::format("checkpoint '{}': particle array '{}' has {} entries for "
                                        "{} particles",
                                        checkpoint, name, v->size(), p.id.size()));
  return p;
}

/// What the outputs held at the checkpoint (empty for checkpoints without a run ID: they
/// cannot resume in place).
OutputMarks read_marks(const CheckpointReader& r) {
  OutputMarks marks;
  if (!r.has("outputs/run_id")) return marks;
  marks.run_id = r.string("outputs/run_id");
  marks.frame_times = r.doubles("run/clock/frame_times");
  marks.continuum_times = r.doubles("outputs/continuum_times");
  const std::string names = r.string("outputs/csv_names");
  for (std::size_t at = 0, end = 0; (end = names.find('\n', at)) != std::string::npos;
       at = end + 1) {
    const std::string name = names.substr(at, end - at);
    const std::string key = "outputs/csv/" + name;
    marks.csv[name] = {static_cast<std::uint64_t>(r.integer(key + "/bytes")),
                       static_cast<std::uint64_t>(r.integer(key + "/hash"))};
  }
  return marks;
}

HardSphereEngine::State read_hard_sphere(const CheckpointReader& r, const std::string& checkpoint) {
  HardSphereEngine::State h;
  h.last_collision = r.doubles("hardsphere/last_collision");
  h.built_x = r.doubles("hardsphere/built_x");
  h.built_y = r.doubles("hardsphere/built_y");
  h.built_z = r.doubles("hardsphere/built_z");
  h.counter = r.uint32s("hardsphere/counter");
  h.list_builds = r.integer("hardsphere/list_builds");
  const auto c = r.int64s("hardsphere/stats/counts");
  const auto e = r.doubles("hardsphere/stats/energies");
  if (c.size() != 5 || e.size() != 2)
    throw CheckpointError("checkpoint '" + checkpoint + "': bad hard-sphere statistics");
  h.stats.collisions = static_cast<long>(c[0]);
  h.stats.wall_collisions = static_cast<long>(c[1]);
  h.stats.tc_elastic = static_cast<long>(c[2]);
  h.stats.slow_elastic = static_cast<long>(c[3]);
  h.stats.events_last_step = static_cast<long>(c[4]);
  h.stats.dissipated = e[0];
  h.stats.tc_energy_kept = e[1];
  h.list = get_list(r, "hardsphere/list");
  if (r.has("hardsphere/skin_probe")) { // (checkpoints before the skin policy: no probe yet)
    const auto probe = r.doubles("hardsphere/skin_probe");
    if (probe.size() != 5)
      throw CheckpointError("checkpoint '" + checkpoint + "': bad hard-sphere skin probe");
    h.skin_probe = {static_cast<std::int64_t>(probe[0]), probe[1], probe[2],
                    static_cast<std::int64_t>(probe[3])};
    h.list_steps = static_cast<std::int64_t>(probe[4]);
  }
  return h;
}

CollisionStatistics::State read_collisions(const CheckpointReader& r) {
  CollisionStatistics::State c;
  c.keys = r.int64s("collisions/keys");
  c.ongoing = r.doubles("collisions/ongoing");
  c.counters = r.int64s("collisions/counters");
  c.sums = r.doubles("collisions/sums");
  c.histogram = r.int64s("collisions/histogram");
  return c;
}

GasCoupling::State read_gas(const CheckpointReader& r, const std::string& checkpoint,
                            const GasCoupling& gas) {
  GasCoupling::State g;
  for (const std::string& name : gas.fluid_state_names()) // [coupling.forces]
    g.fluid.emplace_back(name, r.doubles("gas/fluid/" + name));
  for (int d = 0; d < 3; ++d) {
    g.gas.u[static_cast<std::size_t>(d)] = r.doubles(kGasVelocity[d]);
    g.force[static_cast<std::size_t>(d)] = r.doubles(kGasForce[d]);
  }
  g.gas.p = r.doubles("gas/p");
  g.gas.eps = r.doubles("gas/eps");
  g.gas.eps_old = r.doubles("gas/eps_old");
  g.gas.rho = r.doubles("gas/rho");
  g.gas.last_iterations = r.integer("gas/last_iterations");
  const auto diag = r.doubles("gas/diagnostics");
  if (diag.size() != 3)
    throw CheckpointError("checkpoint '" + checkpoint + "': bad gas diagnostics");
  g.gas.last_mass_residual = diag[0];
  g.gas.last_velocity_change = diag[1];
  g.gas.boundary_outflow = diag[2];
  return g;
}

} // namespace

void Simulation::write_checkpoint(const std::string& path) {
  stepper_->finish_kick(); // the full-step velocities (and their dissipated energy) are the state
  // A distributed run's state, gathered on the root in id order with the contact histories
  // keyed by partner id: the same file whatever the number of ranks (only the root writes).
  DistributedState gathered;
  if (dist_) {
    gathered = dist_->gather(true);
    if (!comm_->root()) {
      if (gas_) gas_->reset_solver_history(); // as the root does after writing (below)
      return;
    }
  }
  const ParticleStore& parts = dist_ ? gathered.particles : p_;
  const ContactStats& stats = contact_stats();
  CheckpointWriter w(path);
  w.put_string("meta/fluidem_version", kVersion);
  w.put_string("case/resolved", write_case_toml(resolved_case()));
  w.put_scalar("run/step", static_cast<std::int64_t>(step_));
  w.put_scalar("run/time", time_);
  w.put_scalar("run/dt", dt_);
  w.put_scalar("run/e_dsp", dissipated_energy());
  w.put_scalar("run/clock/next_frame", clock_.next_frame);
  w.put_scalar("run/clock/next_series", clock_.next_series);
  w.put_scalar("run/clock/next_checkpoint", clock_.next_checkpoint);
  w.put_scalar("run/clock/e0", clock_.e0);
  w.put_scalar("run/clock/escale", clock_.escale);
  w.put_scalar("run/clock/started", static_cast<std::int64_t>(clock_.started));
  // What the outputs hold at this step (output/run_outputs.hpp): a restart continues exactly
  // those files, and refuses others.
  const OutputMarks marks = outputs_ ? outputs_->marks() : OutputMarks{};
  w.put_string("outputs/run_id", marks.run_id);
  w.put("run/clock/frame_times", marks.frame_times);
  w.put("outputs/continuum_times", marks.continuum_times);
  std::string csv_names;
  for (const auto& [name, mark] : marks.csv) {
    csv_names += name + "\n";
    w.put_scalar("outputs/csv/" + name + "/bytes", static_cast<std::int64_t>(mark.bytes));
    w.put_scalar("outputs/csv/" + name + "/hash", static_cast<std::int64_t>(mark.hash));
  }
  w.put_string("outputs/csv_names", csv_names);
  if (continuum_) { // the sums of the averaging interval in progress
    w.put_scalar("run/clock/next_continuum", clock_.next_continuum);
    w.put("continuum/sums", continuum_->state().sums);
    w.put_scalar("continuum/samples", static_cast<std::int64_t>(continuum_->state().samples));
  }
  w.put_scalar("stats/n_contacts", static_cast<std::int64_t>(stats.n_contacts));
  w.put_scalar("stats/max_overlap_ratio", stats.max_overlap_ratio);
  w.put_scalar("stats/max_overlap_particle", static_cast<std::int64_t>(stats.max_overlap_particle));
  w.put_scalar("stats/elastic_energy", stats.elastic_energy);
  w.put_scalar("stats/spring_losses", stats.spring_losses);
  // The particle arrays and the list's state as views (no second copy of the run's largest
  // arrays while the checkpoint is written); they stay unchanged until w.commit() below.
  for (const auto& [name, v] : double_arrays(parts))
    w.put_view(std::string("particles/") + name, *v);
  // zero for the hard-sphere engine, which keeps no contact forces
  static_assert(ContactScratch::kAcc == OrderedContactSums::kAcc);
  const std::vector<double>& acc = dist_ ? gathered.contact : contact_sums();
  const bool have_forces = acc.size() == ContactScratch::kAcc * parts.size();
  std::array<std::vector<double>, 6> contact_force;
  for (std::size_t a = 0; a < 6; ++a) {
    contact_force[a].assign(parts.size(), 0.0);
    if (have_forces)
      for (std::size_t i = 0; i < parts.size(); ++i)
        contact_force[a][i] = acc[ContactScratch::kAcc * i + a];
    w.put_view(std::string("particles/") + kContactForce[a], contact_force[a]);
  }
  w.put_view("particles/species", parts.species);
  w.put_view("particles/id", parts.id);
  w.put_view("particles/layer", parts.layer);
  w.put_view("particles/charge", parts.charge);
  if (dist_) { // what continues the rank-independent engine bitwise on any number of ranks
    w.put_view("rank_independent/contact", gathered.contact);
    w.put_view("rank_independent/elastic", gathered.elastic);
    w.put_view("rank_independent/dissipated", gathered.dissipated);
    w.put_view("rank_independent/x0", gathered.x0);
    w.put_view("rank_independent/history/offset", gathered.history.offset);
    w.put_view("rank_independent/history/key", gathered.history.key);
    w.put_view("rank_independent/history/values", gathered.history.values);
    w.put_scalar("rank_independent/builds", gathered.builds);
    if (!gathered.bridge_force.empty()) { // the liquid bridges, keyed as the contact histories
      w.put_view("rank_independent/bridge_force", gathered.bridge_force);
      w.put_view("rank_independent/bridges/offset", gathered.bridges.offset);
      w.put_view("rank_independent/bridges/key", gathered.bridges.key);
      w.put_view("rank_independent/bridges/values", gathered.bridges.values);
    }
  }
  if (soft_) // the list's own arrays, unchanged until commit
    put_list(w, "neighbour", soft_->list().state_view());
  if (bridges_) // which pairs hold a bridge: the history of their list
    put_list(w, "liquid_bridges", bridges_->list().state_view());
  // The forces of the sources evaluated every step, as the next kick uses them (a source's
  // forces may depend on the half-step velocities, which the checkpoint does not hold).
  const auto& step_sources = forces_.step_sources();
  for (std::size_t k = 0; k < step_sources.size(); ++k)
    for (std::size_t a = 0; a < 3; ++a)
      w.put_view(fmt::format("step_sources/{}/force_{}", k, "xyz"[a]),
                 step_sources[k]->forces()[a]);
  HardSphereEngine::State h; // its list goes in as views: alive until w.commit()
  if (hard_) {
    h = hard_->engine().state();
    w.put("hardsphere/last_collision", h.last_collision);
    w.put("hardsphere/built_x", h.built_x);
    w.put("hardsphere/built_y", h.built_y);
    w.put("hardsphere/built_z", h.built_z);
    w.put("hardsphere/counter", h.counter);
    w.put_scalar("hardsphere/list_builds", h.list_builds);
    w.put("hardsphere/stats/counts",
          std::vector<std::int64_t>{h.stats.collisions, h.stats.wall_collisions, h.stats.tc_elastic,
                                    h.stats.slow_elastic, h.stats.events_last_step});
    w.put("hardsphere/stats/energies",
          std::vector<double>{h.stats.dissipated, h.stats.tc_energy_kept});
    put_list(w, "hardsphere/list", h.list);
    w.put("hardsphere/skin_probe",
          std::vector<double>{static_cast<double>(h.skin_probe.build), h.skin_probe.long_entries,
                              h.skin_probe.short_entries, static_cast<double>(h.skin_probe.life),
                              static_cast<double>(h.list_steps)});
  }
  if (collisions_) { // the ongoing contacts and the accumulators of the statistics
    const CollisionStatistics::State c = collisions_->state();
    w.put("collisions/keys", c.keys);
    w.put("collisions/ongoing", c.ongoing);
    w.put("collisions/counters", c.counters);
    w.put("collisions/sums", c.sums);
    w.put("collisions/histogram", c.histogram);
  }
  if (gas_) {
    const GasCoupling::State g = gas_->state();
    for (int d = 0; d < 3; ++d) {
      w.put(kGasVelocity[d], g.gas.u[static_cast<std::size_t>(d)]);
      if (!dist_) {
        w.put(kGasForce[d], g.force[static_cast<std::size_t>(d)]);
        continue;
      }
      // Ranks: each holds its own particles' forces; the gathered ones, in id order.
      std::vector<double> f(parts.size());
      for (std::size_t i = 0; i < f.size(); ++i)
        f[i] = gathered.held[3 * i + static_cast<std::size_t>(d)];
      w.put(kGasForce[d], f);
    }
    w.put("gas/p", g.gas.p);
    w.put("gas/eps", g.gas.eps);
    w.put("gas/eps_old", g.gas.eps_old);
    w.put("gas/rho", g.gas.rho);
    w.put_scalar("gas/last_iterations", g.gas.last_iterations);
    w.put("gas/diagnostics",
          std::vector<double>{g.gas.last_mass_residual, g.gas.last_velocity_change,
                              g.gas.boundary_outflow});
    // Ranks: the fluid forces' state of every particle, gathered with them (id order).
    const auto fluid = dist_ && gas_->fluid_forces()
                           ? gas_->fluid_forces()->unpacked(gathered.attached, parts.size())
                           : g.fluid;
    for (const auto& [name, v] : fluid) w.put("gas/fluid/" + name, v);
  }
  w.commit();
  // A synchronisation point: the run that continues from here and one restarted from the
  // file both start the next flow step with fresh linear-solver set-ups.
  if (gas_) gas_->reset_solver_history();
}

std::unique_ptr<Simulation> Simulation::restart(const std::string& checkpoint,
                                                const std::vector<std::string>& overrides) {
  const CheckpointReader r(checkpoint);
  check_restart_overrides(overrides);
  CaseSpec spec = read_case_string(r.string("case/resolved"), checkpoint, overrides);
  std::array<std::vector<double>, 6> contact_force;
  const ParticleStore p = read_particles(r, checkpoint, contact_force);
  // A rank-independent run continues from its gathered state on any number of ranks.
  std::optional<DistributedState> state;
  if (r.has("rank_independent/contact")) {
    state.emplace();
    state->particles = p;
    state->contact = r.doubles("rank_independent/contact");
    state->elastic = r.doubles("rank_independent/elastic");
    state->dissipated = r.doubles("rank_independent/dissipated");
    state->x0 = r.doubles("rank_independent/x0");
    state->history.offset = r.uint32s("rank_independent/history/offset");
    state->history.key = r.int64s("rank_independent/history/key");
    state->history.values = r.doubles("rank_independent/history/values");
    state->builds = r.integer("rank_independent/builds");
    const std::size_t n = p.size();
    const KeptHistory& h = state->history;
    if (state->contact.size() != 12 * n || state->elastic.size() != n ||
        state->dissipated.size() != n || state->x0.size() != 3 * n || h.offset.size() != n + 1 ||
        h.offset.back() != h.key.size() ||
        (h.key.empty() ? !h.values.empty() : h.values.size() % h.key.size() != 0))
      throw CheckpointError("checkpoint '" + checkpoint +
                            "': its rank-independent state does not match its particles");
    state->history.width = h.key.empty() ? 0 : static_cast<int>(h.values.size() / h.key.size());
    if (r.has("rank_independent/bridge_force")) {
      state->bridge_force = r.doubles("rank_independent/bridge_force");
      KeptHistory& b = state->bridges;
      b.width = 1;
      b.offset = r.uint32s("rank_independent/bridges/offset");
      b.key = r.int64s("rank_independent/bridges/key");
      b.values = r.doubles("rank_independent/bridges/values");
      if (state->bridge_force.size() != 3 * n || b.offset.size() != n + 1 ||
          b.offset.back() != b.key.size() || b.values.size() != b.key.size())
        throw CheckpointError("checkpoint '" + checkpoint +
                              "': its liquid bridges do not match its particles");
    }
  }
  // "auto" continues on the engine that wrote the checkpoint.
  if (!spec.parallel.rank_independent) spec.parallel.rank_independent = state.has_value();
  std::unique_ptr<Simulation> sim(new Simulation(std::move(spec), &p, state ? &*state : nullptr));
  if (state.has_value() != sim->rank_independent())
    throw InputError(fmt::format(
        "checkpoint '{}' was written by the {} engine; continue it with parallel.rank_independent "
        "= {} (--set parallel.rank_independent={})",
        checkpoint, state ? "rank-independent" : "single-process", state ? "true" : "false",
        state ? "true" : "false"));
  Simulation& s = *sim;
  const double dt = r.scalar("run/dt");
  if (dt != s.dt_)
    throw CheckpointError(fmt::format("checkpoint '{}': its time step {:.17g} s differs from the "
                                      "one its case gives, {:.17g} s",
                                      checkpoint, dt, s.dt_));
  s.p_ = p; // the constructor computed forces and moved nothing; the saved arrays win
  if (s.soft_) {
    ContactScratch& nc = s.soft_->scratch();
    nc.resize(p.size());
    for (std::size_t a = 0; a < 6; ++a)
      for (std::size_t i = 0; i < p.size(); ++i)
        nc.acc[ContactScratch::kAcc * i + a] = contact_force[a][i];
  }
  s.step_ = static_cast<long>(r.integer("run/step"));
  s.time_ = static_cast<double>(s.step_) * s.dt_;
  if (s.total_steps() <= s.step_)
    throw InputError(fmt::format(
        "simulation.end_time = {:.6g} s is not after the time of checkpoint '{}', t = {:.6g} s "
        "(step {}): there is nothing to run; continue with --set simulation.end_time=T, T > "
        "{:.6g}",
        s.spec_.simulation.end_time, checkpoint, s.time_, s.step_, s.time_));
  if (s.soft_) s.soft_->set_dissipated_energy(r.scalar("run/e_dsp")); // (hard: the engine's)
  s.clock_.next_frame = r.scalar("run/clock/next_frame");
  s.clock_.next_series = r.scalar("run/clock/next_series");
  s.clock_.next_checkpoint = r.scalar("run/clock/next_checkpoint");
  s.clock_.e0 = r.scalar("run/clock/e0");
  s.clock_.escale = r.scalar("run/clock/escale");
  s.clock_.started = r.integer("run/clock/started") != 0;
  s.marks_ = read_marks(r);
  if (s.soft_) {
    ContactStats& stats = s.soft_->stats();
    stats.n_contacts = static_cast<long>(r.integer("stats/n_contacts"));
    stats.max_overlap_ratio = r.scalar("stats/max_overlap_ratio");
    stats.max_overlap_particle = static_cast<long>(r.integer("stats/max_overlap_particle"));
    stats.elastic_energy = r.scalar("stats/elastic_energy");
    stats.spring_losses = r.scalar("stats/spring_losses");
  }
  try {
    if (s.continuum_) {
      if (r.has("continuum/sums")) {
        s.continuum_->set_state({r.doubles("continuum/sums"), r.integer("continuum/samples")});
        s.clock_.next_continuum = r.scalar("run/clock/next_continuum");
      } else { // a checkpoint without continuum averages: the first interval starts here
        s.clock_.next_continuum = s.time_ + s.continuum_interval_;
      }
    }
    if (s.soft_) s.soft_->list().restore(s.p_, get_list(r, "neighbour"));
    if (s.bridges_) s.bridges_->list().restore(s.p_, get_list(r, "liquid_bridges"));
    const auto& step_sources = s.forces_.step_sources();
    for (std::size_t k = 0; k < step_sources.size(); ++k)
      for (std::size_t a = 0; a < 3; ++a) {
        const std::string name = fmt::format("step_sources/{}/force_{}", k, "xyz"[a]);
        std::vector<double> f = r.doubles(name);
        if (f.size() != s.p_.size())
          throw CheckpointError(fmt::format("checkpoint '{}': '{}' has {} entries for {} "
                                            "particles",
                                            checkpoint, name, f.size(), s.p_.size()));
        step_sources[k]->forces()[a] = std::move(f);
      }
    s.forces_.refresh(s.p_.size());
    if (s.hard_) s.hard_->engine().restore(s.p_, read_hard_sphere(r, checkpoint));
    // Collision statistics: continued when the checkpoint holds them; a run that switches
    // them on at the restart (--set output.collisions=true) starts them there.
    if (s.collisions_ && r.has("collisions/counters"))
      s.collisions_->restore(read_collisions(r));
    else if (s.collisions_)
      s.collisions_ = std::make_unique<CollisionStatistics>(s.collisions_->settings(), s.time_);
    if (s.gas_) s.gas_->restore(read_gas(r, checkpoint, *s.gas_));
    if (s.gas_ && s.dist_) { // the forces held over the flow step, from the gas's (id order)
      s.dist_->hold_forces(
          s.p_, {s.gas_->force(0).data(), s.gas_->force(1).data(), s.gas_->force(2).data()});
      if (s.gas_->fluid_state_width() > 0) { // [coupling.forces]: their state and torque
        std::vector<double> packed(s.gas_->fluid_state_width() * s.p_.size());
        s.gas_->save_fluid_state(packed);
        s.dist_->set_attached(s.p_, packed);
        if (s.gas_->torque(0))
          s.dist_->hold_torques(s.p_, {s.gas_->torque(0), s.gas_->torque(1), s.gas_->torque(2)});
      }
    }
  } catch (const CheckpointError&) {
    throw;
  } catch (const std::exception& e) {
    throw CheckpointError("checkpoint '" + checkpoint + "': " + e.what());
  }
  return sim;
}

} // namespace fluidem
