// python/fluidem_plot.py on a coupled run's output: a small fixture directory written with the
// output module's own writers (particles.h5, fields.h5, series.csv with pressure_drop, probes.csv;
// 2 frames, a 4 x 1 x 6 gas grid with a known porosity pattern). Checks that the script exits 0
// and writes a valid PNG of reasonable size, that the porosity panel shows the right frame with
// cells in the right place (x along the columns, z up, mm, the particle panel's limits), that the
// pressure curves are the files' values in kPa, and the documented behaviour for a bad fields.h5:
// warning on stderr, picture without the porosity panel, exit 0.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "output/fields_writer.hpp"
#include "output/h5md_writer.hpp"
#include "output/series_writer.hpp"

namespace fs = std::filesystem;
using fluidem::FieldGrid;
using fluidem::FieldsWriter;
using fluidem::H5mdBox;
using fluidem::H5mdWriter;
using fluidem::ParticleStore;
using fluidem::SeriesWriter;

namespace {

// A fresh directory per test, removed afterwards (kept with FLUIDEM_KEEP_TEST_FILES set).
class TempDir {
public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("fluidem_plotcpl_" + std::to_string(::getpid()) + "_" +
                                         info->test_suite_name() + "_" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    if (std::getenv("FLUIDEM_KEEP_TEST_FILES") != nullptr) return;
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string str() const { return path_.string(); }

private:
  fs::path path_;
};

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1 || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

bool python_has_plot_modules() {
  static const bool ok = run(std::string(FLUIDEM_PYTHON) +
                             " -c 'import h5py, numpy, matplotlib' >/dev/null 2>&1") == 0;
  return ok;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Run the plot script on `dir` with extra arguments; stdout+stderr go to dir/plot.log.
int plot(const TempDir& dir, const std::string& extra = "") {
  const std::string cmd = std::string(FLUIDEM_PYTHON) + " '" + FLUIDEM_SOURCE_DIR +
                          "/python/fluidem_plot.py' '" + dir.str() + "' " + extra + " > '" +
                          dir.file("plot.log") + "' 2>&1";
  return run(cmd);
}

// A valid PNG (signature, IHDR first) of a plausible picture size; width/height returned.
bool png_size(const std::string& path, std::uint32_t& width, std::uint32_t& height) {
  const std::string s = slurp(path);
  if (s.size() < 33 || std::memcmp(s.data(), "\x89PNG\r\n\x1a\n", 8) != 0) return false;
  if (s.compare(12, 4, "IHDR") != 0) return false;
  auto be32 = [&](std::size_t at) {
    return (std::uint32_t(std::uint8_t(s[at])) << 24) |
           (std::uint32_t(std::uint8_t(s[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(s[at + 2])) << 8) | std::uint32_t(std::uint8_t(s[at + 3]));
  };
  width = be32(16);
  height = be32(20);
  return s.compare(s.size() - 8, 4, "IEND") == 0; // complete file
}

// --- the fixture ---------------------------------------------------------------------------

constexpr int kNx = 4, kNy = 1, kNz = 6;
constexpr double kDx = 0.01, kDy = 0.004, kDz = 0.01; // domain 40 mm x 4 mm x 60 mm
const long kSteps[2] = {0, 100};
const double kTimes[2] = {0.0, 0.01};

// The porosity of cell (i, k) in frame f: distinct in every cell and frame, so a transposed,
// flipped or wrong-frame picture is caught. The check script has the same formula.
double porosity(int i, int k, int f) {
  return 0.4 + 0.1 * i + 0.01 * k + 0.005 * f;
}

ParticleStore particles(int f) {
  ParticleStore p;
  for (int n = 0; n < 6; ++n) {
    p.add({0.005 + 0.006 * n, 0.002, 0.004 + 0.001 * f + 0.002 * (n % 2)}, {0.0, 0.0, 0.1 * n},
          0.002, 2500.0, n % 2, 10 + n);
  }
  return p;
}

void write_particles(const TempDir& dir) {
  H5mdBox box;
  box.lo = {0.0, 0.0, 0.0};
  box.hi = {kNx * kDx, kNy * kDy, kNz * kDz};
  H5mdWriter w(dir.file("particles.h5"), 6, 2, "test", box);
  for (int f = 0; f < 2; ++f) w.write_frame(kSteps[f], kTimes[f], particles(f));
}

// fields.h5 with `frames` frames (at kTimes, then 0.01 apart); `with_porosity` false leaves the
// porosity out; `time_shift` is added to the written times.
void write_fields(const TempDir& dir, int frames, bool with_porosity = true,
                  double time_shift = 0.0) {
  FieldGrid g;
  g.cells = {kNx, kNy, kNz};
  g.lo = {0.0, 0.0, 0.0};
  g.spacing = {kDx, kDy, kDz};
  std::vector<std::string> scalars{"pressure"};
  if (with_porosity) scalars.insert(scalars.begin(), "porosity");
  FieldsWriter w(dir.file("fields.h5"), g, scalars, {"gas_velocity", "solids_velocity"}, "test");
  const std::size_t n = g.size();
  for (int f = 0; f < frames; ++f) {
    std::vector<double> eps(n), p(n), ux(n), uy(n, 0.0), uz(n), zero(n, 0.0);
    for (int k = 0; k < kNz; ++k) {
      for (int i = 0; i < kNx; ++i) {
        const std::size_t c = static_cast<std::size_t>(i + kNx * k); // ny = 1
        eps[c] = porosity(i, k, f);
        p[c] = 101325.0 + 100.0 * (kNz - k);
        ux[c] = 0.1 * (i - 1.5);
        uz[c] = 1.0 + 0.5 * i + (i == 2 && k == 0 ? 20.0 : 0.0); // one fast cell: a red arrow
      }
    }
    std::vector<const double*> sp{p.data()};
    if (with_porosity) sp.insert(sp.begin(), eps.data());
    const double t = (f < 2 ? kTimes[f] : 0.01 * f) + time_shift;
    w.write_frame(f < 2 ? kSteps[f] : 100L * f, t, sp,
                  {{ux.data(), uy.data(), uz.data()}, {zero.data(), zero.data(), zero.data()}});
  }
}

// series.csv of a coupled run (with pressure_drop), and probes.csv with two probes.
void write_series_and_probes(const TempDir& dir) {
  SeriesWriter s(dir.file("series.csv"),
                 {"time", "e_kin", "e_rot", "e_pot", "e_el", "e_dsp", "e_total", "n_contacts",
                  "pressure_drop", "bed_height", "gas_iterations"});
  SeriesWriter pr(dir.file("probes.csv"), {"time", "p_low", "p_high"});
  for (int r = 0; r <= 10; ++r) {
    const double t = 0.001 * r;
    s.write_row({t, 1e-4 * r, 0.0, 0.01 - 1e-4 * r, 0.0, 1e-5 * r, 0.01 + 1e-5 * r, 3.0,
                 500.0 + 50.0 * r, 0.02, 7.0});
    pr.write_row({t, 101825.0 + 10.0 * r, 101425.0 - 5.0 * r});
  }
}

// Python that rebuilds the figure with the script's make_figure and checks what it holds.
// argv: outdir, mode ("full" or "no_porosity"), frame.
const char* kCheckScript = R"PY(
import sys
import numpy as np
sys.path.insert(0, sys.argv[1])
import fluidem_plot as fp
from matplotlib.collections import QuadMesh

outdir, mode, frame = sys.argv[2], sys.argv[3], int(sys.argv[4])
fig, d = fp.make_figure(fp.parse_args([outdir, "--frame", str(frame)]))
axes = {a.get_label(): a for a in fig.axes if a.get_label()}
def check(cond, what):
    if not cond:
        print("CHECK FAILED:", what, file=sys.stderr)
        sys.exit(1)

expected = {"particles", "pressure_drop", "probes", "energies"}
if mode == "full":
    expected.add("porosity")
check(expected <= set(axes), f"axes {sorted(axes)}, expected {sorted(expected)}")
if mode != "full":
    check("porosity" not in axes, "porosity panel drawn from a bad fields.h5")
    sys.exit(0)

f = d["frame"]
ax = axes["porosity"]
meshes = [c for c in ax.collections if isinstance(c, QuadMesh)]
check(len(meshes) == 1, f"{len(meshes)} QuadMesh in the porosity panel")
mesh = meshes[0]
xy = np.asarray(mesh.get_coordinates())            # (nz+1, nx+1, 2), mm
vals = np.asarray(mesh.get_array()).reshape(6, 4)  # rows: z, columns: x
check(xy.shape == (7, 5, 2), f"mesh vertices {xy.shape}")
centres = 0.25 * (xy[:-1, :-1] + xy[1:, :-1] + xy[:-1, 1:] + xy[1:, 1:])
for k in range(6):
    for i in range(4):
        cx, cz = centres[k, i]
        check(abs(cx - 10.0 * (i + 0.5)) < 1e-9 and abs(cz - 10.0 * (k + 0.5)) < 1e-9,
              f"cell {i},{k} centred at ({cx}, {cz}) mm")
        want = 0.4 + 0.1 * i + 0.01 * k + 0.005 * f
        check(abs(vals[k, i] - want) < 1e-12, f"porosity of cell {i},{k}: {vals[k, i]} != {want}")
p_ax = axes["particles"]
check(np.allclose(ax.get_xlim(), p_ax.get_xlim()) and np.allclose(ax.get_ylim(), p_ax.get_ylim()),
      f"porosity limits {ax.get_xlim()} {ax.get_ylim()} vs particles {p_ax.get_xlim()} "
      f"{p_ax.get_ylim()}")
check(np.allclose(ax.get_xlim(), (0, 40)) and np.allclose(ax.get_ylim(), (0, 60)), "limits in mm")
check(ax.get_aspect() == 1.0, f"aspect {ax.get_aspect()}")
labels = [a.get_ylabel() for a in fig.axes]
check("gas volume fraction" in labels, f"no colour bar 'gas volume fraction' in {labels}")
check(len(ax.collections) > 1, "no gas velocity arrows")

t = 0.001 * np.arange(11)
dp = [l for l in axes["pressure_drop"].get_lines() if len(l.get_xdata()) == 11]
check(len(dp) == 1 and np.allclose(dp[0].get_ydata(), (500 + 50 * np.arange(11)) / 1e3),
      "pressure drop curve (kPa)")
pl = [l for l in axes["probes"].get_lines() if len(l.get_xdata()) == 11]
low = 101825 + 10.0 * np.arange(11)
high = 101425 - 5.0 * np.arange(11)
check(len(pl) == 2, f"{len(pl)} probe curves")
check(np.allclose(pl[0].get_ydata(), (low - low.mean()) / 1e3)
      and np.allclose(pl[1].get_ydata(), (high - high.mean()) / 1e3), "probe curves (kPa)")
check("kPa" in axes["probes"].get_ylabel() and "mean" in axes["probes"].get_ylabel(),
      axes["probes"].get_ylabel())
check("not conserved" in axes["energies"].get_title(), axes["energies"].get_title())
)PY";

int check_figure(const TempDir& dir, const std::string& mode, int frame) {
  {
    std::ofstream out(dir.file("check_figure.py"));
    out << kCheckScript;
  }
  const std::string cmd = std::string(FLUIDEM_PYTHON) + " '" + dir.file("check_figure.py") + "' '" +
                          FLUIDEM_SOURCE_DIR + "/python' '" + dir.str() + "' " + mode + " " +
                          std::to_string(frame) + " > '" + dir.file("check.log") + "' 2>&1";
  return run(cmd);
}

void expect_png(const std::string& path) {
  ASSERT_TRUE(fs::exists(path)) << path;
  std::uint32_t w = 0, h = 0;
  ASSERT_TRUE(png_size(path, w, h)) << path << " is not a complete PNG";
  EXPECT_GT(fs::file_size(path), 20000u);
  EXPECT_GE(w, 1000u);
  EXPECT_LE(w, 6000u);
  EXPECT_GE(h, 600u);
  EXPECT_LE(h, 3000u);
}

} // namespace

TEST(FluidemPlotCoupled, PorosityPanelAndPressureCurves) {
  if (!python_has_plot_modules()) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy/matplotlib";
  TempDir dir;
  write_particles(dir);
  write_fields(dir, 2);
  write_series_and_probes(dir);

  ASSERT_EQ(plot(dir), 0) << slurp(dir.file("plot.log"));
  EXPECT_EQ(slurp(dir.file("plot.log")).find("warning"), std::string::npos)
      << slurp(dir.file("plot.log"));
  expect_png(dir.file("snapshot.png"));

  const std::string first = dir.file("first.png");
  ASSERT_EQ(plot(dir, "--frame 0 --color-by speed --out '" + first + "'"), 0)
      << slurp(dir.file("plot.log"));
  expect_png(first);

  // What the figure holds: the last frame by default, and frame 0 on request.
  EXPECT_EQ(check_figure(dir, "full", -1), 0) << slurp(dir.file("check.log"));
  EXPECT_EQ(check_figure(dir, "full", 0), 0) << slurp(dir.file("check.log"));

  // A frame particles.h5 does not hold is still bad input.
  EXPECT_EQ(plot(dir, "--frame 2"), 2);
}

TEST(FluidemPlotCoupled, FrameCountMismatchSkipsThePanelWithAWarning) {
  if (!python_has_plot_modules()) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy/matplotlib";
  for (const int frames : {1, 3}) {
    TempDir dir;
    write_particles(dir);
    write_fields(dir, frames);
    write_series_and_probes(dir);
    ASSERT_EQ(plot(dir), 0) << frames << ": " << slurp(dir.file("plot.log"));
    const std::string log = slurp(dir.file("plot.log"));
    EXPECT_NE(log.find("fluidem_plot: warning:"), std::string::npos) << log;
    EXPECT_NE(log.find("fields.h5 holds " + std::to_string(frames) + " frames"), std::string::npos)
        << log;
    EXPECT_NE(log.find("particles.h5 holds 2"), std::string::npos) << log;
    expect_png(dir.file("snapshot.png"));
    EXPECT_EQ(check_figure(dir, "no_porosity", -1), 0) << slurp(dir.file("check.log"));
  }
}

TEST(FluidemPlotCoupled, MissingPorosityOrOtherTimesSkipThePanelWithAWarning) {
  if (!python_has_plot_modules()) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy/matplotlib";
  {
    TempDir dir;
    write_particles(dir);
    write_fields(dir, 2, /*with_porosity=*/false);
    write_series_and_probes(dir);
    ASSERT_EQ(plot(dir), 0) << slurp(dir.file("plot.log"));
    const std::string log = slurp(dir.file("plot.log"));
    EXPECT_NE(log.find("no dataset /fields/porosity"), std::string::npos) << log;
    expect_png(dir.file("snapshot.png"));
    EXPECT_EQ(check_figure(dir, "no_porosity", -1), 0) << slurp(dir.file("check.log"));
  }
  {
    TempDir dir;
    write_particles(dir);
    write_fields(dir, 2, true, /*time_shift=*/0.5);
    write_series_and_probes(dir);
    ASSERT_EQ(plot(dir), 0) << slurp(dir.file("plot.log"));
    const std::string log = slurp(dir.file("plot.log"));
    EXPECT_NE(log.find("warning: frame 1 of"), std::string::npos) << log;
    expect_png(dir.file("snapshot.png"));
  }
  {
    // Not an HDF5 file at all.
    TempDir dir;
    write_particles(dir);
    std::ofstream(dir.file("fields.h5")) << "not hdf5\n";
    ASSERT_EQ(plot(dir), 0) << slurp(dir.file("plot.log"));
    EXPECT_NE(slurp(dir.file("plot.log")).find("warning: cannot open"), std::string::npos)
        << slurp(dir.file("plot.log"));
    expect_png(dir.file("snapshot.png"));
  }
}
