// `fluidem analyse` and `fluidem plot` as a user meets them: the real binary (FLUIDEM_BINARY) on
// a small coupled run (2-D hard spheres of two sizes fluidised by gas, one pressure probe), and
// on a synthetic probes.csv with a known spectrum. Independent references: the variance of the
// probe signal computed here from probes.csv (Parseval), the exact Welch power computed here in
// the time domain, the normalisation of probability densities, the standard normal and Rayleigh
// densities evaluated here, the degree of segregation [Deen07 eq. 49] computed here from the
// particle file, the frequency of a synthetic sine.
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iostream>
#include <map>
#include <numbers>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../../common/cli_runner.hpp"
#include "output/h5md_reader.hpp"

namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path p =
      fs::temp_directory_path() / ("fluidem_analyse_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

using fluidem::test::fluidem;
using fluidem::test::quote;
using fluidem::test::read_file;
using fluidem::test::Result;
Result run(const std::string& command, const fs::path& cwd) {
  return fluidem::test::run_command(command, cwd);
}

struct Csv {
  std::vector<std::string> header;
  std::map<std::string, std::vector<double>> col;
  std::size_t rows = 0;
};

Csv read_csv(const fs::path& p) {
  Csv c;
  std::ifstream in(p);
  std::string line, cell;
  if (!std::getline(in, line)) return c;
  std::istringstream h(line);
  while (std::getline(h, cell, ',')) c.header.push_back(cell);
  while (std::getline(in, line)) {
    std::istringstream r(line);
    for (std::size_t k = 0; k < c.header.size() && std::getline(r, cell, ','); ++k)
      c.col[c.header[k]].push_back(std::strtod(cell.c_str(), nullptr));
    ++c.rows;
  }
  return c;
}

std::map<std::string, double> read_summary(const fs::path& p) {
  std::map<std::string, double> m;
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    const auto a = line.find(','), b = line.rfind(',');
    m[line.substr(0, a)] = std::strtod(line.substr(a + 1, b - a - 1).c_str(), nullptr);
  }
  return m;
}

// 2-D hard spheres of 3 and 4 mm (150 each) in a 60 mm x 200 mm bed, gas through a uniform
// distributor at about twice minimum fluidisation, a probe 40 mm above it: a bubbling bed of
// one second, sampled every millisecond.
const std::string kCase = R"([simulation]
engine = "hard_sphere"
dimension = 2
end_time = 1.0
time_step = 1e-4
gravity = [0.0, 0.0, -9.81]

[output]
frame_interval = 0.02
series_interval = 0.001

[[output.probe]]
name = "p_low"
position = [0.03, 0.002, 0.04]

[[output.probe]]
name = "p_top"
position = [0.03, 0.002, 0.19]

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.06, 0.004, 0.2]

[[species]]
name = "small"
diameter = 0.003
density = 2500.0

[[species]]
name = "large"
diameter = 0.004
density = 2500.0

[[insert]]
species = "large"
count = 150

[[insert]]
species = "small"
count = 150

[gas]
cells = [6, 1, 20]

[gas.boundary.bottom]
type = "inflow"
velocity = 2.0
porosity = 0.4

[gas.boundary.top]
type = "pressure"
pressure = 101325.0

[gas.boundary.left]
type = "wall_no_slip"

[gas.boundary.right]
type = "wall_no_slip"
)";

// One coupled run and its analysis, checked by the functions below in one test (under ctest
// every test is its own process: separate tests would repeat the run each time).
fs::path dir_;
Result analyse_;
fs::path out() {
  return dir_ / "out";
}
fs::path analysis() {
  return dir_ / "out" / "analysis";
}

