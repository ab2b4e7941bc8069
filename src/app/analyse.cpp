#include "app/analyse.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "analysis/segregation.hpp"
#include "analysis/size_classes.hpp"
#include "analysis/spectrum.hpp"
#include "analysis/velocity_distribution.hpp"
#include "app/analyse_bed.hpp"
#include "app/analyse_bubbles.hpp"
#include "app/analysis_table.hpp"
#include "app/python_scripts.hpp"
#include "core/error.hpp"
#include "io/case_reader.hpp"
#include "output/h5md_reader.hpp"

namespace fluidem {

namespace {

namespace fs = std::filesystem;

// The velocity distribution per size class (analysis/size_classes.hpp) of the fluctuations `C`
// (sample j of class sample_class[j]; the local means are those of all particles, so the classes'
// samples together are the whole bed's) into `path`, one row per class, and summary rows
// granular_temperature_size_K. A class whose distribution cannot be formed (fewer than 2
// samples, a zero variance) gets NaN.
void write_velocity_by_size(const SizeClasses& classes, const std::vector<std::array<double, 3>>& C,
                            const std::vector<std::size_t>& sample_class,
                            const VelocityDistributionOptions& vo, const fs::path& path,
                            std::vector<SummaryRow>& summary) {
  std::vector<std::vector<std::array<double, 3>>> by(classes.size());
  for (std::size_t j = 0; j < C.size(); ++j) by[sample_class[j]].push_back(C[j]);
  std::ofstream f = open_out(path);
  f << (vo.two_d ? "class,d_min,d_max,particles,samples,variance_x,variance_z,"
                   "granular_temperature,anisotropy\n"
                 : "class,d_min,d_max,particles,samples,variance_x,variance_y,variance_z,"
                   "granular_temperature,anisotropy\n");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < classes.size(); ++k) {
    VelocityDistribution vd;
    bool ok = true;
    try {
      vd = fluctuation_distribution(by[k], vo);
    } catch (const std::invalid_argument&) {
      ok = false;
    }
    f << k << ',' << g(classes.d_min[k]) << ',' << g(classes.d_max[k]) << ',' << classes.count[k]
      << ',' << by[k].size();
    for (int d = 0; d < 3; ++d)
      if (!(vo.two_d && d == 1)) f << ',' << g(ok ? vd.variance[d] : nan);
    f << ',' << g(ok ? vd.granular_temperature : nan) << ',' << g(ok ? vd.anisotropy : nan) << '\n';
    summary.push_back({"granular_temperature_size_" + std::to_string(k),
                       ok ? vd.granular_temperature : nan, "m^2/s^2"});
    fmt::print("  size class {} ({:.4g} to {:.4g} m, {} particles): granular temperature {:.4g} "
               "m^2/s^2\n",
               k, classes.d_min[k], classes.d_max[k], classes.count[k],
               ok ? vd.granular_temperature : nan);
  }
}

// The particle analyses of the run in `out` into `dir`; true when segregation.csv was written.
bool analyse_particles(const fs::path& particles_path, const fs::path& out, const fs::path& dir,
                       double t0, double t1, std::vector<SummaryRow>& summary) {
  std::unique_ptr<H5mdReader> reader;
  try {
    reader = std::make_unique<H5mdReader>(particles_path.string());
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
  const bool two_d = reader->dimension() == 2;
  const H5mdBox& box = reader->box();
  VelocityDistributionOptions vo;
  vo.two_d = two_d;
  std::array<double, 3> lo = box.lo, hi = box.hi;
  std::string cells_note = "one cell (the whole box)";
  try { // local means per gas cell when the resolved case has a gas grid
    const CaseSpec spec = read_case_file((out / "case.resolved.toml").string());
    if (spec.gas) {
      vo.cells = spec.gas->cells;
      if (two_d) vo.cells[1] = 1;
      lo = {spec.gas->lo.x, spec.gas->lo.y, spec.gas->lo.z};
      hi = {spec.gas->hi.x, two_d ? std::max(spec.gas->hi.y, box.hi[1]) : spec.gas->hi.y,
            spec.gas->hi.z};
      if (two_d && !(hi[1] > lo[1])) hi[1] = lo[1] + 1.0;
      cells_note =
          fmt::format("the gas cells ({} x {} x {})", vo.cells[0], vo.cells[1], vo.cells[2]);
    }
  } catch (const std::exception&) {
  }
  for (int d = 0; d < 3; ++d)
    if (!(hi[d] > lo[d])) hi[d] = lo[d] + 1.0; // a flat box (2-D without depth)
  std::vector<std::array<double, 3>> C, local_scale;
  ParticleStore p;
  long frames_used = 0;
  const auto& ft = reader->times();
  // The size classes of the first frame's diameters (analysis/size_classes.hpp), and the class
  // of each fluctuation sample.
  std::vector<double> diameters;
  std::optional<SizeClasses> classes;
  std::vector<std::size_t> sample_class, which;
  try {
    if (reader->frames() > 0) {
      reader->read_frame(0, p);
      for (const double r : p.radius) diameters.push_back(2.0 * r);
      if (!diameters.empty()) classes = size_classes(diameters);
    }
    for (std::size_t k = 0; k < reader->frames(); ++k) {
      if (ft[k] < t0 || ft[k] > t1) continue;
      reader->read_frame(k, p);
      which.clear();
      append_velocity_fluctuations(p, lo, hi, vo, C, &which, &local_scale);
      if (classes)
        for (const std::size_t i : which) sample_class.push_back(classes->of(2.0 * p.radius[i]));
      ++frames_used;
    }
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
  if (frames_used == 0)
    throw InputError(fmt::format("'{}' has no frame in [{}, {}] s (its {} frames cover {} to {} s)",
                                 particles_path.string(), g(t0), g(t1), reader->frames(),
                                 ft.empty() ? "-" : g(ft.front()),
                                 ft.empty() ? "-" : g(ft.back())));
  VelocityDistribution vd;
  bool have_vd = true;
  try {
    vd = fluctuation_distribution(C, vo);
  } catch (const std::invalid_argument& e) {
    // E.g. a bed one particle deep, whose particles never move across it: no distribution,
    // the other analyses go on.
    fmt::print("velocities         left out over {} frames of '{}': {}\n", frames_used,
               particles_path.string(), e.what());
    have_vd = false;
  }
  if (have_vd) {
    {
      std::ofstream f = open_out(dir / "velocity_distribution.csv");
      f << (two_d
                ? "bin_centre,density_x,density_z,normal,speed,speed_density,rayleigh\n"
                : "bin_centre,density_x,density_y,density_z,normal,speed,speed_density,maxwell\n");
      for (std::size_t b = 0; b < vd.bin_centres.size(); ++b) {
        f << g(vd.bin_centres[b]) << ',' << g(vd.density[0][b]) << ',';
        if (!two_d) f << g(vd.density[1][b]) << ',';
        f << g(vd.density[2][b]) << ',' << g(normal_density(vd.bin_centres[b])) << ','
          << g(vd.speed_centres[b]) << ',' << g(vd.speed_density[b]) << ','
          << g(two_d ? rayleigh_speed_density(vd.speed_centres[b])
                     : maxwell_speed_density(vd.speed_centres[b]))
          << '\n';
      }
    }
    fmt::print("velocities         {} frames, {} fluctuation samples, local means over {}\n",
               frames_used, vd.samples, cells_note);
    summary.push_back({"velocity_frames", static_cast<double>(frames_used), "1"});
    summary.push_back({"velocity_samples", static_cast<double>(vd.samples), "1"});
    const char* axis = "xyz";
    for (int d = 0; d < 3; ++d) {
      if (two_d && d == 1) continue;
      const std::string a(1, axis[d]);
      summary.push_back({"velocity_variance_" + a, vd.variance[d], "m^2/s^2"});
      summary.push_back({"velocity_skewness_" + a, vd.skewness[d], "1"});
      summary.push_back({"velocity_kurtosis_" + a, vd.kurtosis[d], "1"});
      summary.push_back({"velocity_outside_range_" + a, vd.outside[d], "1"});
      fmt::print(
          "  {}: variance {:.4g} m^2/s^2, skewness {:.3f}, kurtosis {:.3f} (Gaussian: 0, 3)\n", a,
          vd.variance[d], vd.skewness[d], vd.kurtosis[d]);
    }
    try { // each fluctuation over its cell's rms (analysis/velocity_distribution.hpp)
      const LocalMoments lm = local_moments(C, local_scale, vo);
      fmt::print("  locally normalised (cells of {}+ particles, {} samples): kurtosis",
                 vo.min_local, lm.samples);
      for (int d = 0; d < 3; ++d) {
        if (two_d && d == 1) continue;
        const std::string a(1, axis[d]);
        summary.push_back({"velocity_kurtosis_local_" + a, lm.kurtosis[d], "1"});
        fmt::print(" {} {:.3f}", a, lm.kurtosis[d]);
      }
      summary.push_back({"velocity_local_samples", static_cast<double>(lm.samples), "1"});
      fmt::print("\n");
    } catch (const std::invalid_argument& e) {
      fmt::print("  locally normalised: left out ({})\n", e.what());
    }
    summary.push_back({"speed_outside_range", vd.speed_outside, "1"});
    summary.push_back({"anisotropy", vd.anisotropy, "1"});
    summary.push_back({"granular_temperature", vd.granular_temperature, "m^2/s^2"});
    fmt::print("  granular temperature {:.4g} m^2/s^2, anisotropy {:.3f} (vertical / horizontal "
               "variance)\n",
               vd.granular_temperature, vd.anisotropy);
    if (classes && classes->size() >= 2)
      write_velocity_by_size(*classes, C, sample_class, vo,
                             dir / "velocity_distribution_by_size.csv", summary);
  }

  // Segregation when the particles have two sizes or more: two split at the mean of their
  // diameters, more (a size distribution, three species) at the volume-weighted median diameter.
  std::set<double> radii;
  if (reader->frames() > 0) {
    reader->read_frame(0, p);
    radii.insert(p.radius.begin(), p.radius.end());
  }
  if (radii.size() >= 2) {
    const double split = radii.size() == 2
                             ? *radii.begin() + *radii.rbegin() // the mean of the two diameters
                             : volume_weighted_median_diameter(diameters, two_d);
    if (radii.size() > 2) summary.push_back({"segregation_split_diameter", split, "m"});
    std::ofstream f = open_out(dir / "segregation.csv");
    f << "time,s\n";
    double sum = 0.0, last = 0.0;
    long in_window = 0;
    for (std::size_t k = 0; k < reader->frames(); ++k) {
      reader->read_frame(k, p);
      const Segregation s = segregation(p, split, 2, box.lo[2], true, two_d);
      f << g(ft[k]) << ',' << g(s.s) << '\n';
      last = s.s;
      if (ft[k] >= t0 && ft[k] <= t1) sum += s.s, ++in_window;
    }
    summary.push_back({"segregation_last_frame", last, "1"});
    if (in_window > 0)
      summary.push_back({"segregation_mean_window", sum / static_cast<double>(in_window), "1"});
    if (radii.size() == 2)
      fmt::print("segregation        s = {:.4f} at the last frame (diameters {:.4g} and {:.4g} "
                 "m)\n",
                 last, 2.0 * *radii.begin(), 2.0 * *radii.rbegin());
    else
      fmt::print("segregation        s = {:.4f} at the last frame ({} diameters from {:.4g} to "
                 "{:.4g} m, split at the volume-weighted median {:.4g} m)\n",
                 last, radii.size(), 2.0 * *radii.begin(), 2.0 * *radii.rbegin(), split);
  }

  return radii.size() >= 2;
}

} // namespace

namespace {

// Collision statistics (OUT/collisions.csv, analysis/collision_statistics.hpp) over the rows whose
// interval ends in (t0, t1]: collision counts summed, max_overlap_extent the largest, every other
// column the mean of its finite values, and mean_free_time = 1 / mean collision frequency.
void analyse_collisions(const fs::path& path, double t0, double t1,
                        std::vector<SummaryRow>& summary) {
  const Table t = read_csv(path);
  const std::vector<double>& time = t.data[0];
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < time.size(); ++i)
    if (time[i] > t0 && time[i] <= t1) rows.push_back(i);
  if (rows.empty()) {
    fmt::print("collisions         no rows of {} in ({}, {}] s: left out\n", path.string(), g(t0),
               g(t1));
    return;
  }
  auto unit_of = [](const std::string& c) -> std::string {
    if (c.ends_with("_collisions") || c.ends_with("_extent") || c.ends_with("_fraction") ||
        c.ends_with("_particles"))
      return "1";
    if (c.ends_with("_frequency")) return "1/s";
    return "s"; // mean_free_time, mean_contact_duration
  };
  double f_mean = std::numeric_limits<double>::quiet_NaN();
  std::map<std::string, double> totals; // by column
  for (std::size_t c = 1; c < t.columns.size(); ++c) {
    const std::string& name = t.columns[c];
    if (name == "mean_free_time") continue; // from the mean frequency below
    double sum = 0.0, max = -std::numeric_limits<double>::infinity();
    long finite = 0;
    for (const std::size_t r : rows) {
      const double v = t.data[c][r];
      if (!std::isfinite(v)) continue;
      sum += v, max = std::max(max, v), ++finite;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    double value = finite > 0 ? sum / static_cast<double>(finite) : nan;
    if (name.ends_with("_collisions")) value = sum;
    if (name == "max_overlap_extent") value = finite > 0 ? max : nan;
    if (name == "collision_frequency") f_mean = value;
    summary.push_back(
        {name == "pair_collisions" || name == "wall_collisions" ? name + "_window" : name, value,
         unit_of(name)});
    if (name == "collision_frequency") summary.push_back({"mean_free_time", 1.0 / value, "s"});
    totals[name] = value;
  }
  // Soft spheres: the share of the pair collisions ended in the window that were multiple
  // (a particle of the pair in another contact meanwhile), globally and per region.
  for (const auto& [name, multiple] : totals) {
    const std::string suffix = "multiple_collisions";
    if (!name.ends_with(suffix)) continue;
    const std::string prefix = name.substr(0, name.size() - suffix.size());
    const auto ended = totals.find(prefix + "ended_collisions");
    if (ended == totals.end()) continue;
    summary.push_back(
        {prefix + "multiple_collision_fraction",
         ended->second > 0.0 ? multiple / ended->second : std::numeric_limits<double>::quiet_NaN(),
         "1"});
  }
  fmt::print("collisions         {} rows of {}: collision frequency {} 1/s, mean free time {} s\n",
             rows.size(), path.string(), g(f_mean), g(1.0 / f_mean));
}

// The time span of the run's results: probes.csv, else series.csv, else particles.h5.
std::pair<double, double> run_time_span(const fs::path& out, const std::optional<Table>& probes) {
  std::error_code ec;
  if (probes) return {probes->data[0].front(), probes->data[0].back()};
  if (fs::exists(out / "series.csv", ec)) {
    const Table s = read_csv(out / "series.csv");
    if (!s.data[0].empty()) return {s.data[0].front(), s.data[0].back()};
  }
  if (fs::exists(out / "particles.h5", ec)) {
    try {
      const H5mdReader r((out / "particles.h5").string());
      if (r.frames() > 0) return {r.times().front(), r.times().back()};
    } catch (const std::runtime_error& e) {
      throw InputError(e.what());
    }
  }
  throw InputError(fmt::format("'{}' holds no results of a run (probes.csv, series.csv or "
                               "particles.h5)",
                               out.string()));
}

// The Welch spectra of the probes of probes.csv over [t0, t1] [Chang08 §4.2].
// Returns the times of the first and last samples in the window.
std::pair<double, double> analyse_probes(const Table& probes, const fs::path& probes_path,
                                         const AnalyseOptions& o, double t0, double t1,
                                         const fs::path& dir, std::vector<SummaryRow>& summary) {
  const std::vector<double>& time = probes.data[0];
  std::vector<std::size_t> chosen;
  for (std::size_t c = 1; c < probes.columns.size(); ++c)
    if (o.probe.empty() || probes.columns[c] == o.probe) chosen.push_back(c);
  if (chosen.empty()) {
    std::vector<std::string> names(probes.columns.begin() + 1, probes.columns.end());
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError(
        fmt::format("no probe '{}' in '{}' (its probes: {})", o.probe, probes_path.string(), list));
  }
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < time.size(); ++i)
    if (time[i] >= t0 && time[i] <= t1) rows.push_back(i);
  const std::size_t n = rows.size();
  if (n < 32)
    throw InputError(fmt::format("too few samples: {} rows of '{}' in [{}, {}] s, at least 32 "
                                 "needed for a spectrum (a longer run, or a wider --from/--to)",
                                 n, probes_path.string(), g(t0), g(t1)));
  const double dt = (time[rows.back()] - time[rows.front()]) / static_cast<double>(n - 1);
  for (std::size_t k = 1; k < n; ++k)
    if (std::fabs(time[rows[k]] - time[rows[k - 1]] - dt) > 1e-3 * dt)
      throw InputError(fmt::format("'{}': the rows are not evenly spaced in time near t = {} s "
                                   "(a spectrum needs a constant sampling interval)",
                                   probes_path.string(), g(time[rows[k]])));
  const double fs_rate = 1.0 / dt;
  std::size_t segment = 0;
  if (o.segment_seconds > 0.0) {
    segment = static_cast<std::size_t>(std::llround(o.segment_seconds * fs_rate));
    segment -= segment % 2;
    if (segment < 8 || segment > n)
      throw InputError(fmt::format("--segment {} s is {} samples at {} Hz; it must be between 8 "
                                   "and the {} samples of the window",
                                   g(o.segment_seconds), segment, g(fs_rate), n));
  } else {
    segment = 8;
    while (segment * 2 <= n / 4) segment *= 2;
    if (segment > n / 4)
      throw InputError(fmt::format("too few samples: {} in the window, at least 32 needed", n));
  }

  summary.push_back({"probe_sample_rate", fs_rate, "Hz"});
  summary.push_back({"probe_samples", static_cast<double>(n), "1"});
  summary.push_back({"spectrum_segment_length", static_cast<double>(segment), "1"});
  fmt::print("window             {} to {} s ({} probe samples at {:.6g} Hz)\n",
             g(time[rows.front()]), g(time[rows.back()]), n, fs_rate);
  for (std::size_t c : chosen) {
    const std::string& name = probes.columns[c];
    std::vector<double> signal(n);
    for (std::size_t k = 0; k < n; ++k) signal[k] = probes.data[c][rows[k]];
    Spectrum s;
    try {
      s = welch_psd(signal, fs_rate, segment);
    } catch (const std::invalid_argument& e) {
      throw InputError(fmt::format("probe '{}': {}", name, e.what()));
    }
    double mean = 0.0, var = 0.0;
    for (double v : signal) mean += v / static_cast<double>(n);
    for (double v : signal) var += (v - mean) * (v - mean) / static_cast<double>(n);
    std::ofstream f = open_out(dir / ("spectrum_" + name + ".csv"));
    f << "frequency,psd\n";
    for (std::size_t k = 0; k < s.psd.size(); ++k)
      f << g(s.frequency[k]) << ',' << g(s.psd[k]) << '\n';
    fmt::print("probe {:<12} dominant frequency {:.4g} Hz (resolution {:.3g} Hz, {} segments of "
               "{} samples; variance {:.4g} Pa^2, PSD power {:.4g} Pa^2)\n",
               name, s.dominant_frequency, s.resolution, s.segments, segment, var, s.power());
    if (s.power() < 0.9 * var)
      fmt::print("  note: the spectrum holds {:.0f}% of the variance; the rest varies slower than "
                 "one segment ({:.3g} s): use a longer window (--from) or --segment\n",
                 100.0 * s.power() / var, static_cast<double>(segment) / fs_rate);
    summary.push_back({"dominant_frequency_" + name, s.dominant_frequency, "Hz"});
    summary.push_back({"spectrum_resolution_" + name, s.resolution, "Hz"});
    summary.push_back({"pressure_variance_" + name, var, "Pa^2"});
    summary.push_back({"psd_power_" + name, s.power(), "Pa^2"});
  }
  return {time[rows.front()], time[rows.back()]};
}

} // namespace

namespace {

/// The run's directory, locked while analyse or plot write into it (not created when missing).
std::optional<OutputDirectory> lock_run_directory(const std::string& out_dir,
                                                  const OutputDirectory* held, const char* who) {
  std::error_code ec;
  if (!fs::is_directory(out_dir, ec))
    throw InputError(
        fmt::format("'{}' is not a directory (the output directory of a run)", out_dir));
  std::optional<OutputDirectory> own;
  if (held == nullptr) own.emplace(out_dir, who);
  (held ? *held : *own).refuse_links(); // nothing is written through a link
  return own;
}

} // namespace

int analyse(const AnalyseOptions& o) {
  const fs::path out(o.out_dir);
  std::error_code ec;
  const auto lock = lock_run_directory(o.out_dir, o.directory, "fluidem analyse");
  const fs::path probes_path = out / "probes.csv";
  std::optional<Table> probes;
  if (fs::exists(probes_path, ec)) {
    probes = read_csv(probes_path);
    if (probes->data[0].size() < 2 || probes->columns.size() < 2)
      throw InputError(fmt::format("'{}' holds {} rows and {} probes: too few to analyse",
                                   probes_path.string(), probes->data[0].size(),
                                   probes->columns.size() - 1));
  } else if (!o.probe.empty()) {
    throw InputError(fmt::format("'{}' does not exist: the run has no pressure probes (a case "
                                 "with [gas] and [[output.probe]] writes it)",
                                 probes_path.string()));
  }

  // The window [T0, T1]: default the second half of the run.
  const auto [t_first, t_last] = run_time_span(out, probes);
  const double t0 = o.from.value_or(t_first + 0.5 * (t_last - t_first));
  const double t1 = o.to.value_or(t_last);
  if (!(t1 > t0))
    throw InputError(fmt::format("empty window: --from {} must be before --to {} (the run covers "
                                 "{} to {} s)",
                                 g(t0), g(t1), g(t_first), g(t_last)));

  const fs::path dir = out / "analysis";
  fs::create_directories(dir, ec);
  if (ec) throw InputError(fmt::format("cannot create '{}': {}", dir.string(), ec.message()));
  std::vector<SummaryRow> summary;
  std::pair<double, double> window{t0, std::min(t1, t_last)};
  if (probes)
    window = analyse_probes(*probes, probes_path, o, t0, t1, dir, summary);
  else
    fmt::print("probes             no {}: no pressure spectra\n", probes_path.string());
  summary.insert(summary.begin(),
                 {{"window_start", window.first, "s"}, {"window_end", window.second, "s"}});
  analyse_bed(out, t0, t1, summary);

  // Particles: velocity distribution over the frames in the window, segregation over all.
  const fs::path particles_path = out / "particles.h5";
  bool two_sizes = false;
  if (fs::exists(particles_path, ec))
    two_sizes = analyse_particles(particles_path, out, dir, t0, t1, summary);
  else
    fmt::print("particles          no {}: velocity distribution and segregation left out\n",
               particles_path.string());

  // Bubbles: the voids of every frame of fields.h5 (coupled runs).
  const fs::path fields_path = out / "fields.h5";
  const bool bubbles = fs::exists(fields_path, ec);
  if (bubbles) analyse_bubbles(fields_path, dir, t0, t1, o.void_porosity, summary);

  const fs::path collisions_path = out / "collisions.csv";
  if (fs::exists(collisions_path, ec))
    analyse_collisions(collisions_path, window.first, window.second, summary);

  std::ofstream f = open_out(dir / "summary.csv");
  f << "name,value,unit\n";
  for (const auto& r : summary) f << r.name << ',' << g(r.value) << ',' << r.unit << '\n';
  fmt::print(
      "written            {}/ (summary.csv, velocity_distribution.csv, spectrum_*.csv{}{})\n",
      dir.string(), two_sizes ? ", velocity_distribution_by_size.csv, segregation.csv" : "",
      bubbles ? ", bubbles.csv, bubble_frames.csv" : "");
  return 0;
}

int plot(const std::string& out_dir, const char* argv0, int movie_every) {
  const auto lock = lock_run_directory(out_dir, nullptr, "fluidem plot");
  const fs::path dir = find_python_script_dir("fluidem_analysis_plot.py", argv0);
  if (movie_every > 0)
    return run_python_script(dir / "fluidem_plot.py",
                             {out_dir, "--movie", "--every", std::to_string(movie_every)});
  if (const int code = run_python_script(dir / "fluidem_plot.py", {out_dir}); code != 0)
    return code;
  // The analysis the pictures need, with its default window, unless `analyse` wrote one.
  std::error_code ec;
  if (!fs::exists(fs::path(out_dir) / "analysis" / "summary.csv", ec)) {
    fmt::print("no {}/analysis/ yet: analysing the run (fluidem analyse {})\n", out_dir, out_dir);
    AnalyseOptions o;
    o.out_dir = out_dir;
    o.directory = &*lock;
    try {
      analyse(o);
    } catch (const InputError& e) {
      fmt::print("the analysis pictures are left out: {}\npicture: {}/snapshot.png\n", e.what(),
                 out_dir);
      return 0;
    }
  }
  if (const int code = run_python_script(dir / "fluidem_analysis_plot.py", {out_dir}); code != 0)
    return code;
  fmt::print("pictures: {}/snapshot.png, {}/analysis/*.png\n", out_dir, out_dir);
  return 0;
}

int plot_together(const std::vector<std::string>& out_dirs, const char* argv0) {
  for (const auto& d : out_dirs)
    if (const int code = plot(d, argv0); code != 0) return code;
  const auto lock = lock_run_directory(out_dirs.front(), nullptr, "fluidem plot");
  const fs::path dir = find_python_script_dir("fluidem_analysis_plot.py", argv0);
  std::vector<std::string> args = {"--compare"};
  args.insert(args.end(), out_dirs.begin(), out_dirs.end());
  return run_python_script(dir / "fluidem_analysis_plot.py", args);
}

int AnalysisCommands::run(const char* argv0) const {
  if (*analyse) return fluidem::analyse(options);
  if (plot_dirs.size() > 1) {
    if (movie) throw InputError("fluidem plot: --movie draws one run (give one OUT)");
    return fluidem::plot_together(plot_dirs, argv0);
  }
  return fluidem::plot(plot_dirs.front(), argv0, movie ? movie_every : 0);
}

std::unique_ptr<AnalysisCommands> add_analysis_commands(CLI::App& app) {
  auto c = std::make_unique<AnalysisCommands>();
  AnalyseOptions& o = c->options;
  c->analyse = app.add_subcommand(
      "analyse", "Analyse a run's outputs into OUT/analysis/: probe spectra, velocity "
                 "distributions, segregation, summary.csv (docs/analysis.md)");
  c->analyse->add_option("out", o.out_dir, "Output directory of a run")->required();
  c->analyse->add_option("--probe", o.probe, "Only this probe of probes.csv (default: all)");
  c->analyse
      ->add_option("--segment", o.segment_seconds,
                   "Welch segment length, s (default: the largest power of two of "
                   "samples not above a quarter of the window)")
      ->check(CLI::PositiveNumber);
  c->analyse->add_option("--from", o.from, "Window start T0, s (default: half the run)");
  c->analyse->add_option("--to", o.to, "Window end T1, s (default: the end of the run)");
  c->analyse
      ->add_option("--void-porosity", o.void_porosity,
                   "Bubbles: cells above this porosity are dilute (default 0.8)")
      ->check(CLI::Range(0.0, 1.0));
  c->plot = app.add_subcommand("plot", "Draw a run's pictures: OUT/snapshot.png and, from "
                                       "`fluidem analyse`, OUT/analysis/*.png; several runs: "
                                       "also their shared curves on one figure, with the "
                                       "published values (OUT1/analysis/*_compare.png)");
  c->plot->add_option("out", c->plot_dirs, "Output directory of a run (or several)")->required();
  c->plot->add_flag("--movie", c->movie,
                    "Every frame as a picture (OUT/movie_frames/) joined into OUT/movie.mp4 "
                    "(needs ffmpeg)");
  c->plot->add_option("--every", c->movie_every, "With --movie: every N-th frame")
      ->check(CLI::PositiveNumber);
  return c;
}

} // namespace fluidem
