// Google Benchmark: one gas flow step (GasSolver::step, SIMPLEC iterations with the momentum
// and pressure-correction solves) on a fluidised-bed-like field.
//  - Bed2D: the Tsuji bed grid, 2-D 15 x 1 x 25 cells over 0.15 x 0.5 m (depth 4 mm), ideal gas,
//    inflow 2.5 m/s superficial through distributor porosity 0.4 at the bottom, prescribed
//    pressure at the top, no-slip side walls. Lower half: porosity 0.45 +- 0.02 (a travelling
//    wave, so every step has work to do, as in a coupled run), drag coefficient K = 1e4
//    kg/m3/s on every face of the bed; upper half: porosity 1, no drag. DT = 1e-4 s.
//  - Bed3D: the same set-up in 3-D, 40 x 40 x 40 cells over 0.2 x 0.2 x 0.4 m.
// The counter `iters` is the mean number of SIMPLEC iterations per step (pcg_its: Krylov
// iterations per pressure solve, 1 for the direct solve of the default); the time per
// iteration of the benchmark is the time per flow step. Arguments: OpenMP threads (and, 3-D,
// whether every threaded loop is switched on).
// Run: build/bench/fluidem_gas_bench (or fluidem_bench --benchmark_filter=Gas)
#include <benchmark/benchmark.h>

#include <cmath>
#include <exception>
#include <numbers>
#include <omp.h>

#include "gas/gas_solver.hpp"

namespace {

using namespace fluidem::gas;

GasSettings bed_settings(int dim, std::array<int, 3> cells, fluidem::Vec3 hi) {
  GasSettings s;
  s.dimension = dim;
  s.cells = cells;
  s.lo = {0.0, 0.0, 0.0};
  s.hi = hi;
  s.depth = 0.004;
  for (auto& b : s.boundary) b.type = BoundaryType::wall_no_slip;
  s.boundary[bottom].type = BoundaryType::inflow;
  s.boundary[bottom].inflow.velocity = 2.5;
  s.boundary[bottom].porosity = 0.4;
  s.boundary[top].type = BoundaryType::pressure;
  return s;
}

// The bed fields: porosity 0.45 + 0.02 sin(w t + phase(cell)) in the lower half (1 above),
// K = 1e4 on the faces of the bed. sin(w t + a) = sin(w t) cos a + cos(w t) sin a with the
// per-cell cos a, sin a tabulated, so setting the field costs little next to a step.
struct BedFields {
  std::vector<double> sin_a, cos_a;
  explicit BedFields(GasSolver& gs) : sin_a(gs.grid().size(), 0.0), cos_a(gs.grid().size(), 0.0) {
    const GasGrid& g = gs.grid();
    for (int k = 1; k <= g.n[2]; ++k)
      for (int j = 1; j <= g.n[1]; ++j)
        for (int i = 1; i <= g.n[0]; ++i) {
          const double a = 2.0 * std::numbers::pi * (0.3 * i + 0.2 * j + 0.1 * k);
          sin_a[g.idx(i, j, k)] = std::sin(a);
          cos_a[g.idx(i, j, k)] = std::cos(a);
        }
    const int kbed = g.n[2] / 2;
    for (int d = 0; d < 3; ++d) {
      std::vector<double>& K = gs.drag_coefficient(d);
      for (int k = 0; k <= g.n[2]; ++k)
        for (int j = 0; j <= g.n[1]; ++j)
          for (int i = 0; i <= g.n[0]; ++i) K[g.idx(i, j, k)] = k <= kbed ? 1e4 : 0.0;
    }
  }
  void set(GasSolver& gs, double t) const {
    const GasGrid& g = gs.grid();
    const int kbed = g.n[2] / 2;
    const double w = 2.0 * std::numbers::pi / 0.02, st = std::sin(w * t), ct = std::cos(w * t);
    std::vector<double>& eps = gs.porosity();
    for (int k = 1; k <= g.n[2]; ++k)
      for (int j = 1; j <= g.n[1]; ++j)
        for (int i = 1; i <= g.n[0]; ++i) {
          const long q = g.idx(i, j, k);
          eps[q] = k <= kbed ? 0.45 + 0.02 * (st * cos_a[q] + ct * sin_a[q]) : 1.0;
        }
  }
};

void run_bed_steps(benchmark::State& state, const GasSettings& s, int warmup,
                   const LinearSolverOptions& lin, bool threaded);

// A failed step (InstabilityError) ends the benchmark with its message instead of aborting.
void run_bed(benchmark::State& state, const GasSettings& s, int warmup,
             const LinearSolverOptions& lin = {}, bool threaded = false) {
  const int threads_before = omp_get_max_threads();
  try {
    run_bed_steps(state, s, warmup, lin, threaded);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
  }
  omp_set_num_threads(threads_before);
}

void run_bed_steps(benchmark::State& state, const GasSettings& s, int warmup,
                   const LinearSolverOptions& lin, bool threaded) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  GasSolver gs(s);
  gs.set_linear_solver_options(lin);
  if (threaded) gs.set_parallel_cells(0, 0); // every threaded loop on, whatever the grid
  const BedFields bed(gs);
  bed.set(gs, 0.0);
  gs.sync_old_porosity();
  const double dt = 1e-4;
  double t = 0.0;
  for (int n = 0; n < warmup; ++n, t += dt) {
    bed.set(gs, t + dt);
    gs.step(t, dt);
  }
  long steps = 0, iterations = 0;
  const LinearSolverCounters c0 = gs.linear_counters();
  for (auto _ : state) {
    bed.set(gs, t + dt);
    gs.step(t, dt);
    t += dt;
    ++steps;
    iterations += gs.last_iterations();
  }
  const LinearSolverCounters& c = gs.linear_counters();
  const auto per = [](long a, long b) {
    return b > 0 ? static_cast<double>(a) / static_cast<double>(b) : 0.0;
  };
  state.counters["iters"] = per(iterations, steps);
  state.counters["gs_sweeps"] =
      per(c.momentum_sweeps - c0.momentum_sweeps, c.momentum_solves - c0.momentum_solves);
  state.counters["fallbacks"] = per(c.momentum_fallbacks - c0.momentum_fallbacks, steps);
  state.counters["pcg_its"] =
      per(c.pressure_iterations - c0.pressure_iterations, c.pressure_solves - c0.pressure_solves);
  state.counters["setups"] = per(c.pressure_setups - c0.pressure_setups, steps);
  state.counters["cells"] = static_cast<double>(gs.grid().n[0] * gs.grid().n[1] * gs.grid().n[2]);
}

