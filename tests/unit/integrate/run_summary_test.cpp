// The time split at the end of a run (RunSummary, the log's "time in ..." line): the gas
// solver's seconds are part of the gas-and-coupling seconds, which are part of the run's wall
// time; a run without gas reports none. A coupled hard-sphere bed of 20 spheres on the Tsuji
// grid, 0.01 s (100 flow steps), and the same bed without gas (soft spheres).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;

const std::string kBed = "[simulation]\ndimension = 2\nengine = \"hard_sphere\"\n"
                         "end_time = 0.01\ntime_step = 1e-4\n"
                         "[domain]\nlo = [0, 0, 0]\nhi = [0.15, 0.004, 0.3]\n"
                         "[[species]]\nname = \"s\"\ndiameter = 0.004\ndensity = 2700\n"
                         "[[insert]]\nspecies = \"s\"\ncount = 20\nplacement = \"lattice\"\n";
const std::string kGas = "[gas]\ncells = [15, 1, 15]\n"
                         "[gas.boundary.bottom]\ntype = \"inflow\"\nvelocity = 1.8\n"
                         "[gas.boundary.top]\ntype = \"pressure\"\npressure = 101325.0\n";

RunSummary run(const std::string& text, const std::string& name) {
  const fs::path out = fs::temp_directory_path() / name;
  fs::remove_all(out);
  Simulation sim(read_case_string(text, "case.toml"));
  const RunSummary s = sim.run(out.string());
  fs::remove_all(out);
  return s;
}

TEST(RunSummary, GasSolverTimeIsPartOfTheGasAndCouplingTime) {
  const RunSummary s = run(kBed + kGas, "fluidem_summary_gas");
  EXPECT_EQ(s.steps, 100);
  EXPECT_GT(s.seconds_gas_solver, 0.0);
  EXPECT_LE(s.seconds_gas_solver, s.seconds_gas);
  EXPECT_LE(s.seconds_gas, s.wall_seconds);
}

TEST(RunSummary, NoGasNoGasTime) {
  // Without gas the lattice settles into resting contacts: soft spheres (a hard-sphere bed
  // at rest collapses inelastically).
  std::string dry = kBed;
  dry.replace(dry.find("hard_sphere"), 11, "soft_sphere");
  dry.replace(dry.find("time_step = 1e-4"), 16, "time_step = 5e-5"); // < contact time / 10
  dry += "[contact]\nnormal = \"linear\"\nstiffness = 800.0\n";
  const RunSummary s = run(dry, "fluidem_summary_dry");
  EXPECT_EQ(s.steps, 200);
  EXPECT_EQ(s.seconds_gas, 0.0);
  EXPECT_EQ(s.seconds_gas_solver, 0.0);
}

} // namespace
} // namespace fluidem
