// `mpirun -n P fluidem run` (docs/parallel.md): a settling bed of 1500 glass spheres (Hertz,
// tangential history; periodic along y, walls elsewhere; random start with velocities, so that
// particles cross the ranks' cut planes and the lists are rebuilt) run by one process with
// parallel.rank_independent = true and by mpirun on 2, 3 and 4 ranks (oversubscribed on two
// cores) writes the same series.csv, bit for bit, and checkpoints whose every array but the
// run's random id is the same; a checkpoint written on 4 ranks continues in place on 1, 2 and 3
// ranks to the same files as the uninterrupted run; two skins give the same particles (only the
// build count differs); a coupled bed and a liquid-fluidised bed with [coupling.forces] give
// the files of one process (tests below), as do non-contact forces and liquid bridges; what the
// distributed engine does not take is refused with exit 2.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../../common/cli_runner.hpp"
#include "output/checkpoint_file.hpp"

namespace fluidem {
namespace {

using test::contains;
using test::Result;
using test::TempDir;

const char* const kBed = R"(
[simulation]
engine = "soft_sphere"
dimension = 3
end_time = 0.012
time_step = 1e-5
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.03, 0.02, 0.04]
periodic = [false, true, false]
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
youngs_modulus = 1e7
restitution = 0.8
friction = 0.4
rolling_friction = 0.05
[[insert]]
species = "glass"
count = 1500
placement = "random"
velocity_spread = 0.5
seed = 3
[contact]
normal = "hertz"
tangential = "history"
[output]
frame_interval = 0.004
series_interval = 0.001
checkpoint_interval = 0.006
)";

/// A coupled bed: 1200 glass spheres of 2 mm in a column periodic across, air from below at
/// 1.5 m/s through 4 x 2 x 12 gas cells (Model A, porosity by cell, Ergun/Wen-Yu drag).
const char* const kCoupled = R"(
[simulation]
engine = "soft_sphere"
dimension = 3
end_time = 0.012
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.04, 0.02, 0.12]
periodic = [true, true, false]
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
youngs_modulus = 1e7
restitution = 0.9
friction = 0.3
[[insert]]
species = "glass"
count = 1200
placement = "random"
region = { lo = [0.0, 0.0, 0.0], hi = [0.04, 0.02, 0.06] }
seed = 4
[contact]
normal = "hertz"
tangential = "history"
[gas]
cells = [4, 2, 12]
time_step = 1e-4
[gas.boundary.bottom]
type = "inflow"
velocity = 1.5
[gas.boundary.top]
type = "pressure"
[output]
frame_interval = 0.004
series_interval = 0.001
checkpoint_interval = 0.004
)";

/// A liquid-fluidised bed with every fluid force beyond drag and pressure ([coupling.forces]:
/// virtual mass, Basset history, Saffman and Magnus lift, fluid torque): 600 glass spheres of
/// 2 mm in water (incompressible, 1000 kg/m^3, 1 mPa s) from below at 5 cm/s, periodic across.
const char* const kFluidForces = R"(
[simulation]
engine = "soft_sphere"
dimension = 3
end_time = 0.02
gravity = [0.0, 0.0, -9.81]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.04, 0.02, 0.12]
periodic = [true, true, false]
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
youngs_modulus = 1e7
restitution = 0.9
friction = 0.3
[[insert]]
species = "glass"
count = 600
placement = "random"
region = { lo = [0.0, 0.0, 0.0], hi = [0.04, 0.02, 0.04] }
seed = 9
[contact]
normal = "hertz"
tangential = "history"
[gas]
eos = "incompressible"
density = 1000.0
viscosity = 1.0e-3
cells = [4, 2, 12]
time_step = 1e-4
[gas.boundary.bottom]
type = "inflow"
velocity = 0.05
[gas.boundary.top]
type = "pressure"
[coupling.forces]
virtual_mass = true
basset = true
saffman = true
magnus = "rubinow_keller"
torque = "stokes"
[output]
frame_interval = 0.01
series_interval = 0.001
checkpoint_interval = 0.01
)";

/// `mpirun -n RANKS fluidem ARGS... -t 1` in cwd; stopped after timeout_s seconds when given
/// (exit code 124: the ranks did not end).
Result mpirun(int ranks, const std::vector<std::string>& args, const test::fs::path& cwd,
              int timeout_s = 0) {
  std::string cmd = (timeout_s > 0 ? "timeout " + std::to_string(timeout_s) + " " : "") +
                    "mpirun --oversubscribe --allow-run-as-root --mca btl self,vader -n " +
                    std::to_string(ranks) + " " + test::quote(FLUIDEM_BINARY);
  for (const auto& a : args) cmd += " " + test::quote(a);
  cmd += " -t 1"; // one thread per rank
  return test::run_command(cmd, cwd);
}

