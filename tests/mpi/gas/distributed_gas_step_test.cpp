// The gas step shared by MPI ranks by z planes (gas::GasSolver::share, gas/plane_slabs.hpp,
// docs/parallel.md "The gas on several ranks"). Run by ctest under mpirun with 1, 2, 3 and 4
// ranks. Flow steps of a gas with a porosity field, drag and sources that change at every step
// (a stand-in for the particles), on
//  - a walled 3-D box with a bottom distributor, a central jet and a pressure top (ideal gas),
//  - a box periodic along x and z driven by a source, walls in y (ideal gas: z's images cross
//    from the last rank to the first),
//  - a 2-D bed (x-z plane) with inflow and an outflow top (incompressible, Model B),
//  - a box of 3 z planes, so that at 4 ranks one rank has no plane (more ranks than planes),
// give on P ranks the velocities, pressure, density and the step's diagnostics of the same
// solver shared by one process alone, bit for bit, on every rank (each rank steps only its own
// planes: checked). The reference for the physics is the
// single-process solver (hypre's PCG, floating-point sums): the shared one agrees with it to
// 1e-7 of the largest velocity and pressure difference (the linear and outer tolerances).
// A control: another source gives other fields.
#define OMPI_SKIP_MPICXX 1
#include "../../common/mpi_bits.hpp"
#include "gas/gas_solver.hpp"
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <mpi.h>

using namespace fluidem;
using namespace fluidem::gas;
using fluidem::test::bits_hash;
using fluidem::test::same_on_every_rank;
using fluidem::test::world_rank;
using fluidem::test::world_size;

