// Restart identity (issue "Runs that never lose data"): a run to 2T that writes a checkpoint at
// T, and a run to T followed by `restart` from its checkpoint and a run on to 2T, must end in
// bitwise-identical particle arrays (positions, velocities, angular velocities, forces,
// torques) and gas fields (velocity, pressure, porosity), and the continued run's output files
// must equal the uninterrupted run's: series.csv and probes.csv byte for byte, the particle and
// field frames (times and positions) of particles.h5 the same frames with the same values, the
// XDMF indexes byte for byte (no duplicated, no missing frame). The runs keep 4 initial layers
// (output.layers): the layer array and particles.h5's layer frames must be identical too, and
// they record collision statistics (output.collisions, one region): collisions.csv and
// collision_overlap.csv must be identical byte for byte.
// The soft-sphere runs also average continuum fields ([output.continuum], weighted for the 2-D
// pouring, volume for the coupled column) over intervals of 0.3 T, so that the checkpoint at T
// cuts an interval: continuum.xmf byte for byte and continuum.h5's times and fields the same
// (the interval's sums are in the checkpoint).
// Engines: soft spheres (Hoomans pouring, 500 discs, with tangential-spring history in the
// contacts; once more without the continuum averages, so that most steps are folded: the
// integrator's pass inside the contact loop, Simulation::step), hard spheres (the same with the
// event-driven engine), and both coupled to the gas (the Tsuji column of tests/common, 200
// particles), the pouring runs of both engines with a row of fixed particles, and the soft-sphere
// pouring with the non-contact forces (van der Waals, charges, images, liquid bridges). The time
// step is fixed explicitly (an automatic step depends on end_time). T is short (a few hundred
// steps): identity must hold from any state. Also: a checkpoint truncated or with a flipped byte is
// rejected with a message naming the file (CheckpointError), and the previous checkpoint
// (checkpoint.prev.h5) still loads.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <hdf5.h>
#include <unistd.h>

#include "../../common/fold_threshold.hpp"
#include "../../common/tsuji_column.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"
#include "output/checkpoint_file.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<double> read_h5_doubles(const fs::path& file, const char* dataset) {
  std::vector<double> v;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return v;
  const hid_t d = H5Dopen2(f, dataset, H5P_DEFAULT);
  if (d >= 0) {
    const hid_t s = H5Dget_space(d);
    v.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(s)));
    if (!v.empty()) H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Sclose(s);
    H5Dclose(d);
  }
  H5Fclose(f);
  return v;
}

void expect_same_arrays(const Simulation& a, const Simulation& b) {
  const ParticleStore& p = a.particles();
  const ParticleStore& q = b.particles();
  ASSERT_EQ(p.size(), q.size());
  const std::pair<const char*, std::pair<const std::vector<double>*, const std::vector<double>*>>
      arrays[] = {{"x", {&p.x, &q.x}},
                  {"y", {&p.y, &q.y}},
                  {"z", {&p.z, &q.z}},
                  {"vx", {&p.vx, &q.vx}},
                  {"vy", {&p.vy, &q.vy}},
                  {"vz", {&p.vz, &q.vz}},
                  {"wx", {&p.wx, &q.wx}},
                  {"wy", {&p.wy, &q.wy}},
                  {"wz", {&p.wz, &q.wz}},
                  {"contact forces and torques", {&a.contact_sums(), &b.contact_sums()}}};
  for (const auto& [name, v] : arrays) {
    std::size_t differ = 0;
    for (std::size_t i = 0; i < v.first->size(); ++i)
      if ((*v.first)[i] != (*v.second)[i]) ++differ; // bitwise (no NaN expected)
    EXPECT_EQ(differ, 0u) << "particle array " << name << ": " << differ << " entries differ";
  }
  // The initial layers (output.layers = 4 in these runs): kept exactly, and not all alike.
  EXPECT_TRUE(p.layer == q.layer) << "particle array layer differs";
  EXPECT_NE(std::count(p.layer.begin(), p.layer.end(), 3), 0) << "no particle in layer 3";
  ASSERT_EQ(a.gas() != nullptr, b.gas() != nullptr);
  if (a.gas()) {
    const gas::GasSolver& g = a.gas()->solver();
    const gas::GasSolver& h = b.gas()->solver();
    EXPECT_TRUE(g.pressure() == h.pressure()) << "gas pressure differs";
    EXPECT_TRUE(g.porosity() == h.porosity()) << "gas porosity differs";
    for (int d = 0; d < 3; ++d)
      EXPECT_TRUE(g.velocity(d) == h.velocity(d)) << "gas velocity component " << d << " differs";
  }
}