void WritesTheCsvFilesWithTheirColumns() {
  using V = std::vector<std::string>;
  EXPECT_EQ(read_csv(analysis() / "spectrum_p_low.csv").header, (V{"frequency", "psd"}));
  EXPECT_EQ(read_csv(analysis() / "spectrum_p_top.csv").header, (V{"frequency", "psd"}));
  EXPECT_EQ(
      read_csv(analysis() / "velocity_distribution.csv").header,
      (V{"bin_centre", "density_x", "density_z", "normal", "speed", "speed_density", "rayleigh"}));
  EXPECT_EQ(read_csv(analysis() / "segregation.csv").header, (V{"time", "s"}));
  EXPECT_EQ(read_csv(analysis() / "summary.csv").header, (V{"name", "value", "unit"}));
  // Every frame of the run (0, 0.02, ..., 1.0 s) has a segregation value.
  EXPECT_EQ(read_csv(analysis() / "segregation.csv").rows, 51u);
  const auto s = read_summary(analysis() / "summary.csv");
  for (const char* key : {"dominant_frequency_p_low", "granular_temperature", "anisotropy",
                          "velocity_variance_x", "velocity_kurtosis_z", "segregation_last_frame"})
    EXPECT_EQ(s.count(key), 1u) << key;
  EXPECT_NE(analyse_.out.find("dominant frequency"), std::string::npos) << analyse_.out;
}

// Parseval: the PSD integrates to the mean square of the fluctuation: exactly (1e-8) to the
// Welch estimate's own time-domain power (segments of L samples overlapping by half, each less
// its mean, Hann-weighted). Not to the plain variance of this short window: L = 64 ms, and most
// of the variance of a bubbling bed is slower than that (the ratio is printed; the synthetic
// test below checks the 1% agreement with the variance of a stationary signal).
void SpectrumIntegratesToTheProbeVariance() {
  const Csv probes = read_csv(out() / "probes.csv");
  const auto summary = read_summary(analysis() / "summary.csv");
  const std::vector<double>& t = probes.col.at("time");
  const double t0 = t.front() + 0.5 * (t.back() - t.front());
  const auto L = static_cast<std::size_t>(summary.at("spectrum_segment_length"));
  for (const std::string name : {"p_low", "p_top"}) {
    std::vector<double> x;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] >= t0) x.push_back(probes.col.at(name)[i]);
    ASSERT_GE(x.size(), 4 * L);
    ASSERT_LT(x.size(), 8 * L) << "L is the largest power of two <= n/4";
    double mean = 0.0, var = 0.0;
    for (double v : x) mean += v / static_cast<double>(x.size());
    for (double v : x) var += (v - mean) * (v - mean) / static_cast<double>(x.size());
    double welch = 0.0, w2 = 0.0;
    int segments = 0;
    for (std::size_t n = 0; n < L; ++n) {
      const double w =
          std::pow(std::sin(std::numbers::pi * static_cast<double>(n) / static_cast<double>(L)), 2);
      w2 += w * w;
    }
    for (std::size_t s0 = 0; s0 + L <= x.size(); s0 += L / 2, ++segments) {
      double m = 0.0;
      for (std::size_t n = 0; n < L; ++n) m += x[s0 + n] / static_cast<double>(L);
      for (std::size_t n = 0; n < L; ++n) {
        const double w = std::pow(
            std::sin(std::numbers::pi * static_cast<double>(n) / static_cast<double>(L)), 2);
        welch += w * w * (x[s0 + n] - m) * (x[s0 + n] - m) / w2;
      }
    }
    welch /= segments;
    const Csv spec = read_csv(analysis() / ("spectrum_" + name + ".csv"));
    const std::vector<double>& f = spec.col.at("frequency");
    ASSERT_EQ(f.size(), L / 2 + 1);
    const double df = f[1] - f[0];
    EXPECT_NEAR(df, summary.at("probe_sample_rate") / static_cast<double>(L), 1e-9 * df);
    double power = 0.0;
    for (double p : spec.col.at("psd")) power += p * df;
    EXPECT_NEAR(power, welch, 1e-8 * welch) << name;
    EXPECT_NEAR(summary.at("pressure_variance_" + name), var, 1e-8 * var);
    std::printf("%s: %zu samples, L = %zu, variance %.6g Pa^2, PSD power %.6g Pa^2 (%.3f%%), "
                "dominant %.4g Hz\n",
                name.c_str(), x.size(), L, var, power, 100.0 * (power / var - 1.0),
                summary.at("dominant_frequency_" + name));
  }
}

