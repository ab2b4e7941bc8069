// `fluidem analyse` on the gas fields (app/analyse_bubbles.hpp): a fields.h5 written by
// FieldsWriter holding a disc-shaped void (porosity 0.95, radius 3.1 cells) in a bed of porosity
// 0.4 under a freeboard of porosity 1, rising 2 cells (10 mm) per frame of 0.02 s. The
// references are those of the painting: one bubble per frame, followed under one id, rising at
// 10 mm / 0.02 s = 0.5 m/s (exactly, up to round-off: the painted cells move rigidly), its share
// of the 30 x 40 bed cells, and its cell count. A file that is not a fields file is an InputError
// naming it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "../../common/cli_runner.hpp"
#include "app/analyse_bubbles.hpp"
#include "core/error.hpp"
#include "output/fields_reader.hpp"
#include "output/fields_writer.hpp"

namespace {

using fluidem::test::TempDir;
namespace fs = std::filesystem;

constexpr double kH = 0.005, kDt = 0.02;

std::vector<double> frame_field(int frame, std::size_t& painted) {
  std::vector<double> eps(30 * 60, 0.4);
  painted = 0;
  const double xc = 0.0725, zc = 0.0525 + 2 * kH * frame, r = 3.1 * kH;
  for (int k = 0; k < 60; ++k)
    for (int i = 0; i < 30; ++i) {
      const double x = (i + 0.5) * kH, z = (k + 0.5) * kH;
      auto& e = eps[static_cast<std::size_t>(i + 30 * k)];
      if (z > 0.2) e = 1.0;
      if ((x - xc) * (x - xc) + (z - zc) * (z - zc) < r * r) {
        e = 0.95;
        ++painted;
      }
    }
  return eps;
}

double summary_value(const std::vector<fluidem::SummaryRow>& rows, const std::string& name) {
  for (const auto& r : rows)
    if (r.name == name) return r.value;
  ADD_FAILURE() << "no summary row " << name;
  return 0.0;
}

} // namespace

TEST(AnalyseBubbles, RisingVoidIsOneBubbleAtItsRiseVelocity) {
  TempDir dir("fluidem_bubbles");
  const fs::path fields = dir.path / "fields.h5";
  fluidem::FieldGrid grid;
  grid.cells = {30, 1, 60};
  grid.spacing = {kH, 0.004, kH};
  std::size_t painted = 0;
  {
    fluidem::FieldsWriter w(fields.string(), grid, {"porosity", "pressure"}, {}, "test");
    const std::vector<double> p(grid.size(), 0.0);
    for (int f = 0; f < 4; ++f) {
      const std::vector<double> eps = frame_field(f, painted);
      w.write_frame(f, f * kDt, {eps.data(), p.data()}, {});
    }
  }
  const fluidem::FieldsReader reader(fields.string());
  EXPECT_EQ(reader.frames(), 4u);
  EXPECT_EQ(reader.cells(), (std::array<int, 3>{30, 1, 60}));
  EXPECT_TRUE(reader.has_scalar("porosity"));
  EXPECT_FALSE(reader.has_scalar("solids_velocity"));

  std::vector<fluidem::SummaryRow> summary;
  fluidem::analyse_bubbles(fields, dir.path, 0.0, 1.0, 0.8, summary);
  EXPECT_DOUBLE_EQ(summary_value(summary, "bubble_count_mean"), 1.0);
  EXPECT_NEAR(summary_value(summary, "bubble_rise_velocity_mean"), 2 * kH / kDt, 1e-12);
  EXPECT_NEAR(summary_value(summary, "bubble_fraction_mean"),
              static_cast<double>(painted) / (30 * 40), 1e-14);
  EXPECT_NEAR(summary_value(summary, "bubble_diameter_mean"),
              std::sqrt(4.0 * static_cast<double>(painted) * kH * kH / std::numbers::pi), 1e-12);
  // bubbles.csv: one row per frame, all id 0, the first without a rise velocity.
  std::ifstream in(dir.path / "bubbles.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "time,id,x,y,z,z_bottom,z_top,cells,size,equivalent_diameter,rise_velocity,"
                  "touches_wall");
  int rows = 0;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string time, id, x, y, z, z_bottom, z_top, cells, size, d, rise;
    std::getline(s, time, ',');
    std::getline(s, id, ',');
    std::getline(s, x, ',');
    std::getline(s, y, ',');
    std::getline(s, z, ',');
    std::getline(s, z_bottom, ',');
    std::getline(s, z_top, ',');
    std::getline(s, cells, ',');
    std::getline(s, size, ',');
    std::getline(s, d, ',');
    std::getline(s, rise, ',');
    EXPECT_EQ(id, "0");
    EXPECT_EQ(cells, std::to_string(painted));
    // The painted disc spans 3 cells below and above its centre cell: 7 cells of height.
    EXPECT_NEAR(std::stod(z_top) - std::stod(z_bottom), 7 * kH, 1e-9);
    if (rows == 0)
      EXPECT_EQ(rise, "nan");
    else
      EXPECT_NEAR(std::stod(rise), 0.5, 1e-9);
    ++rows;
  }
  EXPECT_EQ(rows, 4);
  EXPECT_TRUE(fs::exists(dir.path / "bubble_frames.csv"));
}

TEST(AnalyseBubbles, AFileThatIsNotAFieldsFileIsRefusedByName) {
  TempDir dir("fluidem_bubbles_bad");
  const fs::path bad = dir.write("fields.h5", "not hdf5");
  std::vector<fluidem::SummaryRow> summary;
  try {
    fluidem::analyse_bubbles(bad, dir.path, 0.0, 1.0, 0.8, summary);
    FAIL() << "no error";
  } catch (const fluidem::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
  EXPECT_THROW(fluidem::FieldsReader((dir.path / "none.h5").string()), std::runtime_error);
}