/// Every array of two checkpoints is the same, but the run's random id and what follows from
/// it, and the build count when `builds` is false.
void expect_same_checkpoints(const test::fs::path& a, const test::fs::path& b, bool builds = true) {
  const CheckpointReader ra(a.string()), rb(b.string());
  ASSERT_EQ(ra.names(), rb.names());
  int compared = 0;
  for (const std::string& name : ra.names()) {
    if (name == "outputs/run_id" || name == "case/resolved" ||
        (!builds && name == "rank_independent/builds"))
      continue;
    EXPECT_EQ(ra.stored_bytes(name), rb.stored_bytes(name)) << name;
    ++compared;
  }
  EXPECT_GT(compared, 20);
}

/// `bed` run on `first` ranks to `split` s into cwd/half (with `extra` arguments), then continued
/// from its checkpoint on `second` ranks to `end` s: the files in cwd/half are the whole run's.
void run_and_continue(const test::fs::path& cwd, const test::fs::path& bed, int first, int second,
                      const std::string& split, const std::string& end,
                      const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"run",  bed.string(), "--out",
                                "half", "--set",      "simulation.end_time=" + split};
  args.insert(args.end(), extra.begin(), extra.end());
  const Result half = mpirun(first, args, cwd);
  ASSERT_EQ(half.code, 0) << half.err;
  const Result cont = mpirun(second,
                             {"run", "--restart", (cwd / "half" / "checkpoint.h5").string(),
                              "--set", "simulation.end_time=" + end},
                             cwd);
  ASSERT_EQ(cont.code, 0) << cont.err;
}

TEST(MpiRun, RanksWriteTheFilesOfOneProcess) {
  TempDir tmp;
  const auto bed = tmp.write("bed.toml", kBed);
  const Result one = test::fluidem(
      {"run", bed.string(), "--out", "one", "-t", "2", "--set", "parallel.rank_independent=true"},
      tmp.path);
  ASSERT_EQ(one.code, 0) << one.err;
  EXPECT_TRUE(contains(one.out, "ranks              1")) << one.out;
  const std::string series = test::read_file(tmp.path / "one" / "series.csv");
  for (int p : {2, 3, 4}) {
    const std::string out = "p" + std::to_string(p);
    const Result r = mpirun(p, {"run", bed.string(), "--out", out}, tmp.path);
    ASSERT_EQ(r.code, 0) << r.err << r.out;
    EXPECT_TRUE(contains(r.out, "ranks              " + std::to_string(p))) << r.out;
    EXPECT_TRUE(contains(r.out, "imbalance")) << r.out;
    EXPECT_EQ(test::read_file(tmp.path / out / "series.csv"), series) << p << " ranks";
    expect_same_checkpoints(tmp.path / "one" / "checkpoint.h5", tmp.path / out / "checkpoint.h5");
  }
}

TEST(MpiRun, CoupledBedOnRanksWritesTheFilesOfOneProcess) {
  // Each rank deposits its own particles into its copy of the gas in fixed point, the ranks sum
  // the grids, and every rank steps the same gas (docs/parallel.md): series.csv (with the
  // pressure drop and bed height), the gas fields and the checkpoints are those of one process
  // with two threads, on 2 to 4 ranks cut into columns, slabs and 2 x 2 boxes, and a checkpoint
  // of 3 ranks continues on 2. A control with another insertion seed differs.
  TempDir tmp;
  const auto bed = tmp.write("coupled.toml", kCoupled);
  const Result one = test::fluidem(
      {"run", bed.string(), "--out", "one", "-t", "2", "--set", "parallel.rank_independent=true"},
      tmp.path);
  ASSERT_EQ(one.code, 0) << one.err;
  const std::string series = test::read_file(tmp.path / "one" / "series.csv");
  EXPECT_TRUE(contains(series, "pressure_drop")) << series;
  const std::vector<std::pair<int, std::string>> layouts = {
      {2, "auto"}, {2, "[1, 1, 2]"}, {3, "[3, 1, 1]"}, {4, "[2, 2, 1]"}};
  for (const auto& [p, grid] : layouts) {
    const std::string out = "p" + std::to_string(p) + (grid == "auto" ? "" : "g");
    const std::string value = grid == "auto" ? "\"auto\"" : grid;
    const Result r =
        mpirun(p, {"run", bed.string(), "--out", out, "--set", "parallel.process_grid=" + value},
               tmp.path);
    ASSERT_EQ(r.code, 0) << r.err << r.out;
    EXPECT_EQ(test::read_file(tmp.path / out / "series.csv"), series) << p << " ranks, " << grid;
    expect_same_checkpoints(tmp.path / "one" / "checkpoint.h5", tmp.path / out / "checkpoint.h5");
  }
  const Result other =
      mpirun(2, {"run", bed.string(), "--out", "seed", "--set", "insert[0].seed=5"}, tmp.path);
  ASSERT_EQ(other.code, 0) << other.err;
  EXPECT_NE(test::read_file(tmp.path / "seed" / "series.csv"), series);
  ASSERT_NO_FATAL_FAILURE(run_and_continue(tmp.path, bed, 3, 2, "0.004", "0.012"));
  EXPECT_EQ(test::read_file(tmp.path / "half" / "series.csv"), series);
  expect_same_checkpoints(tmp.path / "one" / "checkpoint.h5", tmp.path / "half" / "checkpoint.h5");
}

