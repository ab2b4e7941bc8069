#include "integrate/run_recorder.hpp"
#include "integrate/wall_clock.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "fluidem_version.hpp"
#include "integrate/simulation.hpp"
#include "io/case_writer.hpp"
#include "output/fields_writer.hpp"
#include "output/h5md_writer.hpp"
#include "output/series_writer.hpp"
#include "particles/id_order.hpp"

namespace fluidem {

namespace {

std::array<const double*, 3> pointers(const std::array<std::vector<double>, 3>& v) {
  return {v[0].data(), v[1].data(), v[2].data()};
}

/// OUT/collision_overlap.csv: the overlap-extent histogram of all pair collisions ended since
/// t = 0 (bins [bin_lo, bin_hi) of max overlap / smaller diameter; the last row, bin_hi = inf,
/// counts the extents above the range); fraction = count / all ended pair collisions.
void write_overlap_histogram(const std::string& path, const CollisionStatistics& c) {
  SeriesWriter w(path, {"bin_lo", "bin_hi", "count", "fraction"});
  const auto& h = c.histogram();
  const std::size_t nb = h.size() - 1;
  const double width = c.settings().histogram_max / static_cast<double>(nb);
  std::int64_t total = 0;
  for (const auto k : h) total += k;
  for (std::size_t k = 0; k <= nb; ++k) {
    const double lo = static_cast<double>(k) * width;
    const double hi =
        k < nb ? static_cast<double>(k + 1) * width : std::numeric_limits<double>::infinity();
    const auto count = static_cast<double>(h[k]);
    w.write_row({lo, hi, count, total > 0 ? count / static_cast<double>(total) : 0.0});
  }
  w.close();
}

/// The case file's absolute path for the outputs' header ("" for a case not read from a file).
std::string absolute_case_file(const std::string& source) {
  std::error_code ec;
  // A run continued from a checkpoint into a new directory has no case file of its own; a path
  // with a line break cannot stand in the header's comment line.
  if (std::filesystem::path(source).extension() != ".toml" ||
      !std::filesystem::is_regular_file(source, ec))
    return {};
  const std::string p = std::filesystem::absolute(source, ec).lexically_normal().string();
  return ec || p.find_first_of("\r\n") != std::string::npos ? std::string() : p;
}

/// The schedule's next mark after t: the first k * interval (k a whole number) above t + eps.
/// The marks are anchored at t = 0, so that round-off does not build up over a long run: adding
/// the interval mark after mark drifted by tens of ulps over thousands of rows, until a step
/// time that sat on a mark fell short of it and every later row came one step late (the 1 kHz
/// probes of chang08/spouted_loop.toml from 5.026 s to 9.79 s, which a spectrum refused).
double next_mark(double t, double interval, double eps) {
  double k = std::floor((t + eps) / interval) + 1.0;
  while (k > 1.0 && (k - 1.0) * interval > t + eps) k -= 1.0; // (round-off of the division)
  while (k * interval <= t + eps) k += 1.0;
  return k * interval;
}

} // namespace

RunRecorder::RunRecorder(Simulation& sim, const OutputDirectory* dir, bool resume)
    : sim_(sim), dir_(dir), eps_(1e-9 * sim.dt_), total_(sim.total_steps()) {
  if (dir)
    outputs_.emplace(resume ? RunOutputs::resume(*dir, layout(sim), sim.marks_,
                                                 write_case_toml(sim.resolved_case()), kVersion)
                            : RunOutputs::start(*dir, layout(sim),
                                                write_case_toml(sim.resolved_case()), kVersion,
                                                absolute_case_file(sim.spec().source_file)));
  sim_.outputs_ = outputs_ ? &*outputs_ : nullptr;
  OutputClock& clock = sim_.clock_;
  if (sim_.continuum_ && !clock.started)
    clock.next_continuum = sim_.time_ + sim_.continuum_interval_;
  if (!clock.started) {
    clock.next_frame = clock.next_series = sim_.time_;
    clock.next_checkpoint = sim_.time_ + sim_.spec_.output.checkpoint_interval;
  }
}

RunRecorder::~RunRecorder() {
  sim_.outputs_ = nullptr; // the outputs live as long as the recorder
}

void RunRecorder::write_due() {
  const OutputClock& clock = sim_.clock_;
  const double t = sim_.time_;
  const bool last = sim_.step_ == total_;
  // Nothing unstable reaches the files: check before any row or frame is written (which also
  // finishes a pending half kick: its time counted as integration, not output).
  const bool continuum_due = sim_.continuum_ && t >= clock.next_continuum - eps_;
  const bool series_due = t >= clock.next_series - eps_ || last;
  const bool frame_due = t >= clock.next_frame - eps_ || last;
  if (series_due || frame_due || continuum_due) sim_.stepper_->finish_kick();
  const auto t0 = WallClock::now();
  if (series_due || frame_due || continuum_due) {
    sim_.check_stability();
    sim_.observe(); // a distributed run's particles and totals, gathered for the writers
  }
  if (series_due) write_series_rows();
  if (frame_due) write_frame();
  if (continuum_due) write_continuum_frame();
  sim_.clock_.started = true;
  seconds_ += seconds_since(t0);
}

void RunRecorder::write_series_rows() {
  OutputClock& clock = sim_.clock_;
  const double t = sim_.time_;
  clock.next_series = next_mark(t, sim_.spec_.output.series_interval, eps_);
  const Energies e = sim_.energies();
  const ContactStats& stats = sim_.contact_stats();
  const double e_dsp = sim_.dissipated_energy();
  const double tot = e.kinetic + e.rotational + e.potential + stats.elastic_energy + e_dsp;
  if (!clock.started) {
    clock.e0 = tot;
    clock.escale = std::max(std::abs(tot), 1e-300);
  }
  std::vector<double> row{t,
                          e.kinetic,
                          e.rotational,
                          e.potential,
                          stats.elastic_energy,
                          e_dsp,
                          tot,
                          static_cast<double>(stats.n_contacts),
                          stats.max_overlap_ratio,
                          static_cast<double>(sim_.neighbour_builds())};
  if (const HardSphereEngine* hard = sim_.hard_sphere()) {
    const auto& h = hard->stats();
    row[7] = static_cast<double>(h.events_last_step);
    row[9] = static_cast<double>(hard->list_builds());
    row.insert(row.end(), {static_cast<double>(h.collisions), static_cast<double>(h.tc_elastic),
                           static_cast<double>(h.slow_elastic), h.tc_energy_kept});
  }
  if (const GasCoupling* gas = sim_.gas()) {
    row.insert(row.end(), {gas->pressure_drop(), sim_.bed_height(),
                           static_cast<double>(gas->solver().last_iterations()),
                           gas->superficial_velocity(t)});
    if (outputs_ && outputs_->has_csv("probes.csv")) {
      std::vector<double> prow{t};
      const std::vector<double> pp = gas->probe_pressures();
      prow.insert(prow.end(), pp.begin(), pp.end());
      outputs_->csv("probes.csv").write_row(prow);
    }
  }
  if (!outputs_) return; // a rank that writes nothing (the values were computed with the root)
  outputs_->csv("series.csv").write_row(row);
  if (outputs_->has_csv("collisions.csv")) {
    const CollisionStatistics::Row c = sim_.collisions_->take_row(t, sim_.p_.size());
    std::vector<double> crow{t,
                             static_cast<double>(c.pair_collisions),
                             static_cast<double>(c.wall_collisions),
                             c.frequency,
                             c.mean_free_time,
                             c.mean_overlap,
                             c.max_overlap,
                             c.mean_duration};
    const bool soft = sim_.collisions_->settings().soft_spheres;
    if (soft)
      crow.insert(crow.end(), {static_cast<double>(c.pair_collisions_ended),
                               static_cast<double>(c.multiple_collisions)});
    for (const auto& r : c.regions) {
      crow.insert(crow.end(), {r.frequency, r.void_fraction, r.particles});
      if (soft)
        crow.insert(crow.end(), {static_cast<double>(r.ended), static_cast<double>(r.multiple)});
    }
    outputs_->csv("collisions.csv").write_row(crow);
  }
}

const std::vector<std::uint32_t>* RunRecorder::output_order() {
  const ParticleStore& p = sim_.p_;
  const long sorts = sim_.spatial_sorts();
  if (order_sorts_ != sorts) { // frames list the particles by id, whatever the store's order
    order_.clear();
    if (!std::is_sorted(p.id.begin(), p.id.end())) order_ = id_order(p);
    order_sorts_ = sorts;
  }
  return order_.empty() ? nullptr : &order_;
}

void RunRecorder::write_frame() {
  OutputClock& clock = sim_.clock_;
  const double t = sim_.time_;
  clock.next_frame = next_mark(t, sim_.spec_.output.frame_interval, eps_);
  if (!outputs_) return;
  H5mdWriter& h5 = outputs_->particles();
  h5.write_frame(sim_.step_, t, sim_.p_, output_order());
  h5.flush();
  if (FieldsWriter* fields = outputs_->fields()) {
    sim_.gas_->cell_fields(sim_.p_, cells_);
    fields->write_frame(sim_.step_, t, {cells_.porosity.data(), cells_.pressure.data()},
                        {pointers(cells_.gas_velocity), pointers(cells_.solids_velocity)});
  }
  outputs_->frame_written(t);
}

void RunRecorder::write_continuum_frame() { // the averages over the interval that ends now
  OutputClock& clock = sim_.clock_;
  const double t = sim_.time_;
  clock.next_continuum = next_mark(t, sim_.continuum_interval_, eps_);
  if (!outputs_) {
    sim_.continuum_->reset();
    return;
  }
  const ContinuumFields f = sim_.continuum_->result();
  std::vector<const double*> sc{f.solid_fraction.data(), f.granular_temperature.data()};
  for (const auto* tensor : {&f.kinetic_stress, &f.contact_stress, &f.couple_stress})
    for (const auto& component : *tensor) sc.push_back(component.data());
  outputs_->continuum()->write_frame(sim_.step_, t, sc,
                                     {pointers(f.velocity), pointers(f.angular_vel)});
  outputs_->continuum_written(t);
  sim_.continuum_->reset();
}

bool RunRecorder::checkpoint_due() {
  OutputClock& clock = sim_.clock_;
  const double t = sim_.time_;
  if (!(t >= clock.next_checkpoint - eps_ && sim_.step_ < total_)) return false;
  clock.next_checkpoint = next_mark(t, sim_.spec_.output.checkpoint_interval, eps_);
  return true;
}

void RunRecorder::checkpoint() {
  sim_.stepper_->finish_kick(); // (integration time, not output)
  const auto t0 = WallClock::now();
  sim_.check_stability();
  sim_.observe();                  // the totals the checkpoint keeps (a distributed run)
  if (outputs_) outputs_->flush(); // (the CSV writers flush every row)
  const std::string path = dir_ ? dir_->file("checkpoint.h5") : std::string();
  sim_.write_checkpoint(path);
  last_checkpoint_ = path;
  seconds_ += seconds_since(t0);
}

void RunRecorder::close() {
  if (!outputs_) return;
  outputs_->close();
  if (outputs_->has_csv("collisions.csv"))
    write_overlap_histogram(dir_->file("collision_overlap.csv"), *sim_.collisions_);
}

OutputLayout RunRecorder::layout(const Simulation& sim) {
  const CaseSpec& spec = sim.spec_;
  OutputLayout l;
  l.particles = sim.p_.size();
  l.dimension = spec.simulation.dimension;
  l.box = H5mdBox{spec.domain.lo, spec.domain.hi, spec.domain.periodic};
  l.layers = spec.output.layers > 0;
  std::vector<std::string> columns{"time",
                                   "e_kin",
                                   "e_rot",
                                   "e_pot",
                                   "e_el",
                                   "e_dsp",
                                   "e_total",
                                   "n_contacts",
                                   "max_overlap_ratio",
                                   "neighbour_builds"};
  if (sim.hard_) {
    // n_contacts is then the number of collisions in the last flow step; n_collisions is
    // cumulative; n_tc_elastic and n_slow_elastic count collisions the TC model and the
    // low-speed rule made elastic (cumulative), e_tc_kept the energy they would have
    // dissipated; neighbour_builds counts the hard-sphere engine's list builds.
    columns.insert(columns.end(), {"n_collisions", "n_tc_elastic", "n_slow_elastic", "e_tc_kept"});
  }
  if (sim.gas_) {
    // Coupled runs: e_total then leaves out the work of the gas on the particles.
    columns.insert(columns.end(),
                   {"pressure_drop", "bed_height", "gas_iterations", "superficial_velocity"});
  }
  l.csv["series.csv"] = columns;
  if (sim.gas_ && !spec.output.probes.empty()) {
    std::vector<std::string> pc{"time"};
    for (const ProbeSpec& pr : spec.output.probes) pc.push_back(pr.name);
    l.csv["probes.csv"] = pc;
  }
  if (sim.collisions_) { // analysis/collision_statistics.hpp; one row per series interval
    std::vector<std::string> cc{
        "time",           "pair_collisions",     "wall_collisions",    "collision_frequency",
        "mean_free_time", "mean_overlap_extent", "max_overlap_extent", "mean_contact_duration"};
    // Soft spheres: the pair collisions ended and, of those, the multiple ones (a particle of
    // the pair in another contact during the collision).
    const bool soft = sim.collisions_->settings().soft_spheres;
    if (soft) cc.insert(cc.end(), {"ended_collisions", "multiple_collisions"});
    for (const CollisionRegionSpec& r : spec.output.collision_regions) {
      cc.insert(cc.end(), {r.name + "_collision_frequency", r.name + "_void_fraction",
                           r.name + "_particles"});
      if (soft)
        cc.insert(cc.end(), {r.name + "_ended_collisions", r.name + "_multiple_collisions"});
    }
    l.csv["collisions.csv"] = cc;
  }
  if (sim.gas_) { // gas fields per particle frame
    const auto& g = sim.gas_->solver().grid();
    l.fields = OutputLayout::Grid{
        FieldGrid{g.n, g.lo, g.h}, {"porosity", "pressure"}, {"gas_velocity", "solids_velocity"}};
  }
  if (sim.continuum_) {
    // Continuum averages [Zhu07 Tables 5-6]: one frame at the end of every averaging interval,
    // the cells as ParaView cell data. Tensor T_ab as the scalar <name>_<a><b>.
    OutputLayout::Grid c;
    const ContinuumGrid& grid = sim.continuum_->grid();
    c.grid = FieldGrid{grid.cells, grid.lo, grid.spacing};
    c.scalars = {"solid_fraction", "granular_temperature"};
    for (const char* tensor : {"kinetic_stress", "contact_stress", "couple_stress"})
      for (const char* ab : {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"})
        c.scalars.push_back(std::string(tensor) + "_" + ab);
    c.vectors = {"velocity", "angular_velocity"};
    l.continuum = c;
  }
  return l;
}

double RunRecorder::bytes_needed(const Simulation& sim) {
  // What the rest of the run writes: particle frames (about 14 values of 8 bytes per particle),
  // gas field frames (8 values per cell), continuum frames (33 values per cell), CSV rows (up to
  // 18 characters a value), and the checkpoint twice (current and previous, about 26 values per
  // particle and 10 per cell); with a margin of 2. Outputs come at most once a step.
  const CaseSpec& spec = sim.spec_;
  const double remaining = std::max(0.0, spec.simulation.end_time - sim.time_);
  const double steps = std::ceil(remaining / sim.dt_) + 1.0;
  const auto count = [&](double interval) {
    return std::min(std::floor(remaining / interval) + 2.0, steps + 1.0);
  };
  const double n = static_cast<double>(sim.p_.size());
  const OutputLayout l = layout(sim);
  const double cells = l.fields ? static_cast<double>(l.fields->grid.size()) : 0.0;
  double need = count(spec.output.frame_interval) * (14.0 * 8.0 * n + 8.0 * 8.0 * cells);
  if (l.continuum)
    need +=
        count(sim.continuum_interval_) * 33.0 * 8.0 * static_cast<double>(l.continuum->grid.size());
  for (const auto& [name, columns] : l.csv)
    need += count(spec.output.series_interval) * 18.0 * static_cast<double>(columns.size());
  need += 2.0 * (26.0 * 8.0 * n + 10.0 * 8.0 * cells);
  return 2.0 * need;
}

} // namespace fluidem