void VelocityDensitiesAreNormalisedAndReferencesExact() {
  const Csv v = read_csv(analysis() / "velocity_distribution.csv");
  const auto s = read_summary(analysis() / "summary.csv");
  ASSERT_GE(v.rows, 10u);
  const std::vector<double>& x = v.col.at("bin_centre");
  const std::vector<double>& c = v.col.at("speed");
  const double w = x[1] - x[0], ws = c[1] - c[0];
  for (const std::string comp : {"x", "z"}) {
    double integral = 0.0;
    for (double d : v.col.at("density_" + comp)) integral += d * w;
    // What falls outside the histogram range is reported; together they make 1.
    EXPECT_NEAR(integral + s.at("velocity_outside_range_" + comp), 1.0, 1e-9) << comp;
    EXPECT_GT(integral, 0.9) << comp;
    std::printf("density_%s integrates to %.12f, outside %.3g, kurtosis %.3f\n", comp.c_str(),
                integral, s.at("velocity_outside_range_" + comp),
                s.at("velocity_kurtosis_" + comp));
  }
  double speed = 0.0;
  for (double d : v.col.at("speed_density")) speed += d * ws;
  EXPECT_NEAR(speed + s.at("speed_outside_range"), 1.0, 1e-9);
  for (std::size_t b = 0; b < v.rows; ++b) {
    const double normal = std::exp(-0.5 * x[b] * x[b]) / std::sqrt(2.0 * std::numbers::pi);
    const double rayleigh = c[b] * std::exp(-0.5 * c[b] * c[b]);
    EXPECT_NEAR(v.col.at("normal")[b], normal, 1e-9 * normal);
    EXPECT_NEAR(v.col.at("rayleigh")[b], rayleigh, 1e-9 * rayleigh);
  }
  // 2-D: theta is the mean of the two in-plane variances; anisotropy their ratio.
  const double vx = s.at("velocity_variance_x"), vz = s.at("velocity_variance_z");
  EXPECT_NEAR(s.at("granular_temperature"), 0.5 * (vx + vz), 1e-8 * (vx + vz));
  EXPECT_NEAR(s.at("anisotropy"), vz / vx, 1e-8 * vz / vx);
  EXPECT_GT(vx, 0.0);
}

// The velocity statistics per size class (docs/analysis.md): the two species of distinct
// diameters are the two classes, 150 particles each; their samples together are the bed's and,
// the fluctuations being the bed's split by particle, the sample-weighted mean of the classes'
// granular temperatures is the bed's (sums of the same squares: to the 10 digits written).
void VelocityBySizeSumsToTheBed() {
  const Csv by = read_csv(analysis() / "velocity_distribution_by_size.csv");
  using V = std::vector<std::string>;
  EXPECT_EQ(by.header, (V{"class", "d_min", "d_max", "particles", "samples", "variance_x",
                          "variance_z", "granular_temperature", "anisotropy"}));
  ASSERT_EQ(by.rows, 2u);
  EXPECT_EQ(by.col.at("d_min")[0], 0.003);
  EXPECT_EQ(by.col.at("d_max")[1], 0.004);
  EXPECT_EQ(by.col.at("particles")[0], 150.0);
  EXPECT_EQ(by.col.at("particles")[1], 150.0);
  const auto s = read_summary(analysis() / "summary.csv");
  const auto& n = by.col.at("samples");
  const auto& theta = by.col.at("granular_temperature");
  EXPECT_EQ(n[0] + n[1], s.at("velocity_samples"));
  const double mixed = (n[0] * theta[0] + n[1] * theta[1]) / (n[0] + n[1]);
  EXPECT_NEAR(mixed, s.at("granular_temperature"), 1e-8 * s.at("granular_temperature"));
  EXPECT_EQ(s.at("granular_temperature_size_1"), theta[1]);
  EXPECT_EQ(s.count("segregation_split_diameter"), 0u); // two sizes: split at their mean
}

