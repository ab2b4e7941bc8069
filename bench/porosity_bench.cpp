// Google Benchmark kernels: the exact sphere-cell intersection volumes behind porosity by cell
// [Deen07 eq. 33]. All cases are closed forms: a sphere cut by one plane is a cap, one cut by
// planes on two or three axes (near a cell edge or corner) a wedge or corner volume (atan2).
// Run: build/bench/fluidem_bench --benchmark_filter=Sphere
#include <benchmark/benchmark.h>

#include <array>

#include "core/vec3.hpp"
#include "coupling/porosity.hpp"

namespace {

using fluidem::Vec3;

// A 4 mm sphere in a 10 mm cell, centred `offset` from the cell's low corner along each of the
// first `axes` axes (the others: centred in the cell).
void sphere_box(benchmark::State& state) {
  const int axes = static_cast<int>(state.range(0));
  const double r = 0.002, h = 0.01;
  const std::array<double, 3> lo{0.0, 0.0, 0.0}, hi{h, h, h};
  Vec3 c{0.5 * h, 0.5 * h, 0.5 * h};
  for (int a = 0; a < axes; ++a) c[a] = 0.0007; // cut by the low plane of axis a
  double sum = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(c);
    sum += fluidem::coupling::sphere_box_volume(c, r, lo, hi);
  }
  benchmark::DoNotOptimize(sum);
}
BENCHMARK(sphere_box)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Name("SphereBoxVolume/cut_axes");

} // namespace