void expect_same_outputs(const fs::path& a, const fs::path& b, bool gas, bool continuum) {
  std::vector<std::string> texts{"series.csv", "particles.xmf", "collisions.csv",
                                 "collision_overlap.csv"};
  if (continuum) {
    texts.push_back("continuum.xmf");
    for (const char* ds :
         {"fields/time", "fields/solid_fraction", "fields/velocity", "fields/contact_stress_zz",
          "fields/couple_stress_yx", "fields/kinetic_stress_xz"}) {
      const auto va = read_h5_doubles(a / "continuum.h5", ds);
      const auto vb = read_h5_doubles(b / "continuum.h5", ds);
      EXPECT_GE(va.size(), 6u) << ds;
      EXPECT_TRUE(va == vb) << "continuum.h5 " << ds << ": " << va.size() << " vs " << vb.size()
                            << " values, or values differ";
    }
  }
  if (gas) {
    texts.push_back("fields.xmf");
  }
  for (const std::string& f : texts) {
    const std::string ta = slurp(a / f), tb = slurp(b / f);
    EXPECT_FALSE(ta.empty()) << f;
    EXPECT_TRUE(ta == tb) << f << " differs between the uninterrupted and the restarted run";
  }
  for (const char* ds : {"particles/all/position/time", "particles/all/position/value",
                         "particles/all/velocity/value", "particles/all/layer/value"}) {
    const auto va = read_h5_doubles(a / "particles.h5", ds);
    const auto vb = read_h5_doubles(b / "particles.h5", ds);
    EXPECT_FALSE(va.empty()) << ds;
    EXPECT_TRUE(va == vb) << "particles.h5 " << ds << ": " << va.size() << " vs " << vb.size()
                          << " values, or values differ";
  }
  if (gas) {
    const auto ta = read_h5_doubles(a / "fields.h5", "fields/time");
    const auto tb = read_h5_doubles(b / "fields.h5", "fields/time");
    EXPECT_FALSE(ta.empty());
    EXPECT_TRUE(ta == tb) << "fields.h5 frame times differ";
  }
}