// The degree of segregation of the first and last frames, computed here from particles.h5
// [Deen07 eq. 49]: s = (S - 1)/(S_max - 1), S = <h_small>/<h_large>, S_max = (x_L + 1)/x_L with
// x_L the disc-area fraction of the large particles (2-D).
void SegregationMatchesDeen07Eq49() {
  const fluidem::H5mdReader reader((out() / "particles.h5").string());
  const Csv seg = read_csv(analysis() / "segregation.csv");
  ASSERT_EQ(seg.rows, reader.frames());
  fluidem::ParticleStore p;
  for (std::size_t k : {std::size_t{0}, reader.frames() - 1}) {
    reader.read_frame(k, p);
    double hs = 0.0, hl = 0.0, as = 0.0, al = 0.0;
    double ns = 0, nl = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double a = p.radius[i] * p.radius[i];
      if (p.radius[i] < 0.00175)
        hs += p.z[i], as += a, ns += 1;
      else
        hl += p.z[i], al += a, nl += 1;
    }
    ASSERT_EQ(ns, 150.0);
    ASSERT_EQ(nl, 150.0);
    const double S = (hs / ns) / (hl / nl), xl = al / (al + as), Smax = (xl + 1.0) / xl;
    const double expected = (S - 1.0) / (Smax - 1.0);
    EXPECT_NEAR(seg.col.at("s")[k], expected, 1e-8) << "frame " << k;
    EXPECT_EQ(seg.col.at("time")[k], reader.times()[k]);
    std::printf("frame %zu (t = %.3g s): s = %.6f (here %.6f)\n", k, reader.times()[k],
                seg.col.at("s")[k], expected);
  }
}

// The bed rows against the case: W = sum m g / (width x depth) from the counts, diameters and
// density of kCase (solid spheres, also in 2-D), the pressure drop's window mean and standard
// deviation and the collision rate computed here from series.csv over the window of the summary.
void BedQuantitiesMatchTheCase() {
  const auto s = read_summary(analysis() / "summary.csv");
  const double pi = std::numbers::pi;
  const double mass = 150 * 2500.0 * pi / 6.0 * (std::pow(0.004, 3) + std::pow(0.003, 3));
  const double W = mass * 9.81 / (0.06 * 0.004);
  EXPECT_NEAR(s.at("bed_weight_per_area"), W, 1e-9 * W);
  const Csv series = read_csv(out() / "series.csv");
  const auto& t = series.col.at("time");
  const auto& dp = series.col.at("pressure_drop");
  const auto& nc = series.col.at("n_collisions");
  const double t0 = s.at("window_start"), t1 = s.at("window_end");
  double sum = 0.0, sum2 = 0.0, n = 0.0, c0 = -1.0, c1 = 0.0, ta = 0.0, tb = 0.0;
  for (std::size_t r = 0; r < t.size(); ++r) {
    if (t[r] < t0 || t[r] > t1) continue;
    sum += dp[r], sum2 += dp[r] * dp[r], n += 1.0;
    if (c0 < 0.0) c0 = nc[r], ta = t[r];
    c1 = nc[r], tb = t[r];
  }
  const double mean = sum / n, sd = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
  EXPECT_NEAR(s.at("pressure_drop_mean"), mean, 1e-6 * std::fabs(mean));
  EXPECT_NEAR(s.at("pressure_drop_std"), sd, 1e-4 * sd);
  EXPECT_NEAR(s.at("pressure_drop_over_weight"), mean / W, 1e-6);
  EXPECT_NEAR(s.at("collisions_per_second"), (c1 - c0) / (tb - ta), 1e-6 * (c1 - c0) / (tb - ta));
  EXPECT_EQ(s.at("bed_height_initial"), series.col.at("bed_height").front());
  // A fluidised bed at twice u_mf carries its weight: the window mean within 15% of W
  // [Kunii & Levenspiel, ch. 3]; the distributor's own drop is not in pressure_drop.
  EXPECT_NEAR(s.at("pressure_drop_over_weight"), 1.0, 0.15);
  std::printf("bed: W = %.2f Pa, pressure drop %.2f Pa = %.4f W, collisions %.4g /s\n", W, mean,
              mean / W, s.at("collisions_per_second"));
}

void ErrorsAreClearAndExitTwo() {
  Result r = fluidem({"analyse", "out", "--probe", "p_nowhere"}, dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no probe 'p_nowhere'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("p_low, p_top"), std::string::npos) << r.err;
  r = fluidem({"analyse", "no_such_dir"}, dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("'no_such_dir' is not a directory"), std::string::npos) << r.err;
  r = fluidem({"analyse", "."}, dir_); // the case folder: no results of a run
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("holds no results of a run"), std::string::npos) << r.err;
  r = fluidem({"analyse", ".", "--probe", "p_top"}, dir_); // a probe asked for, no probes.csv
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("probes.csv' does not exist"), std::string::npos) << r.err;
  r = fluidem({"analyse", "out", "--from", "0.99"}, dir_); // 11 samples
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("too few samples"), std::string::npos) << r.err;
  r = fluidem({"analyse", "out", "--segment", "5"}, dir_); // longer than the window
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--segment 5 s"), std::string::npos) << r.err;
}

