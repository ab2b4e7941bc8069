// Google Benchmark: one flow step of the particle-gas coupling without the gas solve
// (porosity, gas -> particle forces, deposit to the gas, forces after the gas step) for 2400
// particles of 4 mm (the Tsuji bed's count) in a 3-D bed of 60 x 40 x 150 mm on 10 mm cells,
// by kernel: trilinear stencils with porosity by cell [Hoomans96 eq. 40-41, Deen07 eq. 33]
// (arg 0) or the porous cube a = 3 [Deen07 eq. 34-39] (arg 1). Threads: OMP_NUM_THREADS.
// Run: build/bench/fluidem_bench --benchmark_filter=Coupling
#include <benchmark/benchmark.h>

#include <random>

#include "coupling/exchange.hpp"

namespace {

using namespace fluidem;

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
  coupling::ParticleGasForces f;
  for (auto _ : state) {
    coupling::update_porosity(gs, p, c);
    coupling::compute_particle_forces(gs, p, c, f);
    coupling::deposit_momentum_source(gs, p, f);
    coupling::update_particle_forces(gs, p, f);
    benchmark::DoNotOptimize(f.drag_z.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(p.size()));
}
BENCHMARK(coupling_step)
    ->Arg(0)
    ->Arg(1)
    ->Name("CouplingStep/2400_particles/kernel")
    ->Unit(benchmark::kMicrosecond);

} // namespace