TEST(MpiRun, FluidForcesOnRanksWriteTheFilesOfOneProcess) {
  // [coupling.forces] on ranks (docs/parallel.md): each particle's fluid-force state (its Basset
  // history, the last flow step's impulse) travels with it, the fluid torque is held like the
  // force, and the reaction on the liquid is summed in fixed point. With the cut planes moved
  // at every list build (parallel.balance_interval = 1, so that particles change rank), 3 ranks
  // write the series.csv and checkpoint of one process, and a checkpoint of 2 ranks continues
  // on 3 as if uninterrupted. Controls: the forces change the run (the same case without them
  // differs), and they need their state to follow the particles (a sabotage that left it behind
  // at a migration broke this test while it was written).
  TempDir tmp;
  const auto bed = tmp.write("forces.toml", kFluidForces);
  const Result one = test::fluidem(
      {"run", bed.string(), "--out", "one", "-t", "2", "--set", "parallel.rank_independent=true"},
      tmp.path);
  ASSERT_EQ(one.code, 0) << one.err;
  const std::string series = test::read_file(tmp.path / "one" / "series.csv");
  const Result p3 =
      mpirun(3,
             {"run", bed.string(), "--out", "p3", "--set", "parallel.balance_interval=1", "--set",
              "parallel.process_grid=[3, 1, 1]"},
             tmp.path);
  ASSERT_EQ(p3.code, 0) << p3.err << p3.out;
  EXPECT_FALSE(contains(p3.out, " 0 moves of the cut planes")) << p3.out;
  EXPECT_EQ(test::read_file(tmp.path / "p3" / "series.csv"), series);
  expect_same_checkpoints(tmp.path / "one" / "checkpoint.h5", tmp.path / "p3" / "checkpoint.h5");
  ASSERT_NO_FATAL_FAILURE(run_and_continue(tmp.path, bed, 2, 3, "0.01", "0.02",
                                           {"--set", "parallel.balance_interval=1"}));
  EXPECT_EQ(test::read_file(tmp.path / "half" / "series.csv"), series);
  expect_same_checkpoints(tmp.path / "one" / "checkpoint.h5", tmp.path / "half" / "checkpoint.h5");
  const Result plain = test::fluidem(
      {"run", bed.string(), "--out", "plain", "-t", "2", "--set", "parallel.rank_independent=true",
       "--set", "coupling.forces.virtual_mass=false", "--set", "coupling.forces.basset=false",
       "--set", "coupling.forces.saffman=false", "--set", "coupling.forces.magnus=\"off\"", "--set",
       "coupling.forces.torque=\"off\""},
      tmp.path);
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_NE(test::read_file(tmp.path / "plain" / "series.csv"), series);
}

TEST(MpiRun, CheckpointOfFourRanksContinuesOnOneTwoAndThree) {
  TempDir tmp;
  const auto bed = tmp.write("bed.toml", kBed);
  const Result whole = mpirun(2, {"run", bed.string(), "--out", "whole"}, tmp.path);
  ASSERT_EQ(whole.code, 0) << whole.err;
  const Result half = mpirun(
      4, {"run", bed.string(), "--out", "half", "--set", "simulation.end_time=0.008"}, tmp.path);
  ASSERT_EQ(half.code, 0) << half.err;
  for (int q : {1, 2, 3}) {
    const std::string dir = "cont" + std::to_string(q);
    test::fs::copy(tmp.path / "half", tmp.path / dir, test::fs::copy_options::recursive);
    const std::vector<std::string> args{"run", "--restart",
                                        (tmp.path / dir / "checkpoint.h5").string(), "--set",
                                        "simulation.end_time=0.012"};
    const Result r = q == 1 ? test::fluidem(args, tmp.path) : mpirun(q, args, tmp.path);
    ASSERT_EQ(r.code, 0) << r.err << r.out;
    EXPECT_EQ(test::read_file(tmp.path / dir / "series.csv"),
              test::read_file(tmp.path / "whole" / "series.csv"))
        << "4 -> " << q << " ranks";
    expect_same_checkpoints(tmp.path / "whole" / "checkpoint.h5", tmp.path / dir / "checkpoint.h5");
  }
}