// One probe over a chosen window and segment: only that spectrum, L = 0.128 s x 1000 Hz.
void ProbeWindowAndSegmentOptions() {
  const fs::path copy = dir_ / "copy";
  fs::create_directories(copy);
  fs::copy_file(out() / "probes.csv", copy / "probes.csv", fs::copy_options::overwrite_existing);
  const Result r = fluidem(
      {"analyse", "copy", "--probe", "p_top", "--from", "0.2", "--to", "0.8", "--segment", "0.128"},
      dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(copy / "analysis" / "spectrum_p_low.csv"));
  const auto s = read_summary(copy / "analysis" / "summary.csv");
  EXPECT_EQ(s.at("spectrum_segment_length"), 128.0);
  EXPECT_NEAR(s.at("window_start"), 0.2, 1e-9);
  EXPECT_NEAR(s.at("window_end"), 0.8, 1e-9);
  EXPECT_EQ(s.at("probe_samples"), 601.0);
  EXPECT_EQ(read_csv(copy / "analysis" / "spectrum_p_top.csv").rows, 65u);
}

bool python_has_matplotlib() {
  const fs::path d = fs::temp_directory_path();
  return run(std::string(FLUIDEM_PYTHON) + " -c 'import matplotlib, numpy, h5py'", d).code == 0;
}

bool is_png(const fs::path& p) {
  const std::string s = read_file(p);
  return s.size() > 1000 && s.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0 &&
         s.compare(s.size() - 8, 4, "IEND") == 0;
}

void PlotWritesValidPngs() {
  if (!python_has_matplotlib()) {
    std::cout << "plot check skipped: " << FLUIDEM_PYTHON << " lacks matplotlib/numpy/h5py\n";
    return;
  }
  const Result r = fluidem({"plot", "out"}, dir_);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  for (const fs::path& p :
       {out() / "snapshot.png", analysis() / "spectrum_p_low.png",
        analysis() / "spectrum_p_top.png", analysis() / "velocity_distribution.png",
        analysis() / "segregation.png"})
    EXPECT_TRUE(is_png(p)) << p;
}

// `fluidem plot OUT1 OUT2`: the runs' s(t) on one figure with the published values that the
// reference.toml next to the case file gives for this case (rows with curve = "segregation" and
// at_time; the case file is found through the header of case.resolved.toml).
void PlotTogetherDrawsThePublishedValues() {
  const std::string resolved = read_file(out() / "case.resolved.toml");
  const std::string mark =
      "# case file: " + fs::absolute(dir_ / "bed.toml").lexically_normal().string() + "\n";
  EXPECT_NE(resolved.find(mark), std::string::npos) << resolved.substr(0, 300);
  if (!python_has_matplotlib()) {
    std::cout << "plot check skipped: " << FLUIDEM_PYTHON << " lacks matplotlib/numpy/h5py\n";
    return;
  }
  fs::copy(out(), dir_ / "out2", fs::copy_options::recursive);
  std::ofstream(dir_ / "reference.toml")
      << "[[quantity]]\nid = \"bed.s\"\ncase = \"bed\"\nsource = \"[test]\"\n"
         "quantity = \"s\"\npublished = \"0.42 (made up)\"\nvalue = 0.42\nunit = \"\"\n"
         "format = \".3f\"\ncurve = \"segregation\"\nat_time = 0.05\n"
         "[quantity.criterion]\nkind = \"within_abs\"\ntolerance = 0.1\n"
         "[[quantity]]\nid = \"other.s\"\ncase = \"other\"\nsource = \"[test]\"\n"
         "quantity = \"s\"\npublished = \"0.9 (another case)\"\nvalue = 0.9\nunit = \"\"\n"
         "format = \".3f\"\ncurve = \"segregation\"\nat_time = 0.05\n"
         "[quantity.criterion]\nkind = \"within_abs\"\ntolerance = 0.1\n";
  const Result r = fluidem({"plot", "out", "out2"}, dir_);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_TRUE(is_png(analysis() / "segregation_compare.png"));
  // the row of this case, twice (both runs come from bed.toml), and not the other case's
  std::size_t rows = 0;
  for (auto at = r.out.find("0.42 (made up) [test] at t = 0.05 s"); at != std::string::npos;
       at = r.out.find("0.42 (made up) [test] at t = 0.05 s", at + 1))
    ++rows;
  EXPECT_EQ(rows, 2u) << r.out;
  EXPECT_EQ(r.out.find("another case"), std::string::npos) << r.out;
  // one run only: nothing to compare with --movie
  EXPECT_EQ(fluidem({"plot", "out", "out2", "--movie"}, dir_).code, 2);
}

