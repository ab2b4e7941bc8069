// The non-finite guard (Simulation::check_stability): a particle whose velocity becomes NaN
// stops the run with an InstabilityError naming the particle's id and the time, before any
// output row or frame holds the NaN, and without writing a checkpoint of the bad state (the
// last good checkpoint stays).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "../../common/bouncing_spheres.hpp"
#include "core/error.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;

const std::string kCase = fluidem::test::bouncing_spheres_case({.dimension = 2,
                                                                .end_time = 0.02,
                                                                .time_step = 1e-5,
                                                                .frame_interval = 0.01,
                                                                .series_interval = 0.001,
                                                                .checkpoint_interval = 0.01,
                                                                .engine_key = false,
                                                                .moving = false});

TEST(StabilityGuard, NonFiniteVelocityStopsTheRunBeforeItReachesTheOutputs) {
  const fs::path out = fs::temp_directory_path() / "fluidem_guard_nan";
  fs::remove_all(out);
  // A good run to 0.02 s leaves a checkpoint at 0.02 s.
  Simulation good(read_case_string(kCase, "guard.toml"));
  good.run(out.string());
  const auto stamp = fs::last_write_time(out / "checkpoint.h5");
  // Continue from it with particle 4 poisoned.
  auto sim = Simulation::restart((out / "checkpoint.h5").string(), {"simulation.end_time=0.04"});
  sim->particles().vy[4] = std::numeric_limits<double>::quiet_NaN();
  sim->particles().vz[4] = std::numeric_limits<double>::quiet_NaN();
  RunOptions resume;
  resume.resume = true;
  try {
    sim->run(out.string(), {}, resume);
    ADD_FAILURE() << "a NaN velocity did not stop the run";
  } catch (const InstabilityError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("particle " + std::to_string(sim->particles().id[4])), std::string::npos) << m;
    EXPECT_NE(m.find("non-finite"), std::string::npos) << m;
    EXPECT_NE(m.find("t = "), std::string::npos) << m;
  }
  std::ifstream f(out / "series.csv");
  std::stringstream text;
  text << f.rdbuf();
  EXPECT_EQ(text.str().find("nan"), std::string::npos) << "a NaN reached series.csv";
  EXPECT_EQ(fs::last_write_time(out / "checkpoint.h5"), stamp)
      << "the last good checkpoint was replaced";
  EXPECT_NO_THROW(
      Simulation::restart((out / "checkpoint.h5").string(), {"simulation.end_time=0.04"}));
  fs::remove_all(out);
}

} // namespace
} // namespace fluidem