TEST(MpiRun, TwoSkinsGiveTheSameParticles) {
  // A skin of 0.1 d rebuilds the lists more often than one of 0.4 d: the rows hold other pairs
  // and are built at other steps, the contacts and their sums are the same.
  TempDir tmp;
  const auto bed = tmp.write("bed.toml", kBed);
  const Result thin =
      mpirun(3, {"run", bed.string(), "--out", "thin", "--set", "neighbour.skin=0.0002"}, tmp.path);
  const Result thick = mpirun(
      3, {"run", bed.string(), "--out", "thick", "--set", "neighbour.skin=0.0008"}, tmp.path);
  ASSERT_EQ(thin.code, 0) << thin.err;
  ASSERT_EQ(thick.code, 0) << thick.err;
  const CheckpointReader a((tmp.path / "thin" / "checkpoint.h5").string()),
      b((tmp.path / "thick" / "checkpoint.h5").string());
  EXPECT_GT(a.integer("rank_independent/builds"), b.integer("rank_independent/builds"));
  for (const char* name :
       {"particles/x", "particles/vz", "particles/wy", "rank_independent/contact",
        "rank_independent/dissipated", "rank_independent/history/values"})
    EXPECT_EQ(a.stored_bytes(name), b.stored_bytes(name)) << name;
}

TEST(MpiRun, DiscsInTheirPlaneOnRanks) {
  // 2-D: discs in the x-z plane of cases/hoomans96/pouring_soft.toml (the y axis is never cut),
  // 0.05 s of pouring on 1 (rank-independent) and 3 ranks: the same series.csv and checkpoint.
  TempDir tmp;
  const std::string pour =
      (test::fs::path(FLUIDEM_SOURCE_DIR) / "cases" / "hoomans96" / "pouring_soft.toml").string();
  const std::vector<std::string> set{"--set", "simulation.end_time=0.05", "--set",
                                     "output.frame_interval=0.025"};
  std::vector<std::string> one_args{"run", pour,    "--out",
                                    "one", "--set", "parallel.rank_independent=true"};
  one_args.insert(one_args.end(), set.begin(), set.end());
  const Result one = test::fluidem(one_args, tmp.path);
  ASSERT_EQ(one.code, 0) << one.err;
  std::vector<std::string> three_args{"run", pour, "--out", "three"};
  three_args.insert(three_args.end(), set.begin(), set.end());
  const Result three = mpirun(3, three_args, tmp.path);
  ASSERT_EQ(three.code, 0) << three.err;
  EXPECT_TRUE(contains(three.out, "process grid 3 x 1 x 1")) << three.out;
  EXPECT_EQ(test::read_file(tmp.path / "three" / "series.csv"),
            test::read_file(tmp.path / "one" / "series.csv"));
  expect_same_checkpoints(tmp.path / "one" / "checkpoint.h5", tmp.path / "three" / "checkpoint.h5");
}

TEST(MpiRun, RefusedResumeStopsEveryRank) {
  // Only the root opens the outputs: a continued run whose series.csv was cut short is refused
  // there (exit 2, once), and the other ranks stop with it instead of waiting (timeout 120 s).
  TempDir tmp;
  const auto bed = tmp.write("bed.toml", kBed);
  const Result first = mpirun(
      2, {"run", bed.string(), "--out", "r", "--set", "simulation.end_time=0.004"}, tmp.path);
  ASSERT_EQ(first.code, 0) << first.err;
  const auto series = tmp.path / "r" / "series.csv";
  const std::string text = test::read_file(series);
  std::ofstream(series, std::ios::trunc) << text.substr(0, text.size() / 2);
  const Result again = mpirun(2,
                              {"run", "--restart", (tmp.path / "r" / "checkpoint.h5").string(),
                               "--set", "simulation.end_time=0.008"},
                              tmp.path, 120);
  EXPECT_EQ(again.code, 2) << again.err;
  EXPECT_TRUE(contains(again.err, "series.csv")) << again.err;
  EXPECT_EQ(again.err.find("error:"), again.err.rfind("error:")) << again.err;
}

TEST(MpiRun, UnstableRunStopsEveryRankWithExit3) {
  // A time step 20 times the contacts' limit (forced): the first contacts overlap beyond
  // contact.max_overlap; the rank that holds the deepest says so, every rank stops with exit 3,
  // and the message is printed once.
  TempDir tmp;
  const auto bed = tmp.write("bed.toml", kBed);
  const Result r = mpirun(3,
                          {"run", bed.string(), "--out", "u", "--set", "simulation.time_step=2e-4",
                           "--set", "simulation.force_time_step=true"},
                          tmp.path);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "contact.max_overlap")) << r.err;
  EXPECT_EQ(r.err.find("error:"), r.err.rfind("error:")) << r.err;
}