/// Runs `spec` to 2T in one go (checkpoint every T) and as T + restart + T; compares.
void check_restart_identity(CaseSpec spec, double T, const std::string& name,
                            bool with_continuum = true) {
  const fs::path root =
      fs::temp_directory_path() / ("fluidem_restart_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(root);
  const fs::path one = root / "one", two = root / "two";
  spec.simulation.end_time = 2.0 * T;
  spec.output.checkpoint_interval = T;
  spec.output.frame_interval = T / 4.0;
  spec.output.series_interval = T / 20.0;
  spec.output.layers = 4;
  // Collision statistics with one region around the centre: the tracker's ongoing contacts and
  // accumulators are in the checkpoint, so collisions.csv and collision_overlap.csv continue
  // byte for byte.
  spec.output.collisions = true;
  CollisionRegionSpec region{"centre", {}, 0.0};
  for (std::size_t d = 0; d < 3; ++d)
    region.centre[d] = 0.5 * (spec.domain.lo[d] + spec.domain.hi[d]);
  region.radius = 0.25 * (spec.domain.hi[0] - spec.domain.lo[0]);
  spec.output.collision_regions = {region};
  const bool continuum = spec.simulation.engine == Engine::SoftSphere && with_continuum;
  if (continuum) {
    ContinuumOutputSpec c;
    c.cells = {4, spec.simulation.dimension == 2 ? 1 : 2, 5};
    c.interval = 0.3 * T;
    if (spec.simulation.dimension == 2) {
      c.method = ContinuumMethod::Weighted;
      c.width = 0.5 * spec.species[0].diameter * 2.0;
    }
    spec.output.continuum = c;
  }
  Simulation a(spec);
  a.run(one.string());

  spec.simulation.end_time = T;
  Simulation b(spec);
  b.run(two.string());
  ASSERT_TRUE(fs::exists(two / "checkpoint.h5"));
  auto c = Simulation::restart((two / "checkpoint.h5").string(),
                               {fmt::format("simulation.end_time={:.17g}", 2.0 * T)});
  EXPECT_EQ(c->step_count(), b.step_count());
  RunOptions resume;
  resume.resume = true;
  c->run(two.string(), {}, resume);
  EXPECT_EQ(a.step_count(), c->step_count());
  expect_same_arrays(a, *c);
  expect_same_outputs(one, two, spec.gas.has_value(), continuum);
  // Without the continuum averages (which take every step's full-step velocities) the granular
  // soft-sphere runs fold most steps (Simulation::step): the restarted run too.
  if (spec.simulation.engine == Engine::SoftSphere && !continuum && !spec.gas) {
    EXPECT_GT(a.folded_steps(), a.step_count() / 2);
    EXPECT_GT(c->folded_steps(), (c->step_count() - b.step_count()) / 2);
  }
  fs::remove_all(root);
}

CaseSpec pouring(Engine engine) {
  CaseSpec spec =
      read_case_file(std::string(FLUIDEM_SOURCE_DIR) + "/cases/hoomans96/" +
                     (engine == Engine::HardSphere ? "pouring_hard.toml" : "pouring_soft.toml"));
  // The auto step of the 1 s case, fixed (an automatic step depends on end_time).
  Simulation probe(spec);
  spec.simulation.time_step = probe.time_step();
  return spec;
}

// The runs of both engines sort the particles in space at every rebuild of the neighbour list
// (neighbour.sort_interval = 1): the order in memory is part of the state a restart continues.
TEST(Restart, SoftSpheresContinueBitwise) {
  CaseSpec spec = pouring(Engine::SoftSphere);
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.1, "soft");
}

// The same without continuum averages: most steps run the integrator's pass inside the contact
// loop (the folded step), whose choice restarts must reproduce.
TEST(Restart, SoftSpheresWithFoldedStepsContinueBitwise) {
  const test::FoldThreshold fold_always(0.0); // the pouring bed is sparse
  CaseSpec spec = pouring(Engine::SoftSphere);
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.1, "soft_folded", false);
}

// The contact models with history of their own (issue 34): Walton & Braun's normal spring
// (delta_max per contact) and the Mindlin-Deresiewicz tangential force (its displacement); the
// pouring case's stiffness is Walton & Braun's loading stiffness k1.
TEST(Restart, SoftSpheresWithWaltonBraunAndMindlinDeresiewiczContinueBitwise) {
  CaseSpec spec =
      read_case_file(std::string(FLUIDEM_SOURCE_DIR) + "/cases/hoomans96/pouring_soft.toml");
  spec.contact.normal.name = "walton_braun";
  spec.contact.tangential.name = "mindlin_deresiewicz";
  Simulation probe(spec);
  spec.simulation.time_step = probe.time_step();
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.1, "soft_wb_md");
}

// The JKR adhesive normal model (issue 34): its history ("attached") and contacts held in
// tension, through the list's reach.
TEST(Restart, SoftSpheresWithJkrContinueBitwise) {
  CaseSpec spec =
      read_case_file(std::string(FLUIDEM_SOURCE_DIR) + "/cases/hoomans96/pouring_soft.toml");
  spec.contact.normal.name = "jkr";
  spec.contact.normal.coefficients = {{"adhesion_energy", 0.2}};
  Simulation probe(spec);
  spec.simulation.time_step = probe.time_step();
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.1, "soft_jkr");
}

TEST(Restart, HardSpheresContinueBitwise) {
  CaseSpec spec = pouring(Engine::HardSphere);
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.1, "hard");
}