TEST(CoupledRun, RunAnalyseAndPlot) {
  dir_ = temp_dir("coupled");
  std::ofstream(dir_ / "bed.toml") << kCase;
  const Result run = fluidem({"run", "bed.toml", "--out", "out", "--threads", "1"}, dir_);
  ASSERT_EQ(run.code, 0) << run.out << run.err;
  analyse_ = fluidem({"analyse", "out"}, dir_);
  ASSERT_EQ(analyse_.code, 0) << analyse_.out << analyse_.err;
  {
    SCOPED_TRACE("WritesTheCsvFilesWithTheirColumns");
    WritesTheCsvFilesWithTheirColumns();
  }
  {
    SCOPED_TRACE("SpectrumIntegratesToTheProbeVariance");
    SpectrumIntegratesToTheProbeVariance();
  }
  {
    SCOPED_TRACE("VelocityDensitiesAreNormalisedAndReferencesExact");
    VelocityDensitiesAreNormalisedAndReferencesExact();
  }
  {
    SCOPED_TRACE("VelocityBySizeSumsToTheBed");
    VelocityBySizeSumsToTheBed();
  }
  {
    SCOPED_TRACE("SegregationMatchesDeen07Eq49");
    SegregationMatchesDeen07Eq49();
  }
  {
    SCOPED_TRACE("BedQuantitiesMatchTheCase");
    BedQuantitiesMatchTheCase();
  }
  {
    SCOPED_TRACE("ErrorsAreClearAndExitTwo");
    ErrorsAreClearAndExitTwo();
  }
  {
    SCOPED_TRACE("ProbeWindowAndSegmentOptions");
    ProbeWindowAndSegmentOptions();
  }
  {
    SCOPED_TRACE("PlotWritesValidPngs");
    PlotWritesValidPngs();
  }
  {
    SCOPED_TRACE("PlotTogetherDrawsThePublishedValues");
    PlotTogetherDrawsThePublishedValues();
  }
  if (std::getenv("FLUIDEM_KEEP_TEST_FILES") == nullptr) fs::remove_all(dir_);
}

// A Python without matplotlib: the analysis script says so and exits 3 (a stub module that
// fails to import stands in for the missing package).
TEST(AnalysisPlot, MissingMatplotlibIsAClearMessage) {
  const fs::path d = temp_dir("nompl");
  fs::create_directories(d / "stub");
  std::ofstream(d / "stub" / "matplotlib.py")
      << "raise ImportError(\"No module named 'matplotlib'\", name='matplotlib')\n";
  fs::create_directories(d / "out" / "analysis");
  const Result r =
      run("PYTHONPATH=stub " + std::string(FLUIDEM_PYTHON) + " " +
              quote(std::string(FLUIDEM_SOURCE_DIR) + "/python/fluidem_analysis_plot.py") + " out",
          d);
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("cannot import matplotlib"), std::string::npos) << r.err;
  fs::remove_all(d);
}