namespace {

GasSettings walled_jet() {
  GasSettings s;
  s.cells = {6, 4, 10};
  s.hi = {0.06, 0.04, 0.1};
  s.boundary[bottom].type = BoundaryType::inflow;
  s.boundary[bottom].inflow = {InflowMode::constant, 0.3};
  s.boundary[bottom].regions.push_back(
      {BoundaryType::inflow, {0.02, 0.0}, {0.04, 1.0}, {InflowMode::constant, 2.0}, 0.4, 0.0});
  s.boundary[top].type = BoundaryType::pressure;
  return s;
}

GasSettings periodic_xz() {
  GasSettings s;
  s.cells = {5, 3, 8};
  s.hi = {0.05, 0.03, 0.08};
  for (const Side side : {left, right, bottom, top}) s.boundary[side].type = BoundaryType::periodic;
  s.gravity = {0.0, 0.0, 0.0};
  s.initial_velocity = {0.1, 0.0, 0.2};
  return s;
}

GasSettings bed_2d() {
  GasSettings s;
  s.dimension = 2;
  s.cells = {8, 1, 12};
  s.hi = {0.08, 0.0, 0.12};
  s.eos = EquationOfState::incompressible;
  s.model = PressureModel::B;
  s.boundary[bottom].type = BoundaryType::inflow;
  s.boundary[bottom].inflow = {InflowMode::constant, 0.5};
  s.boundary[top].type = BoundaryType::pressure;
  return s;
}

GasSettings three_planes() {
  GasSettings s = walled_jet();
  s.cells = {6, 4, 3};
  s.hi = {0.06, 0.04, 0.03};
  return s;
}

// Porosity, drag and sources of step `n`: smooth fields that move with n (a dense region
// drifting up), the same on every rank.
void set_particles(GasSolver& gs, int n, double source_scale) {
  const GasGrid& g = gs.grid();
  std::vector<double>& eps = gs.porosity();
  for (int k = 0; k < g.padded[2]; ++k)
    for (int j = 0; j < g.padded[1]; ++j)
      for (int i = 0; i < g.padded[0]; ++i) {
        const double z = (k - 0.5) / g.n[2], x = (i - 0.5) / g.n[0];
        const double dense =
            std::exp(-30.0 * ((z - 0.3 - 0.02 * n) * (z - 0.3 - 0.02 * n) + (x - 0.5) * (x - 0.5)));
        eps[static_cast<std::size_t>(g.idx(i, j, k))] = 1.0 - 0.5 * dense;
      }
  for (int d = 0; d < 3; ++d) {
    std::vector<double>& K = gs.drag_coefficient(d);
    std::vector<double>& Kus = gs.drag_velocity_term(d);
    std::vector<double>& f = gs.explicit_source(d);
    for (std::size_t q = 0; q < K.size(); ++q) {
      const double w = 1.0 - eps[q];
      K[q] = 2000.0 * w;
      Kus[q] = K[q] * 0.05 * (d == 2 ? -1.0 : 0.5) * std::sin(0.01 * static_cast<double>(q) + n);
      f[q] = source_scale * (d == 0 ? 1.0 : d == 2 ? 2.0 : 0.0) * (1.0 + 0.1 * w);
    }
  }
}

struct Fields {
  std::vector<double> u0, u1, u2, p, rho;
  int iterations = 0;
  double residual = 0.0, outflow = 0.0;
};

Fields run(const GasSettings& s, const SharedSolve* ranks, double source_scale,
           bool* distributed = nullptr) {
  GasSolver gs(s);
  LinearSolverOptions lin;
  lin.pressure.direct_max_work = 0.0; // hypre (shared: by parts), as on the large grids
  gs.set_linear_solver_options(lin);
  if (ranks) gs.share(*ranks);
  if (distributed) *distributed = gs.distributed();
  const double dt = 2e-4;
  set_particles(gs, 0, source_scale);
  gs.sync_old_porosity();
  int iterations = 0;
  for (int n = 0; n < 6; ++n) {
    set_particles(gs, n, source_scale);
    gs.step(n * dt, dt);
    iterations += gs.last_iterations();
  }
  return {gs.velocity(0), gs.velocity(1), gs.velocity(2),          gs.pressure(),
          gs.density(),   iterations,     gs.last_mass_residual(), gs.boundary_outflow()};
}

std::uint64_t hash(const Fields& f) {
  std::vector<double> all;
  for (const auto* a : {&f.u0, &f.u1, &f.u2, &f.p, &f.rho})
    all.insert(all.end(), a->begin(), a->end());
  all.push_back(f.iterations);
  all.push_back(f.residual);
  all.push_back(f.outflow);
  return bits_hash(all);
}

double max_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

double max_abs(const std::vector<double>& a) {
  double m = 0.0;
  for (const double v : a) m = std::max(m, std::abs(v));
  return m;
}

void check(const GasSettings& s, bool expect_distributed) {
  ensure_mpi_initialised();
  const int comm = MPI_Comm_c2f(MPI_COMM_WORLD);
  const SharedSolve world{comm, world_rank(), world_size()};
  const SharedSolve alone{kThisProcessAlone, 0, 1};
  bool distributed = false;
  const Fields on_ranks = run(s, &world, 1.0, &distributed);
  EXPECT_EQ(distributed, expect_distributed);
  const Fields one = run(s, &alone, 1.0);
  EXPECT_EQ(hash(on_ranks), hash(one)) << "rank " << world_rank();
  EXPECT_TRUE(same_on_every_rank(hash(on_ranks)));
  // The physics: the single-process solver (hypre's PCG, floating-point sums).
  const Fields plain = run(s, nullptr, 1.0);
  const double du = std::max(
      {max_diff(one.u0, plain.u0), max_diff(one.u1, plain.u1), max_diff(one.u2, plain.u2)});
  const double umax = std::max({max_abs(plain.u0), max_abs(plain.u1), max_abs(plain.u2)});
  EXPECT_LE(du, 1e-7 * umax);
  std::vector<double> dp(plain.p.size());
  for (std::size_t q = 0; q < dp.size(); ++q) dp[q] = plain.p[q] - plain.p[0];
  EXPECT_LE(max_diff(one.p, plain.p), 1e-7 * std::max(max_abs(dp), 1.0));
  // Control: another source, other fields.
  const Fields other = run(s, &world, 1.5);
  EXPECT_NE(hash(other), hash(on_ranks));
}

} // namespace

TEST(DistributedGasStep, WalledBedWithJetIsTheSameOnAnyRanks) {
  check(walled_jet(), true);
}

TEST(DistributedGasStep, PeriodicAlongZIsTheSameOnAnyRanks) {
  check(periodic_xz(), true);
}

TEST(DistributedGasStep, IncompressibleTwoDimensionalBedIsTheSameOnAnyRanks) {
  check(bed_2d(), true);
}

TEST(DistributedGasStep, MoreRanksThanPlanesLeaveOneRankWithoutPlanesAndTheSameBits) {
  check(three_planes(), true);
}