/// The pouring case with a row of fixed discs across the box at a quarter of its height (an
/// obstacle the falling discs pile on; inserted first, so the random discs avoid it): fixed
/// particles are inv_mass = inv_inertia = 0 in the particle arrays, which the checkpoint holds.
CaseSpec with_fixed_row(CaseSpec spec) {
  InsertSpec row;
  row.species = spec.species[0].name;
  row.placement = Placement::Lattice;
  row.fixed = true;
  const double d = spec.species[0].diameter;
  row.region_lo = spec.domain.lo;
  row.region_hi = spec.domain.hi;
  row.region_lo[2] = 0.25 * (spec.domain.hi[2] - spec.domain.lo[2]);
  row.region_hi[2] = row.region_lo[2] + d;
  row.count = static_cast<long>((spec.domain.hi[0] - spec.domain.lo[0]) / d * (1.0 + 1e-9));
  spec.inserts.insert(spec.inserts.begin(), row);
  return spec;
}

TEST(Restart, FixedParticlesContinueBitwise) {
  CaseSpec soft = with_fixed_row(pouring(Engine::SoftSphere));
  soft.neighbour.sort_interval = 1;
  check_restart_identity(soft, 0.1, "fixed_soft");
  CaseSpec hard = with_fixed_row(pouring(Engine::HardSphere));
  hard.neighbour.sort_interval = 1;
  check_restart_identity(hard, 0.1, "fixed_hard");
}

TEST(Restart, CoupledSoftSpheresContinueBitwise) {
  test::TsujiColumn c;
  c.engine = Engine::SoftSphere;
  c.count = 200;
  CaseSpec spec = test::tsuji_column(c);
  spec.simulation.time_step = 2.5e-5;
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.02, "coupled_soft");
}

// Coarse-grained parcels (W = 8 real particles of 2 mm: the column's 4 mm parcels): the
// checkpoint holds the case as given (the real particles), which the restart scales again.
TEST(Restart, CoupledCoarseGrainedContinueBitwise) {
  test::TsujiColumn c;
  c.engine = Engine::SoftSphere;
  c.count = 200;
  CaseSpec spec = test::tsuji_column(c);
  spec.species[0].diameter = 0.002;
  spec.coarse_graining.ratio = 8.0;
  spec.simulation.time_step = 2.5e-5;
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.02, "coupled_coarse_grained");
}

TEST(Restart, CoupledHardSpheresContinueBitwise) {
  test::TsujiColumn c;
  c.engine = Engine::HardSphere;
  c.count = 200;
  CaseSpec spec = test::tsuji_column(c);
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.02, "coupled_hard");
}

// A polydisperse closure without a given mean diameter takes the Sauter mean of the particles
// at set-up (beetstra_poly, docs/drag.md). Summed in the store's order, a restart from a store
// sorted in space got another last bit, and the run drifted from the one-piece run (8e-13 m
// after 0.02 s of cases/deen07/segregation_quick.toml); summed in id order it is the same.
TEST(Restart, CoupledBidisperseHardSpheresContinueBitwise) {
  test::TsujiColumn c;
  c.engine = Engine::HardSphere;
  c.count = 150;
  c.depth = 0.008; // two large diameters: room for the small ones beside the large
  CaseSpec spec = test::tsuji_column(c);
  SpeciesSpec small = spec.species[0];
  small.name = "small";
  small.diameter = 0.0025;
  spec.species.push_back(small);
  InsertSpec ins = spec.inserts[0];
  ins.species = small.name;
  ins.seed = 2;
  spec.inserts.push_back(ins);
  spec.coupling.drag = "beetstra_poly";
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.02, "coupled_bidisperse");
}

// The coupled columns in a liquid with every fluid force of [coupling.forces] on: the Basset
// history of each particle, the last step's velocities and fluid impulses (the gas's reaction)
// and the held torque are in the checkpoint.
CaseSpec with_fluid_forces(CaseSpec spec) {
  spec.gas->eos = gas::EquationOfState::incompressible;
  spec.gas->density = 1000.0;
  spec.gas->viscosity = 1e-3;
  spec.gas->boundary[gas::bottom].inflow = {gas::InflowMode::constant, 0.02};
  coupling::FluidForceSettings& f = spec.coupling.forces;
  f.virtual_mass = true;
  f.basset = true;
  f.basset_window = 4;
  f.saffman = true;
  f.magnus = "oesterle_bui_dinh";
  f.torque = "dennis";
  return spec;
}

TEST(Restart, CoupledSoftSpheresWithFluidForcesContinueBitwise) {
  test::TsujiColumn c;
  c.engine = Engine::SoftSphere;
  c.count = 200;
  CaseSpec spec = with_fluid_forces(test::tsuji_column(c));
  spec.simulation.time_step = 2.5e-5;
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.02, "fluid_soft");
}

