#include "app/cli.hpp"

#include <omp.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "app/analyse.hpp"
#include "app/busy_machine.hpp"
#include "app/progress.hpp"
#include "app/signals.hpp"
#include "app/validate.hpp"
#include "contact/contact_models.hpp"
#include "core/error.hpp"
#include "fluidem_version.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"
#include "output/checkpoint_file.hpp"
#include "output/output_directory.hpp"
#include "parallel/communicator.hpp"

namespace fluidem {

namespace {

/// The contact sub-models, and the coefficients they take, as the models declare them.
void print_contact_models(const CaseSpec& spec) {
  namespace cm = contact_models;
  const cm::Chosen chosen = cm::choose(spec);
  fmt::print("contact model      normal {}, tangential {}, rolling {}\n", chosen.normal->name,
             chosen.tangential->name, chosen.rolling->name);
  for (const cm::Kind kind : cm::kKinds) {
    const cm::ModelInfo& m = chosen.of(kind);
    fmt::print("  {} {}: {}{}{}\n", cm::kind_key(kind), m.name, m.summary,
               m.mixing.empty() ? "" : "; mixing: ", m.mixing);
    for (const cm::Coefficient& k : m.coefficients) {
      if (k.given == cm::Given::AutoOnly) continue; // derived by the model
      const auto v = cm::coefficient(cm::of(spec.contact, kind).coefficients, std::string(k.key));
      fmt::print("    contact.{:<23} {}{}{} ({})\n", k.key, v ? fmt::format("{:.6g}", *v) : "auto",
                 k.unit.empty() || !v ? "" : " ", v ? k.unit : std::string_view{}, k.meaning);
    }
  }
}

/// [coarse_graining]: what the run simulates (the contact values printed are the parcels').
void print_coarse_graining(const CaseSpec& spec) {
  const CoarseGrainingSpec& cg = spec.coarse_graining;
  if (!cg.active()) return;
  fmt::print("coarse graining    parcels of W = {:.6g} real particles (diameter x {:.6g}) "
             "[Chang08 §2.2.3]; contact scaling {}, drag at the {} diameter "
             "(docs/coarse-graining.md); the contact values below are the parcels'\n",
             cg.ratio, coarse_graining::diameter_factor(cg.ratio), to_string(cg.contact_scaling),
             to_string(cg.drag_diameter));
}

void print_gas_report(const CaseSpec& spec, const CaseReport& r) {
  if (!spec.gas) return;
  const auto& g = *spec.gas;
  const bool two_d = spec.simulation.dimension == 2;
  fmt::print("gas                {} cells ({}), model {}, {}, viscosity {:.4g} Pa s\n",
             two_d ? fmt::format("{} x {}", g.cells[0], g.cells[2])
                   : fmt::format("{} x {} x {}", g.cells[0], g.cells[1], g.cells[2]),
             two_d ? "x-z plane" : "3-D", g.model == gas::PressureModel::A ? "A" : "B",
             g.eos == gas::EquationOfState::ideal_gas ? "ideal gas" : "incompressible",
             g.viscosity);
  const int scheme = spec.coupling.scheme == coupling::ExchangeScheme::scheme1   ? 1
                     : spec.coupling.scheme == coupling::ExchangeScheme::scheme2 ? 2
                                                                                 : 3;
  fmt::print("coupling           {}, drag {}, porosity {}, exchange scheme {} [Zhu07 §3.2]\n",
             coupling::to_string(spec.coupling.mode), spec.coupling.drag,
             coupling::to_string(spec.coupling.porosity.method), scheme);
  const coupling::FluidForceSettings& ff = spec.coupling.forces;
  std::string particle_force(
      spec.coupling.particle_force
          ? coupling::to_string(*spec.coupling.particle_force)
          : (g.model == gas::PressureModel::A ? "pressure_gradient" : "buoyancy"));
  if (ff.virtual_mass)
    particle_force += fmt::format(", virtual mass C = {:.3g}", ff.virtual_mass_coefficient);
  if (ff.basset) particle_force += fmt::format(", Basset (window {} flow steps)", ff.basset_window);
  if (ff.saffman) particle_force += ", Saffman-Mei lift";
  if (ff.magnus != "off") particle_force += ", Magnus lift (" + ff.magnus + ")";
  if (ff.torque != "off") particle_force += ", fluid torque (" + ff.torque + ")";
  fmt::print("particle force     {}\n", particle_force);
  fmt::print("gas time step DT   {:.4g} s", r.flow_time_step);
  if (spec.simulation.engine == Engine::SoftSphere)
    fmt::print(" ({} DEM steps each)", r.steps_per_flow_step);
  fmt::print("\n");
}

void print_report(const CaseSpec& spec, const CaseReport& r) {
  fmt::print("case               {}\n", spec.source_file);
  fmt::print("dimension          {} ({})\n", spec.simulation.dimension,
             spec.simulation.dimension == 2 ? "discs in the x-z plane" : "spheres");
  fmt::print("particle engine    {}\n", to_string(spec.simulation.engine));
  print_coarse_graining(spec);
  if (spec.simulation.engine == Engine::HardSphere) {
    fmt::print("collisions         event-driven, e_n / mu / beta_0 per material [Deen07 eq. "
               "17-21]; TC model tc_time = {:.3g} s\n",
               spec.hardsphere.tc_time);
    fmt::print("particles          {}\n", r.particle_count);
    fmt::print("total mass         {:.6g} kg\n", r.total_mass);
    fmt::print("flow time step DT  {:.4g} s\n", r.chosen_time_step);
    fmt::print("steps              {:.0f}\n", spec.simulation.end_time / r.chosen_time_step);
    print_gas_report(spec, r);
    return;
  }
  print_contact_models(spec);
  fmt::print("particles          {}\n", r.particle_count);
  fmt::print("total mass         {:.6g} kg\n", r.total_mass);
  if (contact_models::choose(spec).normal->uses_impact_speed)
    fmt::print("impact speed       {:.4g} m/s (for Hertz contact durations)\n",
               r.characteristic_velocity);
  fmt::print("contact duration per pair:\n");
  for (const auto& d : r.durations) fmt::print("  {:<28} {:.4g} s\n", d.pair, d.duration);
  fmt::print("largest stable dt  {:.4g} s (shortest contact / 10)\n", r.stable_time_step);
  fmt::print("chosen dt          {:.4g} s{}\n", r.chosen_time_step,
             r.time_step_forced ? "  (FORCED above the stability limit)" : "");
  fmt::print("steps              {:.0f}\n", spec.simulation.end_time / r.chosen_time_step);
  fmt::print("expected overlap   {:.3g} of a diameter under the bed's own weight\n",
             r.expected_overlap_ratio);
  fmt::print("neighbour skin     {:.4g} m\n", r.skin);
  print_gas_report(spec, r);
}

std::string default_out_dir(const std::string& case_path) {
  return (std::filesystem::path("out") / std::filesystem::path(case_path).stem()).string();
}

/// Before a run, with the directory locked: it must not hold another run's results (unless
/// `force`: they are removed, but only once every other check has passed), must hold no link
/// under fluidem's file names, must be writable and should have room for the outputs
/// (InputError otherwise).
void prepare_out_dir(const OutputDirectory& dir, bool force, bool resuming, const Simulation& sim) {
  dir.refuse_links();
  std::vector<std::string> found;
  if (!resuming) found = dir.present_results();
  if (!found.empty() && !force)
    throw InputError(fmt::format(
        "output directory '{}' holds the results of another run ({}); use --force to "
        "overwrite them, --restart {}/checkpoint.h5 to continue that run, or --out elsewhere",
        dir.path(), fmt::join(found, ", "), dir.path()));
  dir.check_writable();
  const double need = sim.output_bytes_needed();
  const double freed = found.empty() ? 0.0 : static_cast<double>(dir.present_bytes());
  const double available = static_cast<double>(dir.available_bytes()) + freed;
  if (available < need)
    throw InputError(fmt::format(
        "not enough disk space in '{}': the run needs about {:.3g} MB for its outputs, {:.3g} MB "
        "are free{} (write fewer frames or rows with output.frame_interval and "
        "output.series_interval, or use --out elsewhere)",
        dir.path(), need / 1e6, available / 1e6,
        freed > 0.0 ? " counting the results --force would remove" : ""));
  if (!found.empty()) dir.remove_results(); // --force, and every check passed
}

/// --threads: a whole number from 1 to 1024 (0 or negative, or text, named in the message).
std::string check_threads(const std::string& text) {
  std::size_t used = 0;
  long n = 0;
  try {
    n = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || n < 1 || n > 1024)
    return fmt::format("--threads {}: give a whole number of threads from 1 to 1024 (leave "
                       "--threads out to use every core)",
                       text);
  return {};
}

/// The options of `fluidem run`.
struct RunArgs {
  std::string case_path, out_dir, restart_path;
  std::vector<std::string> overrides;
  int threads = 0;
  bool force = false;
};

/// The log of a finished run: where the time went, the counts, the main files.
void print_run_summary(const Simulation& sim, const RunSummary& s, const std::string& out_dir) {
  fmt::print("done: {} steps in {:.3f} s wall, {:.4g} particle-steps/s\n", s.steps, s.wall_seconds,
             s.particle_steps_per_second);
  if (s.rank_independent)
    fmt::print("ranks {}: {:.4g} particle-steps/s per rank; imbalance {:.3f} (the slowest rank's "
               "contact time over the mean)\n",
               s.ranks, s.particle_steps_per_second / s.ranks, s.imbalance);
  if (s.rank_independent && s.ranks > 1)
    fmt::print("exchange: {:.4g} bytes and {:.3g} messages per rank and step (ghosts, particles "
               "changing rank); {} moves of the cut planes\n",
               s.bytes_per_rank_step, s.messages_per_rank_step, s.rebalances);
  if (s.rank_independent && s.ranks > 1 && s.gas_sums_per_flow_step > 0.0)
    fmt::print("gas sums: {:.4g} bytes in {:.3g} reductions per rank and flow step (fixed-point "
               "deposition summed over the ranks)\n",
               s.gas_sum_bytes_per_flow_step, s.gas_sums_per_flow_step);
  // Where the time went: the particles (contacts, integration and lists; the event-driven
  // engine does all three), the gas solver, the coupling (porosity, forces both ways, the
  // gas kicks) and the output.
  const std::string gas_time =
      sim.gas()
          ? fmt::format(", gas solver {:.3f} s (pressure solve {:.3f} s{}), coupling {:.3f} s",
                        s.seconds_gas_solver, s.seconds_gas_pressure,
                        s.ranks <= 1 ? ""
                        : sim.gas()->solver().distributed()
                            ? "; the gas step shared by the ranks' z planes"
                            : "; it and the momentum solves shared by the ranks",
                        s.seconds_gas - s.seconds_gas_solver)
          : "";
  if (sim.hard_sphere())
    fmt::print("time in the collision engine {:.3f} s (events and neighbour lists, {} builds), "
               "output {:.3f} s{}\n",
               s.seconds_contacts + s.seconds_integration + s.seconds_neighbour, s.neighbour_builds,
               s.seconds_output, gas_time);
  else
    fmt::print("time in contacts {:.3f} s, integration {:.3f} s, neighbour lists {:.3f} s "
               "({} builds{}),{} output {:.3f} s{}\n",
               s.seconds_contacts, s.seconds_integration, s.seconds_neighbour, s.neighbour_builds,
               s.spatial_sorts > 0 ? fmt::format(", {} spatial sorts", s.spatial_sorts) : "",
               s.seconds_step_sources > 0.0
                   ? fmt::format(" non-contact forces {:.3f} s,", s.seconds_step_sources)
                   : "",
               s.seconds_output, gas_time);
  if (s.folded_steps > 0)
    fmt::print("integration folded into the contact loop on {} of {} steps (its time counted "
               "in contacts)\n",
               s.folded_steps, s.steps);
  if (s.collisions == 0 && s.pairs_per_particle > 0.0)
    fmt::print("neighbour pairs {:.2f} and wall entries {:.2f} per particle, {} contacts (pairs "
               "and walls) at the end\n",
               s.pairs_per_particle, s.walls_per_particle, s.contacts);
  if (s.collisions > 0)
    fmt::print("{} collisions, {:.4g} collisions per second of wall time\n", s.collisions,
               static_cast<double>(s.collisions) / std::max(s.wall_seconds, 1e-9));
  if (sim.gas()) // the gas does work on the particles: their energy sum is not conserved
    fmt::print("memory {} bytes per particle\n", s.bytes_per_particle);
  else
    fmt::print("memory {} bytes per particle; energy balance drift {:.3g} (relative)\n",
               s.bytes_per_particle, s.energy_drift);
  fmt::print("results: {}/particles.h5 (+ particles.xmf for ParaView), {}/series.csv\n", out_dir,
             out_dir);
  fmt::print("         {} (continue with --restart and --set simulation.end_time=...)\n",
             s.checkpoint);
  if (sim.gas())
    fmt::print("         {}/fields.h5 (+ fields.xmf){}\n", out_dir,
               sim.spec().output.probes.empty() ? "" : fmt::format(", {}/probes.csv", out_dir));
}

/// The files of the analyses that ran with the run.
void print_analysis_files(const Simulation& sim, const std::string& out_dir) {
  if (sim.collisions())
    fmt::print("         {}/collisions.csv, {}/collision_overlap.csv\n", out_dir, out_dir);
  if (sim.continuum())
    fmt::print("         {}/continuum.h5 (+ continuum.xmf for ParaView)\n", out_dir);
}

/// `fluidem run`: a case, or a checkpoint to continue, into its output directory; the exit
/// code.
int run_command(RunArgs& a) {
  if (a.threads > 0) omp_set_num_threads(a.threads);
  if (a.threads > omp_get_num_procs())
    fmt::print(stderr,
               "warning: --threads {} on a machine with {} cores: the results are the same, "
               "but threads that share a core wait for each other (--threads {} is faster)\n",
               a.threads, omp_get_num_procs(), omp_get_num_procs());
  std::unique_ptr<Simulation> sim_owner;
  bool resuming = false;
  if (!a.restart_path.empty()) {
    const std::string ckpt_dir = std::filesystem::path(a.restart_path).parent_path().string();
    if (a.out_dir.empty()) a.out_dir = ckpt_dir.empty() ? "." : ckpt_dir;
    std::error_code ec;
    resuming = std::filesystem::equivalent(a.out_dir, ckpt_dir.empty() ? "." : ckpt_dir, ec);
    try {
      sim_owner = Simulation::restart(a.restart_path, a.overrides);
    } catch (const CheckpointError& e) {
      throw InputError(e.what());
    }
  } else {
    if (a.out_dir.empty()) a.out_dir = default_out_dir(a.case_path);
    sim_owner = std::make_unique<Simulation>(read_case_file(a.case_path, a.overrides));
  }
  Simulation& sim = *sim_owner;
  // A distributed run's root writes and prints; the other ranks compute with it, silently. The
  // root's checks of the directory decide for all of them (every rank stops alike).
  const Communicator& ranks = sim.communicator();
  std::optional<OutputDirectory> locked;
  std::string refused;
  if (ranks.root()) try {
      // Locked for the run (and its analysis) before anything in it is looked at.
      locked.emplace(a.out_dir, "this run");
      prepare_out_dir(*locked, a.force, resuming, sim);
    } catch (const InputError& e) {
      refused = e.what();
    }
  refused = ranks.broadcast(refused);
  if (!refused.empty()) throw InputError(refused);
  if (!ranks.root()) {
    RunOptions ro;
    ro.write_outputs = false;
    ro.stop = &install_stop_handlers(false); // the root announces the stop
    const RunSummary s = sim.run(a.out_dir, {}, ro);
    remove_stop_handlers();
    return s.stopped_by_signal != 0 ? 128 + s.stopped_by_signal : 0;
  }
  const OutputDirectory& dir = *locked;
  print_report(sim.spec(), sim.report());
  fmt::print("threads            {}{}\noutput             {}\n", omp_get_max_threads(),
             sim.rank_independent() ? " per rank" : "", a.out_dir);
  if (const DistributedSoftSphere* d = sim.distributed()) {
    const auto g = d->decomposition().process_grid();
    fmt::print("ranks              {} (process grid {} x {} x {}), rank-independent results\n",
               ranks.size(), g[0], g[1], g[2]);
  }
  if (omp_get_max_threads() > 1)
    if (const auto busy = busy_cores(200))
      if (const auto w = busy_machine_warning(*busy, omp_get_num_procs(), omp_get_max_threads()))
        fmt::print(stderr, "{}\n", *w);
  if (!a.restart_path.empty())
    fmt::print("restart            from {} at t = {:.6g} s (step {}){}\n", a.restart_path,
               sim.time(), sim.step_count(),
               resuming ? ", appending to the outputs there" : ", new output files");
  std::fflush(stdout);
  ProgressDisplay progress(stdout);
  RunSummary s;
  RunOptions ro;
  ro.resume = resuming;
  ro.directory = &dir;
  ro.stop = &install_stop_handlers();
  try {
    s = sim.run(
        a.out_dir, [&](const RunStatus& st) { progress(st); }, ro);
  } catch (const InstabilityError&) {
    remove_stop_handlers();
    progress.finish();
    throw;
  }
  remove_stop_handlers();
  progress.finish();
  if (s.stopped_by_signal != 0) {
    const int sig = s.stopped_by_signal;
    fmt::print(stderr,
               "stopped by {} at t = {:.6g} s (step {}): checkpoint {}, outputs flushed in "
               "{}\ncontinue with: fluidem run --restart {}\n",
               sig == SIGINT    ? "SIGINT"
               : sig == SIGTERM ? "SIGTERM"
               : sig == SIGUSR1 ? "SIGUSR1"
                                : "a signal",
               sim.time(), sim.step_count(), s.checkpoint, a.out_dir, s.checkpoint);
    return 128 + sig;
  }
  print_run_summary(sim, s, a.out_dir);
  if (sim.spec().output.analyse) { // output.analyse: the run's analysis, as `fluidem analyse`
    AnalyseOptions ao;
    ao.out_dir = a.out_dir;
    ao.directory = &dir;
    fmt::print("analysis (output.analyse = true):\n");
    try {
      analyse(ao);
    } catch (const InputError& e) { // the run's results are safe: say why, keep exit 0
      fmt::print(stderr,
                 "warning: the analysis was not written: {}\n(run `fluidem analyse {} "
                 "--from T0 --to T1` with another window)\n",
                 e.what(), a.out_dir);
    }
  }
  print_analysis_files(sim, a.out_dir);
  return 0;
}

} // namespace

namespace {
/// The exit code of an error on this rank: an error only this rank met (an output the root could
/// not write, an unexpected failure) ends every rank of a distributed run (MPI_Abort), which the
/// others would wait for; errors every rank meets alike (input, instability) return it.
int end_ranks(int code, bool every_rank) {
  const Communicator& world = Communicator::world();
  if (!every_rank && world.size() > 1) world.abort(code);
  return code;
}
} // namespace

int run_cli(int argc, char** argv) {
  const Communicator& world = Communicator::world();
  CLI::App app{
      "fluidem: discrete particle simulation of gas-fluidised beds (CFD-DEM)\n"
      "Exit codes: 0 success, 2 invalid input, 3 run stopped because it went unstable, 4 an "
      "output could not be written (disk full, I/O error), 130/143/138 stopped by "
      "SIGINT/SIGTERM/SIGUSR1 (under mpirun: SIGUSR1, see docs/parallel.md).",
      "fluidem"};
  app.set_version_flag("--version", std::string("fluidem ") + kVersion);
  app.require_subcommand(1);

  RunArgs a;
  auto* run = app.add_subcommand("run", "Run a case and write its results to OUT");
  auto* case_opt = run->add_option("case", a.case_path, "Case file (TOML)");
  auto* restart_opt =
      run->add_option("--restart", a.restart_path,
                      "Continue the run saved in this checkpoint (OUT/checkpoint.h5) instead of "
                      "starting a case; --set may then change only simulation.end_time and "
                      "output.*");
  case_opt->excludes(restart_opt);
  run->add_flag("--force", a.force, "Overwrite the results of another run in the output directory");
  auto* out_opt =
      run->add_option("--out,-o", a.out_dir, "Output directory (default: out/<case name>)");
  run->add_option("--set", a.overrides,
                  "Override a case value: section.key=value (repeatable), e.g. "
                  "--set simulation.end_time=0.5");
  run->add_option("--threads,-t", a.threads, "OpenMP threads, 1 to 1024 (default: all cores)")
      ->check(CLI::Validator(check_threads, "1..1024", "threads"))
      ->type_name("N");

  std::string check_path;
  std::vector<std::string> check_overrides;
  auto* check = app.add_subcommand("check", "Validate a case and print its derived quantities");
  check->add_option("case", check_path, "Case file (TOML)")->required();
  check->add_option("--set", check_overrides, "Override a case value: section.key=value");
  const auto analysis = add_analysis_commands(app); // analyse, plot (app/analyse.hpp)
  const auto validate = add_validate_command(app);  // validate (app/validate.hpp)

  // A first word that is not an option nor a command: say so (CLI11 would ask for a command).
  if (argc > 1 && argv[1][0] != '-') {
    const std::string word = argv[1];
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) known = known || sub->check_name(word);
    if (!known) {
      std::vector<std::string> names;
      for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
      fmt::print(stderr, "error: unknown command '{}'; the commands are {} (fluidem --help)\n",
                 word, fmt::join(names, ", "));
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
    if (*run && out_opt->count() > 0 && a.out_dir.empty())
      throw CLI::ValidationError("--out", "the output directory is an empty path");
    if (*run && a.case_path.empty() && a.restart_path.empty())
      throw CLI::RequiredError("a case file (or --restart CHECKPOINT)");
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }

  try {
    if (analysis->selected()) return analysis->run(argv[0]);
    if (validate->selected()) return validate->run(argv[0]);
    if (*check) {
      const CaseSpec spec = read_case_file(check_path, check_overrides);
      Simulation sim(spec);
      if (!world.root()) return 0;
      print_report(sim.spec(), sim.report());
      fmt::print("case is valid\n");
      return 0;
    }
    return run_command(a);
  } catch (const InputError& e) {
    if (world.root()) fmt::print(stderr, "error: {}\n", e.what());
    return end_ranks(2, true);
  } catch (const InstabilityError& e) {
    if (world.root())
      fmt::print(stderr,
                 "error: {}\nthe outputs up to the last good frame are in {}; the last good "
                 "checkpoint (if one was written) is {}/checkpoint.h5\n",
                 e.what(), a.out_dir, a.out_dir);
    return end_ranks(3, true);
  } catch (const OutputError& e) {
    fmt::print(stderr,
               "error: {}\nthe run stopped; the last good checkpoint (if one was written) is "
               "{}/checkpoint.h5: continue with fluidem run --restart {}/checkpoint.h5 once "
               "there is room\n",
               e.what(), a.out_dir, a.out_dir);
    return end_ranks(4, false);
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return end_ranks(1, false);
  }
}

} // namespace fluidem