/// `fluidem run CASE --out OUT` with the options `common`, then `extra`.
std::vector<std::string> run_args(const std::filesystem::path& bed, const std::string& out,
                                  const std::vector<std::string>& common,
                                  const std::vector<std::string>& extra) {
  std::vector<std::string> a = {"run", bed.string(), "--out", out};
  a.insert(a.end(), common.begin(), common.end());
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

/// The column `name` of a series.csv, per row.
std::vector<double> column(const std::string& csv, const std::string& name) {
  std::vector<double> out;
  std::size_t col = std::string::npos, pos = 0;
  while (pos < csv.size()) {
    const std::size_t end = csv.find('\n', pos);
    const std::string line = csv.substr(pos, end - pos);
    pos = end == std::string::npos ? csv.size() : end + 1;
    std::vector<std::string> cells;
    for (std::size_t a = 0, b; a <= line.size(); a = b + 1) {
      b = line.find(',', a);
      if (b == std::string::npos) b = line.size();
      cells.push_back(line.substr(a, b - a));
    }
    if (col == std::string::npos) {
      for (std::size_t k = 0; k < cells.size(); ++k)
        if (cells[k] == name) col = k;
      if (col == std::string::npos) return out;
      continue;
    }
    if (col < cells.size()) out.push_back(std::stod(cells[col]));
  }
  return out;
}

TEST(MpiRun, BodyForceOnRanks) {
  // The [Chang08] sinusoidal field drives 1500 spheres from rest without gravity (periodic box
  // of one wavelength along y; its half kicks at x^n and x^{n+1}, core/body_force.hpp): 3 ranks
  // write the series of the rank-independent engine on one process, bit for bit; that engine
  // agrees with the single-process engine (whose field is tested against the analytic one in
  // body_force_test) on the kinetic energy to 1e-9 relative (the two differ by round-off in the
  // contacts' summation order only); without the field the bed stays nearly at rest (control).
  TempDir tmp;
  const auto bed = tmp.write("field.toml", std::string(kBed) + R"(
[body_force]
type = "sinusoidal_cube"
amplitude = 3.0
wavelength = 0.02
)");
  const std::vector<std::string> still = {"--set", "simulation.gravity=[0.0, 0.0, 0.0]", "--set",
                                          "insert[0].velocity_spread=0.0"};
  auto args = [&](const std::string& out, const std::vector<std::string>& extra) {
    return run_args(bed, out, still, extra);
  };
  const Result one =
      test::fluidem(args("one", {"-t", "1", "--set", "parallel.rank_independent=true"}), tmp.path);
  ASSERT_EQ(one.code, 0) << one.err;
  const std::string series = test::read_file(tmp.path / "one" / "series.csv");
  const Result three = mpirun(3, args("three", {}), tmp.path);
  ASSERT_EQ(three.code, 0) << three.err;
  EXPECT_EQ(test::read_file(tmp.path / "three" / "series.csv"), series);
  const Result fast = test::fluidem(args("fast", {"-t", "1"}), tmp.path);
  ASSERT_EQ(fast.code, 0) << fast.err;
  const std::vector<double> ri = column(series, "e_kin"),
                            sp = column(test::read_file(tmp.path / "fast" / "series.csv"), "e_kin");
  ASSERT_EQ(ri.size(), sp.size());
  ASSERT_GE(ri.size(), 10u);
  for (std::size_t k = 1; k < ri.size(); ++k) EXPECT_NEAR(ri[k] / sp[k], 1.0, 1e-9) << "row " << k;
  const Result none =
      test::fluidem({"run", bed.string(), "--out", "none", "-t", "1", "--set",
                     "simulation.gravity=[0.0, 0.0, 0.0]", "--set", "insert[0].velocity_spread=0.0",
                     "--set", "body_force.amplitude=0.0"},
                    tmp.path);
  ASSERT_EQ(none.code, 0) << none.err;
  const std::vector<double> rest =
      column(test::read_file(tmp.path / "none" / "series.csv"), "e_kin");
  EXPECT_LT(rest.back(), 1e-3 * ri.back());
}

TEST(MpiRun, NonContactForcesOnRanks) {
  // The settling bed (600 spheres) with van der Waals attraction (between particles and to the
  // walls) and charges of 1e-10 C (Coulomb, cut off at 5 mm, a grounded floor;
  // noncontact/pair_forces.hpp): forces of the order of the weight. 2 and 3 ranks write the series
  // of the rank-independent engine on one process, bit for bit (e_pot holds the non-contact
  // potential, summed in id order), and a checkpoint of 3 ranks continues on 2 to the same series.
  // That engine sums the same pair terms as the single-process engine in another order (partner id,
  // not index): their energies agree to 1e-9 relative after 2400 steps (series.csv holds 10
  // digits; leaving out the wall terms alone shows at 8e-6). A control without the forces
  // differs.
  TempDir tmp;
  const auto bed = tmp.write("sticky.toml", std::string(kBed) + R"(
[van_der_waals]
hamaker = 1e-19
min_separation = 4e-10
range = 2e-4
wall_hamaker = 1e-19
[electrostatics]
cutoff = 0.005
conducting_walls = ["z_lo"]
)");
  // The van der Waals spring needs steps below 1.4e-6 s: 1.25e-6 s, 3 ms of bed in 2400 steps
  // (600 particles, to keep it short).
  const std::vector<std::string> charged = {
      "--set", "species[0].charge=1e-10",           "--set", "simulation.time_step=1.25e-6",
      "--set", "simulation.end_time=0.003",         "--set", "output.series_interval=0.0002",
      "--set", "output.checkpoint_interval=0.0015", "--set", "insert[0].count=600"};
  auto args = [&](const std::string& out, const std::vector<std::string>& extra) {
    return run_args(bed, out, charged, extra);
  };
  const Result one =
      test::fluidem(args("one", {"-t", "2", "--set", "parallel.rank_independent=true"}), tmp.path);
  ASSERT_EQ(one.code, 0) << one.err;
  const std::string series = test::read_file(tmp.path / "one" / "series.csv");
  for (int p : {2, 3}) {
    const std::string out = "p" + std::to_string(p);
    const Result r = mpirun(p, args(out, {}), tmp.path);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(test::read_file(tmp.path / out / "series.csv"), series) << p << " ranks";
  }
  const Result half = mpirun(3, args("half", {"--set", "simulation.end_time=0.0016"}), tmp.path);
  ASSERT_EQ(half.code, 0) << half.err;
  const Result cont = mpirun(2,
                             {"run", "--restart", (tmp.path / "half" / "checkpoint.h5").string(),
                              "--set", "simulation.end_time=0.003"},
                             tmp.path);
  ASSERT_EQ(cont.code, 0) << cont.err;
  EXPECT_EQ(test::read_file(tmp.path / "half" / "series.csv"), series);
  const Result fast = test::fluidem(args("fast", {"-t", "1"}), tmp.path);
  ASSERT_EQ(fast.code, 0) << fast.err;
  const std::string fast_series = test::read_file(tmp.path / "fast" / "series.csv");
  for (const char* name : {"e_kin", "e_pot", "e_total"}) {
    const std::vector<double> a = column(series, name), b = column(fast_series, name);
    ASSERT_EQ(a.size(), b.size()) << name;
    ASSERT_GE(a.size(), 10u) << name;
    for (std::size_t k = 1; k < a.size(); ++k)
      EXPECT_NEAR(a[k] / b[k], 1.0, 1e-9) << name << ", row " << k;
  }
  const Result plain =
      test::fluidem({"run", tmp.write("plain.toml", kBed).string(), "--out", "plain", "-t", "1",
                     "--set", "parallel.rank_independent=true"},
                    tmp.path);
  ASSERT_EQ(plain.code, 0) << plain.err;
  const std::vector<double> with = column(series, "e_pot"),
                            without =
                                column(test::read_file(tmp.path / "plain" / "series.csv"), "e_pot");
  EXPECT_GT(std::abs(with.back() - without.back()), 1e-3 * std::abs(without.back()));
}

TEST(MpiRun, SigUsr1StopsEveryRankWithACheckpoint) {
  // SIGUSR1 to mpirun (forwarded to every rank; SIGINT and SIGTERM make Open MPI kill the ranks
  // a second later, docs/parallel.md): the ranks stop after the same step, the root writes the
  // checkpoint and says so once, the run exits 138, and the checkpoint continues on 3 ranks.
  TempDir tmp;
  const auto bed = tmp.write("long.toml", kBed);
  // The signal goes once the run has begun (its series.csv exists, written after the stop
  // handlers are in place; a second more for the ranks' handlers): a fixed delay raced with the
  // set-up on a loaded machine, where SIGUSR1 then ended a rank before its handler was there.
  const std::string cmd =
      "( mpirun --oversubscribe --allow-run-as-root --mca btl self,vader -n 2 " +
      test::quote(FLUIDEM_BINARY) + " run " + test::quote(bed.string()) +
      " --out stopped --set simulation.end_time=5.0 -t 1 & pid=$!; i=0; "
      "while [ ! -s stopped/series.csv ] && [ $i -lt 600 ]; do sleep 0.2; i=$((i+1)); done; "
      "sleep 1; kill -USR1 $pid; wait $pid )";
  const Result r = test::run_command(cmd, tmp.path);
  ASSERT_EQ(r.code, 138) << r.err;
  const std::string said = "stopped by SIGUSR1 at t = ";
  ASSERT_TRUE(contains(r.err, said)) << r.err;
  EXPECT_EQ(r.err.find(said), r.err.rfind(said)) << r.err; // once, by the root
  const std::string stopping = "stopping after this step"; // the handler's notice: once too
  ASSERT_TRUE(contains(r.err, stopping)) << r.err;
  EXPECT_EQ(r.err.find(stopping), r.err.rfind(stopping)) << r.err;
  const double t = std::stod(r.err.substr(r.err.find(said) + said.size()));
  EXPECT_GT(t, 0.0);
  const CheckpointReader ck((tmp.path / "stopped" / "checkpoint.h5").string());
  EXPECT_TRUE(ck.has("rank_independent/contact"));
  const Result cont = mpirun(3,
                             {"run", "--restart", (tmp.path / "stopped" / "checkpoint.h5").string(),
                              "--set", "simulation.end_time=" + std::to_string(t + 0.001)},
                             tmp.path, 120);
  EXPECT_EQ(cont.code, 0) << cont.err;
}

TEST(MpiRun, CollisionStatisticsOnRanksWriteTheFilesOfOneProcess) {
  // The settling bed with output.collisions and a region across the cut planes of 2 and 3
  // ranks (the statistics are kept by the root from the ranks' contacts, each pair recorded in
  // its lower id's row): collisions.csv and collision_overlap.csv are one process's, bit for
  // bit, and so is a run continued from a 2-rank checkpoint on 3 ranks (the ongoing contacts
  // kept in it). The statistics count contacts: pair and wall collisions, particles in the
  // region.
  TempDir tmp;
  const auto bed = tmp.write("bed.toml", std::string(kBed) + R"(collisions = true
[[output.collision_region]]
name = "middle"
centre = [0.015, 0.01, 0.006]
radius = 0.006
)");
  const Result one = test::fluidem(
      {"run", bed.string(), "--out", "one", "--set", "parallel.rank_independent=true"}, tmp.path);
  ASSERT_EQ(one.code, 0) << one.err;
  const std::string rows = test::read_file(tmp.path / "one" / "collisions.csv");
  const std::string histogram = test::read_file(tmp.path / "one" / "collision_overlap.csv");
  const std::vector<double> pairs = column(rows, "pair_collisions");
  const std::vector<double> walls = column(rows, "wall_collisions");
  const std::vector<double> inside = column(rows, "middle_particles");
  ASSERT_FALSE(pairs.empty());
  EXPECT_GT(*std::max_element(pairs.begin(), pairs.end()), 0.0) << rows;
  EXPECT_GT(*std::max_element(walls.begin(), walls.end()), 0.0) << rows;
  EXPECT_GT(inside.back(), 0.0) << rows;
  for (int p : {2, 3}) {
    const std::string out = "p" + std::to_string(p);
    const Result r = mpirun(p, {"run", bed.string(), "--out", out}, tmp.path);
    ASSERT_EQ(r.code, 0) << r.err << r.out;
    EXPECT_EQ(test::read_file(tmp.path / out / "collisions.csv"), rows) << p << " ranks";
    EXPECT_EQ(test::read_file(tmp.path / out / "collision_overlap.csv"), histogram) << p;
  }
  ASSERT_NO_FATAL_FAILURE(run_and_continue(tmp.path, bed, 2, 3, "0.006", "0.012"));
  EXPECT_EQ(test::read_file(tmp.path / "half" / "collisions.csv"), rows);
  EXPECT_EQ(test::read_file(tmp.path / "half" / "collision_overlap.csv"), histogram);
}

TEST(MpiRun, WhatTheRanksDoNotTakeIsRefused) {
  TempDir tmp;
  const auto bed = tmp.write("bed.toml", kBed);
  const Result hard = mpirun(
      2, {"run", bed.string(), "--out", "h", "--set", "simulation.engine=hard_sphere"}, tmp.path);
  EXPECT_EQ(hard.code, 2);
  EXPECT_TRUE(contains(hard.err, "simulation.engine")) << hard.err;
  const Result off = mpirun(
      2, {"run", bed.string(), "--out", "o", "--set", "parallel.rank_independent=false"}, tmp.path);
  EXPECT_EQ(off.code, 2);
  EXPECT_TRUE(contains(off.err, "parallel.rank_independent")) << off.err;
  const Result grid = mpirun(
      2, {"run", bed.string(), "--out", "g", "--set", "parallel.process_grid=[3, 1, 1]"}, tmp.path);
  EXPECT_EQ(grid.code, 2);
  EXPECT_TRUE(contains(grid.err, "parallel.process_grid")) << grid.err;
  // The message is printed once (by the root), not once per rank.
  EXPECT_EQ(grid.err.find("error:"), grid.err.rfind("error:")) << grid.err;
}

TEST(MpiRun, LiquidBridgesOnRanks) {
  // The settling bed wet: liquid 0.1% of each sphere's volume, water's surface tension and
  // viscosity (noncontact/ordered_liquid_bridges.hpp). Bridges form at contact, rupture at
  // Lian's distance with the liquid shared by the bridge counts of both particles (a ghost's
  // from its owner), and travel with their particles keyed by partner id. 2, 3 and 4 ranks,
  // their cut planes moved at every list build, write the series.csv and checkpoint of the
  // rank-independent engine on one process, bit for bit, and a checkpoint of 3 ranks continues
  // on 2 to the same series. The single-process engine (each bridge evaluated from each side,
  // not from its lower id) agrees to 1e-9 relative (measured: the same 10 digits). Controls:
  // the checkpoint holds bridges, and the dry bed's series differs.
  TempDir tmp;
  std::string wet = kBed;
  wet.replace(wet.find("rolling_friction = 0.05"), 23, "liquid_fraction = 0.001");
  const auto bed = tmp.write("wet.toml", wet + R"(
[liquid_bridge]
surface_tension = 0.0728
viscosity = 1e-3
min_gap = 1e-5
)");
  const Result one = test::fluidem(
      {"run", bed.string(), "--out", "one", "-t", "2", "--set", "parallel.rank_independent=true"},
      tmp.path);
  ASSERT_EQ(one.code, 0) << one.err;
  const std::string series = test::read_file(tmp.path / "one" / "series.csv");
  {
    const CheckpointReader r((tmp.path / "one" / "checkpoint.h5").string());
    EXPECT_GT(r.int64s("rank_independent/bridges/key").size(), 300u);
  }
  for (int p : {2, 3, 4}) {
    const std::string out = "p" + std::to_string(p);
    const Result r = mpirun(
        p, {"run", bed.string(), "--out", out, "--set", "parallel.balance_interval=1"}, tmp.path);
    ASSERT_EQ(r.code, 0) << r.err << r.out;
    EXPECT_EQ(test::read_file(tmp.path / out / "series.csv"), series) << p << " ranks";
    expect_same_checkpoints(tmp.path / "one" / "checkpoint.h5", tmp.path / out / "checkpoint.h5");
  }
  ASSERT_NO_FATAL_FAILURE(run_and_continue(tmp.path, bed, 3, 2, "0.006", "0.012"));
  EXPECT_EQ(test::read_file(tmp.path / "half" / "series.csv"), series);
  const Result single = test::fluidem(
      {"run", bed.string(), "--out", "single", "--set", "parallel.rank_independent=false"},
      tmp.path);
  ASSERT_EQ(single.code, 0) << single.err;
  const std::string single_series = test::read_file(tmp.path / "single" / "series.csv");
  for (const char* name : {"e_kin", "e_pot", "e_dsp", "e_total"}) {
    const std::vector<double> a = column(series, name), b = column(single_series, name);
    ASSERT_EQ(a.size(), b.size()) << name;
    ASSERT_GE(a.size(), 10u) << name;
    for (std::size_t k = 1; k < a.size(); ++k)
      EXPECT_NEAR(a[k] / b[k], 1.0, 1e-9) << name << ", row " << k;
  }
  const Result dry = test::fluidem({"run", tmp.write("dry.toml", kBed).string(), "--out", "dry",
                                    "--set", "parallel.rank_independent=true"},
                                   tmp.path);
  ASSERT_EQ(dry.code, 0) << dry.err;
  EXPECT_NE(test::read_file(tmp.path / "dry" / "series.csv"), series);
}

TEST(MpiRun, ContinuumAveragesOnRanksWriteTheFilesOfOneProcess) {
  // The settling bed with output.continuum (volume averages on 3 x 1 x 4 cells, every 5th
  // step): 2 and 3 ranks write one process's continuum.h5, bit for bit (its datasets), and so
  // does a run continued from a 2-rank checkpoint on 3 ranks; the stresses are not all zero.
  TempDir tmp;
  const auto bed = tmp.write("bed.toml", std::string(kBed) + R"(
[output.continuum]
cells = [3, 1, 4]
stride = 5
interval = 0.003
)");
  const Result one = test::fluidem(
      {"run", bed.string(), "--out", "one", "--set", "parallel.rank_independent=true"}, tmp.path);
  ASSERT_EQ(one.code, 0) << one.err;
  const auto one_h5 = tmp.path / "one" / "continuum.h5";
  ASSERT_TRUE(test::fs::exists(one_h5)) << one.out;
  // Every dataset of /fields, each number printed with 17 digits (h5dump; the first line, the
  // file's name, dropped).
  const auto fields_of = [&](const test::fs::path& h5) {
    const Result d =
        test::run_command("h5dump -m %.17g -g /fields " + test::quote(h5.string()), tmp.path);
    EXPECT_EQ(d.code, 0) << d.err;
    return d.out.substr(d.out.find('\n') + 1);
  };
  const std::string fields = fields_of(one_h5);
  // The contact stress is there and not all zero (the settling bed has contacts).
  const std::size_t zz = fields.find("DATASET \"contact_stress_zz\"");
  ASSERT_NE(zz, std::string::npos) << fields.substr(0, 400);
  bool nonzero = false;
  for (std::size_t at = fields.find("): ", zz); at < fields.find("DATASET", zz + 7);
       at = fields.find("): ", at + 3))
    nonzero = nonzero || std::stod(fields.substr(at + 3, 30)) != 0.0;
  EXPECT_TRUE(nonzero);
  const auto same_datasets = [&](const test::fs::path& other, const std::string& what) {
    EXPECT_TRUE(fields_of(other) == fields) << what;
  };
  for (int p : {2, 3}) {
    const std::string out = "p" + std::to_string(p);
    const Result r = mpirun(p, {"run", bed.string(), "--out", out}, tmp.path);
    ASSERT_EQ(r.code, 0) << r.err << r.out;
    same_datasets(tmp.path / out / "continuum.h5", std::to_string(p) + " ranks");
  }
  ASSERT_NO_FATAL_FAILURE(run_and_continue(tmp.path, bed, 2, 3, "0.006", "0.012"));
  same_datasets(tmp.path / "half" / "continuum.h5", "2 -> 3 ranks");
}

} // namespace
} // namespace fluidem
