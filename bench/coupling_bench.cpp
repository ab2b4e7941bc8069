// Google Benchmark: one flow step of the particle-gas coupling without the gas solve
// (porosity, gas -> particle forces, deposit to the gas, forces after the gas step), as
// GasCoupling::step does it (integrate/gas_coupling.cpp), work space kept between steps.
//  - CouplingStep: 2400 particles of 4 mm (the Tsuji bed's count) in a 3-D bed of
//    60 x 40 x 150 mm on 10 mm cells, by kernel: trilinear stencils with porosity by cell
//    [Hoomans96 eq. 40-41, Deen07 eq. 33] (arg 0) or the porous cube a = 3 [Deen07 eq. 34-39]
//    (arg 1). Threads: OMP_NUM_THREADS.
//  - CouplingTsuji: the Tsuji bed's grid, 15 x 1 x 25 cells over 0.15 x 0.004 x 0.5 m, 2400
//    particles of 4 mm on a jittered lattice in the lower 0.3 m (solid fraction ~0.4), 2-D
//    (discs, the hard_2d runs of bench/tsuji.sh) or 3-D one cell deep (spheres, soft_3d); the
//    argument: OpenMP threads.
// Run: build/bench/fluidem_bench --benchmark_filter=Coupling
#include <benchmark/benchmark.h>

#include <omp.h>
#include <random>

#include "coupling/exchange.hpp"

namespace {

using namespace fluidem;

void run_steps(benchmark::State& state, gas::GasSolver& gs, const ParticleStore& p,
               const coupling::CouplingSettings& c) {
  coupling::ParticleGasForces f;
  coupling::PorosityScratch scratch;
  for (auto _ : state) {
    coupling::update_porosity(gs, p, c, scratch);
    coupling::compute_particle_forces(gs, p, c, f);
    coupling::deposit_momentum_source(gs, p, f);
    coupling::update_particle_forces(gs, p, f);
    benchmark::DoNotOptimize(f.drag_z.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(p.size()));
}

void coupling_step(benchmark::State& state) {
  gas::GasSettings s;
  s.cells = {6, 4, 15};
  s.hi = {0.06, 0.04, 0.15};
  gas::GasSolver gs(s);
  ParticleStore p;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> jitter(-0.0004, 0.0004), vel(-0.5, 0.5);
  // Simple cubic lattice of spacing 4.8 mm with jitter: 12 x 8 x 25 = 2400 particles.
  for (int k = 0; k < 25; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 12; ++i)
        p.add({0.0024 + 0.0048 * i + jitter(rng), 0.0024 + 0.0048 * j + jitter(rng),
               0.0024 + 0.0048 * k + jitter(rng)},
              {vel(rng), vel(rng), vel(rng)}, 0.002, 2700.0, 0, p.size());
  coupling::CouplingSettings c;
  if (state.range(0) == 1) {
    c.porosity.method = coupling::PorosityMethod::porous_cube;
    c.porosity.cube_factor = 3.0;
  }
  run_steps(state, gs, p, c);
}
BENCHMARK(coupling_step)
    ->Arg(0)
    ->Arg(1)
    ->Name("CouplingStep/2400_particles/kernel")
    ->Unit(benchmark::kMicrosecond);

void coupling_tsuji(benchmark::State& state, int dim) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(static_cast<int>(state.range(0)));
  gas::GasSettings s;
  s.dimension = dim;
  s.cells = {15, 1, 25};
  s.hi = {0.15, 0.004, 0.5};
  s.depth = 0.004;
  gas::GasSolver gs(s);
  ParticleStore p;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> jitter(-0.0003, 0.0003), vel(-0.5, 0.5);
  // Lattice of spacing 4.6 mm with jitter: 32 x 75 = 2400 particles up to z = 0.345 m.
  for (int k = 0; k < 75; ++k)
    for (int i = 0; i < 32; ++i)
      p.add({0.0023 + 0.0046 * i + jitter(rng), 0.002, 0.0023 + 0.0046 * k + jitter(rng)},
            {vel(rng), 0.0, vel(rng)}, 0.002, 2700.0, 0, p.size());
  run_steps(state, gs, p, coupling::CouplingSettings{});
  omp_set_num_threads(before);
}
void coupling_tsuji_2d(benchmark::State& state) {
  coupling_tsuji(state, 2);
}
void coupling_tsuji_3d(benchmark::State& state) {
  coupling_tsuji(state, 3);
}
BENCHMARK(coupling_tsuji_2d)
    ->Arg(1)
    ->Arg(2)
    ->Name("CouplingTsuji/2D_15x1x25/threads")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(coupling_tsuji_3d)
    ->Arg(1)
    ->Arg(2)
    ->Name("CouplingTsuji/3D_15x1x25/threads")
    ->Unit(benchmark::kMicrosecond);

} // namespace
