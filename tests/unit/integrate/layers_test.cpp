// Coloured layers (output.layers, issue 6): at t = 0 every particle gets the index of the
// horizontal band of the initial bed its centre lies in (bands split [lowest, highest] centre
// height along gravity's axis into N equal slices), the index is kept through a run and written
// to particles.h5 every frame (read back with H5mdReader), unchanged per particle id.
// Facts (exact, integers): for a lattice bed of R rows the particles of row r (counted from the
// bottom in the test from the initial heights) are in layer min(N-1, floor(r N / (R-1))), also
// for rows lying exactly on a band boundary; gravity along x bands the bed along x; layers = 0
// leaves every index 0 and writes no layer dataset; after a short run in which the particles
// move, every frame of particles.h5 holds the same layer for each id as frame 0.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"
#include "output/h5md_reader.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;

// 2-D lattice bed of 90 discs of 4 mm in a 40 mm wide box: 10 per row, 9 rows.
std::string lattice_case(int layers, const std::string& gravity = "[0.0, 0.0, -9.81]") {
  return "[simulation]\ndimension = 2\nend_time = 0.02\ntime_step = 2e-5\ngravity = " + gravity +
         "\n[domain]\nlo = [0, 0, 0]\nhi = [0.04, 0.004, 0.1]\n"
         "[[species]]\nname = \"s\"\ndiameter = 0.004\ndensity = 2500\n"
         "[[insert]]\nspecies = \"s\"\ncount = 90\nplacement = \"lattice\"\n"
         "region = { lo = [0, 0, 0], hi = [0.04, 0.004, 0.1] }\n"
         "[output]\nframe_interval = 0.005\nlayers = " +
         std::to_string(layers) + "\n";
}

// Row index of each particle along `h`: the rank of its height among the distinct heights
// (heights closer than 1e-9 m are one row). Returns the row count in `rows`.
std::vector<int> row_of(const std::vector<double>& h, int& rows) {
  std::vector<double> levels(h);
  std::sort(levels.begin(), levels.end());
  std::vector<double> distinct;
  for (double v : levels)
    if (distinct.empty() || v - distinct.back() > 1e-9) distinct.push_back(v);
  rows = static_cast<int>(distinct.size());
  std::vector<int> r(h.size());
  for (std::size_t i = 0; i < h.size(); ++i)
    r[i] = static_cast<int>(std::lower_bound(distinct.begin(), distinct.end(), h[i] - 1e-9) -
                            distinct.begin());
  return r;
}

void expect_lattice_layers(const std::vector<double>& h, const std::vector<std::int32_t>& layer,
                           int n) {
  int rows = 0;
  const std::vector<int> row = row_of(h, rows);
  ASSERT_GE(rows, 2);
  std::vector<int> count(static_cast<std::size_t>(n), 0);
  for (std::size_t i = 0; i < h.size(); ++i) {
    const int expected = std::min(n - 1, row[i] * n / (rows - 1));
    EXPECT_EQ(layer[i], expected) << "particle " << i << " in row " << row[i] << " of " << rows;
    if (layer[i] >= 0 && layer[i] < n) ++count[static_cast<std::size_t>(layer[i])];
  }
  for (int k = 0; k < n; ++k) EXPECT_GT(count[static_cast<std::size_t>(k)], 0) << "layer " << k;
}

TEST(Layers, LatticeBedBandsFollowTheInitialHeights) {
  // 9 rows: with 4 layers the rows 2, 4, 6 lie exactly on band boundaries (upper band);
  // with 3 and 5 they do not.
  for (const int n : {1, 3, 4, 5, 9}) {
    SCOPED_TRACE("layers = " + std::to_string(n));
    const Simulation sim(read_case_string(lattice_case(n), "case.toml"));
    const ParticleStore& p = sim.particles();
    ASSERT_EQ(p.size(), 90u);
    ASSERT_EQ(p.layer.size(), p.size());
    expect_lattice_layers(p.z, p.layer, n);
  }
}

TEST(Layers, BandsFollowTheAxisOfGravity) {
  const Simulation sim(read_case_string(lattice_case(5, "[-9.81, 0.0, 0.0]"), "case.toml"));
  const ParticleStore& p = sim.particles();
  expect_lattice_layers(p.x, p.layer, 5); // 10 columns along x
}

TEST(Layers, OffMeansLayerZeroAndNoDataset) {
  const fs::path out =
      fs::temp_directory_path() / ("fluidem_layers_off_" + std::to_string(::getpid()));
  fs::remove_all(out);
  CaseSpec spec = read_case_string(lattice_case(0), "case.toml");
  spec.simulation.end_time = 0.002;
  Simulation sim(spec);
  ASSERT_EQ(sim.particles().layer.size(), 90u);
  EXPECT_EQ(std::count(sim.particles().layer.begin(), sim.particles().layer.end(), 0), 90);
  sim.run(out.string());
  const H5mdReader r((out / "particles.h5").string());
  EXPECT_FALSE(r.has_layer());
  ParticleStore f;
  r.read_frame(0, f);
  EXPECT_EQ(std::count(f.layer.begin(), f.layer.end(), 0), 90);
  fs::remove_all(out);
}

TEST(Layers, ConstantPerParticleInParticlesH5) {
  const fs::path out =
      fs::temp_directory_path() / ("fluidem_layers_run_" + std::to_string(::getpid()));
  fs::remove_all(out);
  // An upward kick with a spread, so that the particles move across the bands' heights.
  CaseSpec spec = read_case_string(lattice_case(4), "case.toml");
  spec.inserts[0].velocity = {0.0, 0.0, 0.5};
  spec.inserts[0].velocity_spread = 0.3;
  Simulation sim(spec);
  sim.run(out.string());
  const H5mdReader r((out / "particles.h5").string());
  ASSERT_TRUE(r.has_layer());
  ASSERT_GE(r.frames(), 4u);
  ParticleStore first, frame;
  r.read_frame(0, first);
  expect_lattice_layers(first.z, first.layer, 4); // frame 0 is the initial bed
  std::map<std::int64_t, std::int32_t> layer_of;
  for (std::size_t i = 0; i < first.size(); ++i) layer_of[first.id[i]] = first.layer[i];
  ASSERT_EQ(layer_of.size(), 90u);
  double moved = 0.0;
  for (std::size_t k = 1; k < r.frames(); ++k) {
    r.read_frame(k, frame);
    ASSERT_EQ(frame.size(), 90u);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < frame.size(); ++i) {
      if (frame.layer[i] != layer_of.at(frame.id[i])) ++differ;
      moved = std::max(moved, std::abs(frame.z[i] - first.z[i]));
    }
    EXPECT_EQ(differ, 0u) << "frame " << k << ": " << differ << " particles changed layer";
  }
  // The run must have moved particles (by more than a tenth of a diameter), or constancy
  // would be trivial.
  EXPECT_GT(moved, 0.4e-3);
  fs::remove_all(out);
}

} // namespace
} // namespace fluidem
