// `fluidem analyse OUT` with OUT/collisions.csv (docs/analysis.md, "Collision statistics"): the
// summary rows over the analysis window, checked against sums, means and maxima worked out by
// hand from a synthetic collisions.csv (rows whose interval ends in (T0, T1]; NaN cells left out
// of the means; mean_free_time = 1 / mean frequency). A synthetic probes.csv (64 rows, 1 ms
// apart) gives the window: the second half, [0.0315, 0.063] s.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "../../common/cli_runner.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;

std::map<std::string, double> summary(const fs::path& file) {
  std::map<std::string, double> m;
  std::istringstream in(test::read_file(file));
  std::string line;
  std::getline(in, line); // header
  while (std::getline(in, line)) {
    const auto a = line.find(','), b = line.rfind(',');
    m[line.substr(0, a)] = std::stod(line.substr(a + 1, b - a - 1));
  }
  return m;
}

/// DIR/out with the synthetic probes.csv (the analysis window); returns DIR/out.
fs::path write_probes(test::TempDir& dir) {
  const fs::path out = dir.path / "out";
  fs::create_directories(out);
  std::string probes = "time,p\n";
  for (int k = 0; k < 64; ++k)
    probes += std::to_string(0.001 * k) + "," + std::to_string(std::sin(k)) + "\n";
  dir.write("out/probes.csv", probes);
  return out;
}

TEST(AnalyseCollisions, SummaryOverTheWindow) {
  test::TempDir dir("fluidem_analyse_coll");
  const fs::path out = write_probes(dir);
  dir.write("out/collisions.csv",
            "time,pair_collisions,wall_collisions,collision_frequency,mean_free_time,"
            "mean_overlap_extent,max_overlap_extent,mean_contact_duration,GC_collision_frequency,"
            "GC_void_fraction,GC_particles\n"
            "0,0,0,nan,nan,nan,nan,nan,nan,nan,nan\n"
            "0.02,100,5,200,0.005,0.01,0.03,0.0002,100,0.8,10\n" // before the window
            "0.04,60,4,120,0.0083,0.02,0.05,0.0003,90,0.9,6\n"
            "0.05,0,1,0,inf,nan,nan,nan,nan,0.7,0\n"
            "0.06,90,3,180,0.0056,0.01,0.04,0.0001,30,0.8,8\n");
  const auto r = test::fluidem({"analyse", "out"}, dir.path);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("collisions         3 rows"), std::string::npos) << r.out;
  const auto s = summary(out / "analysis" / "summary.csv");
  EXPECT_EQ(s.at("pair_collisions_window"), 150.0);
  EXPECT_EQ(s.at("wall_collisions_window"), 8.0);
  EXPECT_NEAR(s.at("collision_frequency"), 100.0, 1e-8);
  EXPECT_NEAR(s.at("mean_free_time"), 0.01, 1e-12);
  EXPECT_NEAR(s.at("mean_overlap_extent"), 0.015, 1e-12);
  EXPECT_NEAR(s.at("max_overlap_extent"), 0.05, 1e-12);
  EXPECT_NEAR(s.at("mean_contact_duration"), 0.0002, 1e-12);
  EXPECT_NEAR(s.at("GC_collision_frequency"), 60.0, 1e-8);
  EXPECT_NEAR(s.at("GC_void_fraction"), 0.8, 1e-12);
  EXPECT_NEAR(s.at("GC_particles"), 14.0 / 3.0, 1e-9);
}

// Soft spheres: the multiple-collision fraction over the window is the sum of the multiple
// collisions over the sum of the collisions ended (not the mean of the rows' fractions):
// (3 + 0 + 9) / (30 + 0 + 10) = 0.3; GC (1 + 4) / (10 + 5) = 1/3.
TEST(AnalyseCollisions, MultipleCollisionFractionsAreSumsOverTheWindow) {
  test::TempDir dir("fluidem_analyse_multi");
  const fs::path out = write_probes(dir);
  dir.write("out/collisions.csv",
            "time,pair_collisions,wall_collisions,collision_frequency,mean_free_time,"
            "mean_overlap_extent,max_overlap_extent,mean_contact_duration,ended_collisions,"
            "multiple_collisions,GC_collision_frequency,GC_void_fraction,GC_particles,"
            "GC_ended_collisions,GC_multiple_collisions\n"
            "0.02,100,5,200,0.005,0.01,0.03,0.0002,99,99,100,0.8,10,50,50\n" // before the window
            "0.04,60,4,120,0.0083,0.02,0.05,0.0003,30,3,90,0.9,6,10,1\n"
            "0.05,0,1,0,inf,nan,nan,nan,0,0,nan,0.7,0,0,0\n"
            "0.06,90,3,180,0.0056,0.01,0.04,0.0001,10,9,30,0.8,8,5,4\n");
  const auto r = test::fluidem({"analyse", "out"}, dir.path);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const auto s = summary(out / "analysis" / "summary.csv");
  EXPECT_EQ(s.at("ended_collisions"), 40.0);
  EXPECT_EQ(s.at("multiple_collisions"), 12.0);
  EXPECT_NEAR(s.at("multiple_collision_fraction"), 0.3, 1e-9); // (10 digits in summary.csv)
  EXPECT_NEAR(s.at("GC_multiple_collision_fraction"), 1.0 / 3.0, 1e-9);
}

} // namespace
} // namespace fluidem