// A synthetic probes.csv: 2 Hz sine of 100 Pa plus uniform noise of +-30 Pa, 64 Hz for 64 s.
// The default window (the second half, 2049 samples) gives L = 512, df = 0.125 Hz.
TEST(AnalyseSynthetic, DominantFrequencyOfASine) {
  const fs::path d = temp_dir("sine");
  fs::create_directories(d / "out");
  {
    std::ofstream f(d / "out" / "probes.csv");
    f << "time,p_sine\n";
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> noise(-30.0, 30.0);
    char line[64];
    for (int i = 0; i <= 4096; ++i) {
      const double t = i / 64.0;
      std::snprintf(line, sizeof line, "%.10g,%.10g\n", t,
                    101325.0 + 100.0 * std::sin(2.0 * std::numbers::pi * 2.0 * t + 0.3) +
                        noise(rng));
      f << line;
    }
  }
  const Result r = fluidem({"analyse", "out"}, d);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      r.out, m, std::regex(R"(probe p_sine\s+dominant frequency ([0-9.eE+-]+) Hz)")))
      << r.out;
  const double f = std::stod(m[1]);
  // Parseval against the variance of the window, computed here: a stationary signal whose
  // segments hold whole periods, so the PSD carries all of its variance.
  std::vector<double> x;
  {
    std::ifstream in(d / "out" / "probes.csv");
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      const double t = std::strtod(line.c_str(), nullptr);
      if (t >= 32.0) x.push_back(std::strtod(line.c_str() + line.find(',') + 1, nullptr));
    }
  }
  ASSERT_EQ(x.size(), 2049u);
  double mean = 0.0, var = 0.0;
  for (double v : x) mean += v / static_cast<double>(x.size());
  for (double v : x) var += (v - mean) * (v - mean) / static_cast<double>(x.size());
  const Csv spec = read_csv(d / "out" / "analysis" / "spectrum_p_sine.csv");
  double power = 0.0;
  for (double p : spec.col.at("psd")) power += p * (64.0 / 512.0);
  EXPECT_NEAR(power, var, 0.01 * var);
  std::printf("synthetic: variance %.6g Pa^2, PSD power %.6g Pa^2 (%.3f%%)\n", var, power,
              100.0 * (power / var - 1.0));
  const double df = 64.0 / 512.0;
  EXPECT_NEAR(f, 2.0, df / 5.0) << r.out;
  EXPECT_NE(r.out.find("no "), std::string::npos) << "particles.h5 absent is said: " << r.out;
  std::printf("synthetic 2 Hz sine: dominant %.6g Hz (bin %.4g Hz)\n", f, df);
  fs::remove_all(d);
}

} // namespace

namespace {

// The pressure drop against the superficial velocity (analysis/pressure_drop_velocity.csv) of a
// synthetic velocity loop: U = t/2 up to 2 m/s over 4 s, then back to 0 over 4 s, rows every
// 10 ms; pressure drop 1000 min(U, 1) Pa rising and 900 min(U, 1) falling (a fixed bed, then a
// plateau, lower on the way down). Bins are 1/40 of the range (0.05 m/s) around their centres:
// a bin's mean lies between the function's values at its edges, within slope x 0.025 m/s of the
// value at the centre (25 Pa rising, 22.5 Pa falling), away from the kink at 1 m/s.
TEST(AnalyseSynthetic, PressureDropAgainstVelocity) {
  const fs::path d = temp_dir("loop");
  fs::create_directories(d / "out");
  auto dp = [](double u, bool rising) { return (rising ? 1000.0 : 900.0) * std::min(u, 1.0); };
  {
    std::ofstream f(d / "out" / "series.csv");
    f << "time,pressure_drop,superficial_velocity\n";
    char line[96];
    for (int i = 0; i <= 800; ++i) {
      const double t = 0.01 * i;
      const double u = t <= 4.0 ? 0.5 * t : 0.5 * (8.0 - t);
      std::snprintf(line, sizeof line, "%.10g,%.10g,%.10g\n", t, dp(u, t <= 4.0), u);
      f << line;
    }
  }
  const Result r = fluidem({"analyse", "out"}, d);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const Csv c = read_csv(d / "out" / "analysis" / "pressure_drop_velocity.csv");
  ASSERT_EQ(c.rows, 41u);
  int checked = 0;
  for (std::size_t k = 0; k < c.rows; ++k) {
    const double u = c.col.at("superficial_velocity")[k];
    EXPECT_NEAR(u, 0.05 * static_cast<double>(k), 1e-9);
    if (std::fabs(u - 1.0) < 0.06 || u < 0.01 || u > 1.99) continue; // the kink, the ends
    EXPECT_NEAR(c.col.at("pressure_drop_rising")[k], dp(u, true), 25.0 + 1e-9) << "U = " << u;
    EXPECT_NEAR(c.col.at("pressure_drop_falling")[k], dp(u, false), 22.5 + 1e-9) << "U = " << u;
    ++checked;
  }
  EXPECT_GE(checked, 30);
  EXPECT_NE(r.out.find("pressure_drop_velocity.csv"), std::string::npos) << r.out;
  if (std::getenv("FLUIDEM_KEEP_TEST_FILES") == nullptr) fs::remove_all(d);
}

} // namespace