void gas_bed_2d(benchmark::State& state) {
  run_bed(state, bed_settings(2, {15, 1, 25}, {0.15, 0.004, 0.5}), 200);
}
BENCHMARK(gas_bed_2d)->Arg(1)->Name("GasStep/Bed2D_15x1x25/threads")->Unit(benchmark::kMicrosecond);

// Second argument 1: every threaded loop on (assembly and Gauss-Seidel), 0: the defaults.
void gas_bed_3d(benchmark::State& state) {
  run_bed(state, bed_settings(3, {40, 40, 40}, {0.2, 0.2, 0.4}), 20, {}, state.range(1) != 0);
}
BENCHMARK(gas_bed_3d)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({1, 1})
    ->Args({2, 1})
    ->ArgNames({"threads", "threaded_loops"})
    ->Name("GasStep/Bed3D_40x40x40")
    ->Unit(benchmark::kMicrosecond);

// Linear-solver variants on the 2-D bed (one thread), for the choice documented in docs/gas.md.
using Reuse = StructSolverOptions::Reuse;
using Multigrid = StructSolverOptions::Multigrid;
LinearSolverOptions variant(int v) {
  LinearSolverOptions o;
  StructSolverOptions& p = o.pressure;
  switch (v) {
  case 1: // PFMG set-up once per flow step
    p.reuse = Reuse::per_step;
    break;
  case 2: // PFMG set-up before every solve
    p.reuse = Reuse::every_solve;
    break;
  case 3: // weighted Jacobi smoother, Galerkin coarse operators
    p.relax_type = 1;
    p.rap_type = 0;
    break;
  case 4: // weighted Jacobi smoother, non-Galerkin coarse operators
    p.relax_type = 1;
    p.rap_type = 1;
    break;
  case 5: // 1 + 1 red-black sweeps per level
    p.pre_relax = p.post_relax = 1;
    break;
  case 6: // 2 + 2 red-black sweeps per level
    p.pre_relax = p.post_relax = 2;
    break;
  case 7: // hypre's own number of levels (down to single cells)
    p.min_coarse_cells = 0;
    break;
  case 8: // SMG instead of PFMG
    p.multigrid = Multigrid::smg;
    p.pre_relax = p.post_relax = 1;
    break;
  case 9: // SMG, set-up before every solve
    p.multigrid = Multigrid::smg;
    p.pre_relax = p.post_relax = 1;
    p.reuse = Reuse::every_solve;
    break;
  case 10: // the old scheme: hypre for momentum too, PFMG 1+1, all levels, set-up every solve
    o.momentum = LinearSolverOptions::Momentum::hypre;
    p.reuse = Reuse::every_solve;
    p.pre_relax = p.post_relax = 1;
    p.min_coarse_cells = 0;
    break;
  case 11: // the defaults of hypre: PFMG 3+3 red-black, coarsest level >= 64 cells, adaptive
    break; // reuse (the pressure default before the direct solver)
  default: // the defaults: the direct (banded Cholesky) pressure solve on this grid
    return o;
  }
  p.direct_max_work = 0.0; // the hypre variants
  return o;
}
const char* const variant_names[] = {"default",
                                     "pfmg_per_step",
                                     "pfmg_every_solve",
                                     "pfmg_wjacobi_galerkin",
                                     "pfmg_wjacobi_rap1",
                                     "pfmg_relax_1_1",
                                     "pfmg_relax_2_2",
                                     "pfmg_all_levels",
                                     "smg_adaptive",
                                     "smg_every_solve",
                                     "old_scheme_hypre_momentum",
                                     "pfmg_adaptive"};

void gas_bed_2d_variant(benchmark::State& state) {
  const int v = static_cast<int>(state.range(1));
  state.SetLabel(variant_names[v]);
  run_bed(state, bed_settings(2, {15, 1, 25}, {0.15, 0.004, 0.5}), 200, variant(v));
}
BENCHMARK(gas_bed_2d_variant)
    ->ArgsProduct({{1}, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}})
    ->ArgNames({"threads", "variant"})
    ->Name("GasStepSolvers/Bed2D_15x1x25")
    ->Unit(benchmark::kMicrosecond);

} // namespace
