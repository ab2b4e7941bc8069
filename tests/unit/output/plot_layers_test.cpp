// python/fluidem_plot.py --color layer (issue 6): on a particles.h5 with /particles/all/layer
// (6 particles, layers 0 1 2 0 1 2) the script exits 0 and writes a complete PNG; the particles
// of even layers are drawn in one colour and those of odd layers in another (checked on the
// figure from make_figure); without --color the layer colouring is chosen when the file has
// layers and species colouring when it has none; --color layer on a file without layers exits 2.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "output/h5md_writer.hpp"

namespace fs = std::filesystem;
using fluidem::H5mdBox;
using fluidem::H5mdWriter;
using fluidem::ParticleStore;

namespace {

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1 || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

bool python_has_plot_modules() {
  return run(std::string(FLUIDEM_PYTHON) +
             " -c 'import h5py, numpy, matplotlib' >/dev/null 2>&1") == 0;
}

fs::path make_dir(const std::string& name, bool layers) {
  const fs::path dir =
      fs::temp_directory_path() / ("fluidem_plotlayers_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  H5mdBox box;
  box.hi = {0.04, 0.004, 0.04};
  H5mdWriter w((dir / "particles.h5").string(), 6, 2, "test", box, {}, layers);
  ParticleStore p;
  for (int n = 0; n < 6; ++n)
    p.add({0.005 + 0.006 * n, 0.002, 0.004 + 0.005 * (n % 3)}, {0.0, 0.0, 0.0}, 0.002, 2500.0, 0,
          n);
  for (int n = 0; n < 6; ++n) p.layer[static_cast<std::size_t>(n)] = n % 3;
  w.write_frame(0, 0.0, p);
  w.close();
  return dir;
}

int plot(const fs::path& dir, const std::string& extra) {
  return run(std::string(FLUIDEM_PYTHON) + " '" + FLUIDEM_SOURCE_DIR +
             "/python/fluidem_plot.py' '" + dir.string() + "' " + extra + " > '" +
             (dir / "plot.log").string() + "' 2>&1");
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Rebuilds the figure and checks the colours. argv: script dir, outdir, color argument or "",
// expected colouring ("layer" or "species").
const char* kCheck = R"PY(
import sys
sys.path.insert(0, sys.argv[1])
import numpy as np
import fluidem_plot as fp
from matplotlib.collections import PatchCollection
outdir, colour, expected = sys.argv[2], sys.argv[3], sys.argv[4]
args = [outdir] + (["--color", colour] if colour else [])
fig, d = fp.make_figure(fp.parse_args(args))
ax = [a for a in fig.axes if a.get_label() == "particles"][0]
coll = [c for c in ax.collections if isinstance(c, PatchCollection)][0]
fc = np.asarray(coll.get_facecolors())
layer = np.array([0, 1, 2, 0, 1, 2])
if expected == "layer":
    even = fc[layer % 2 == 0]
    odd = fc[layer % 2 == 1]
    ok = (np.all(even == even[0]) and np.all(odd == odd[0])
          and np.abs(even[0][:3] - odd[0][:3]).sum() > 1.5)  # contrasting (black/white: 3)
else:
    ok = np.all(fc == fc[0])  # one species: one colour
ok = ok and ("coloured by " + expected) in ax.get_title()
print("colours", fc.tolist(), "title", ax.get_title())
sys.exit(0 if ok else 1)
)PY";

int check(const fs::path& dir, const std::string& colour, const std::string& expected) {
  const fs::path script = dir / "check.py";
  std::ofstream(script) << kCheck;
  return run(std::string(FLUIDEM_PYTHON) + " '" + script.string() + "' '" + FLUIDEM_SOURCE_DIR +
             "/python' '" + dir.string() + "' '" + colour + "' " + expected + " >> '" +
             (dir / "plot.log").string() + "' 2>&1");
}

TEST(PlotLayers, ColorLayerWritesAPngWithAlternatingColours) {
  if (!python_has_plot_modules()) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy/matplotlib";
  const fs::path dir = make_dir("with", true);
  ASSERT_EQ(plot(dir, "--color layer --out '" + (dir / "l.png").string() + "'"), 0)
      << slurp(dir / "plot.log");
  const std::string png = slurp(dir / "l.png");
  ASSERT_GT(png.size(), 5000u);
  EXPECT_EQ(std::memcmp(png.data(), "\x89PNG\r\n\x1a\n", 8), 0);
  EXPECT_EQ(png.compare(png.size() - 8, 4, "IEND"), 0); // complete file
  EXPECT_EQ(check(dir, "layer", "layer"), 0) << slurp(dir / "plot.log");
  EXPECT_EQ(check(dir, "", "layer"), 0) << slurp(dir / "plot.log"); // the default with layers
  EXPECT_EQ(check(dir, "species", "species"), 0) << slurp(dir / "plot.log");
  fs::remove_all(dir);
}

TEST(PlotLayers, WithoutLayersDefaultsToSpeciesAndRejectsColorLayer) {
  if (!python_has_plot_modules()) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy/matplotlib";
  const fs::path dir = make_dir("without", false);
  EXPECT_EQ(check(dir, "", "species"), 0) << slurp(dir / "plot.log");
  EXPECT_EQ(plot(dir, "--color layer"), 2) << slurp(dir / "plot.log");
  EXPECT_NE(slurp(dir / "plot.log").find("holds no layers"), std::string::npos);
  fs::remove_all(dir);
}

} // namespace