TEST(Restart, CoupledHardSpheresWithFluidForcesContinueBitwise) {
  test::TsujiColumn c;
  c.engine = Engine::HardSphere;
  c.count = 200;
  CaseSpec spec = with_fluid_forces(test::tsuji_column(c));
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.02, "fluid_hard");
}

// coupling.smoothing_length: stateless (recomputed every flow step from the porosity and the
// source), so a restarted run must repeat the original bitwise with it too.
TEST(Restart, CoupledSmoothedContinueBitwise) {
  test::TsujiColumn c;
  c.engine = Engine::HardSphere;
  c.count = 200;
  CaseSpec spec = test::tsuji_column(c);
  spec.coupling.smoothing_length = 0.01;
  check_restart_identity(spec, 0.02, "coupled_smoothed");
}

// The soft-sphere pouring with the non-contact forces: van der Waals (particles and walls),
// charged discs (Coulomb, image charges in the conducting floor) and wet discs (liquid bridges,
// whose list with its bridges is in the checkpoint). The conservative forces are evaluated every
// step on a list of their own, which the restarted run rebuilds at other moments: their sums
// must not depend on it.
TEST(Restart, NonContactForcesContinueBitwise) {
  CaseSpec spec = pouring(Engine::SoftSphere); // its contacts' step, kept (forced below)
  const double d = spec.species[0].diameter;
  spec.noncontact.van_der_waals = VanDerWaalsSpec{1e-19, 4e-10, 0.1 * d, 1e-19};
  ElectrostaticsSpec e;
  e.cutoff = 3.0 * d;
  e.conducting[static_cast<std::size_t>(Face::ZLo)] = true;
  spec.noncontact.electrostatics = e;
  spec.inserts[0].charge = 2e-11;
  spec.species[0].liquid_fraction = 1e-3;
  LiquidBridgeSpec bridge;
  bridge.surface_tension = 0.0728;
  bridge.viscosity = 1e-3;
  bridge.min_gap = 1e-6;
  spec.noncontact.liquid_bridge = bridge;
  spec.simulation.force_time_step = true; // van der Waals at h0 would ask for a shorter one
  spec.neighbour.sort_interval = 1;
  check_restart_identity(spec, 0.04, "noncontact");
}

TEST(Restart, DamagedCheckpointIsRejectedAndThePreviousOneLoads) {
  CaseSpec spec = pouring(Engine::SoftSphere);
  const fs::path out = fs::temp_directory_path() / "fluidem_restart_damaged";
  fs::remove_all(out);
  spec.simulation.end_time = 0.02;
  spec.output.checkpoint_interval = 0.01; // two checkpoints: current and previous
  Simulation a(spec);
  a.run(out.string());
  const fs::path cur = out / "checkpoint.h5", prev = out / "checkpoint.prev.h5";
  ASSERT_TRUE(fs::exists(prev));
  const std::string good = slurp(cur);
  // Truncated to half.
  {
    std::ofstream f(cur, std::ios::binary | std::ios::trunc);
    f.write(good.data(), static_cast<std::streamsize>(good.size() / 2));
  }
  try {
    Simulation::restart(cur.string());
    ADD_FAILURE() << "a truncated checkpoint was accepted";
  } catch (const CheckpointError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(cur.string()), std::string::npos) << m;
    EXPECT_NE(m.find("checkpoint.prev.h5"), std::string::npos) << m;
  }
  // One byte flipped in the middle of the particle data (the file still opens).
  std::string bad = good;
  const std::size_t at = bad.size() / 2;
  bad[at] = static_cast<char>(bad[at] ^ 0x5a);
  {
    std::ofstream f(cur, std::ios::binary | std::ios::trunc);
    f.write(bad.data(), static_cast<std::streamsize>(bad.size()));
  }
  EXPECT_THROW(Simulation::restart(cur.string()), CheckpointError);
  // The previous checkpoint loads, at the earlier time.
  auto p = Simulation::restart(prev.string());
  EXPECT_NEAR(p->time(), 0.01, 0.5 * p->time_step());
  fs::remove_all(out);
}

} // namespace
} // namespace fluidem
