// Loops over particles (or rows) that run on the OpenMP threads only when that pays, and enter
// no OpenMP region at all otherwise. A `#pragma omp parallel ... if (false)` region still costs a
// system call: libgomp ends every region, even one of a single thread, with a futex wake-up,
// which costs far more than the short loops of a small bed (bench/RESULTS.md, "futex").
#pragma once
#include <cstddef>

#include <omp.h>

namespace fluidem {

/// True if a loop that is `large_enough` to share out should go parallel: more than one
/// OpenMP thread is available (the --threads setting, OMP_NUM_THREADS).
inline bool go_parallel(bool large_enough) {
  return large_enough && omp_get_max_threads() > 1;
}

/// Loops over particles go parallel above this many particles (soft-sphere DEM, neighbour
/// lists, coupling, porosity). Below it the threads cost more than they share out: a worker
/// thread's reads of what the main thread has just written (the gas fields, the contact
/// accumulators) outweigh its share of the work (bench/RESULTS.md).
inline constexpr std::size_t kThreadedParticles = 4096;

/// go_parallel for a loop over n particles.
inline bool threaded_particles(std::size_t n) {
  return go_parallel(n > kThreadedParticles);
}

/// body(i) for i = 0 .. n-1: statically scheduled over the threads if `parallel`, else a plain
/// loop. The static schedule gives each thread a fixed contiguous range, the same from call to
/// call (results must not depend on the thread count: the bodies write per-index data only).
template <class Index, class Body>
void parallel_for(Index n, bool parallel, Body&& body) {
  if (parallel) {
#pragma omp parallel for schedule(static)
    for (Index i = 0; i < n; ++i) body(i);
  } else {
    for (Index i = 0; i < n; ++i) body(i);
  }
}

/// As parallel_for for a body that returns a bool: whether it returned true for any index
/// (every index is run; the OR does not depend on the order).
template <class Index, class Body>
bool parallel_any(Index n, bool parallel, Body&& body) {
  bool any = false;
  if (parallel) {
#pragma omp parallel for schedule(static) reduction(|| : any)
    for (Index i = 0; i < n; ++i) any = body(i) || any;
  } else {
    for (Index i = 0; i < n; ++i) any = body(i) || any;
  }
  return any;
}

/// As parallel_for with per-thread scratch: make() builds one per thread (one in all when the
/// loop runs serially), body(scratch, i).
template <class Index, class Make, class Body>
void parallel_for_with(Index n, bool parallel, Make&& make, Body&& body) {
  if (parallel) {
#pragma omp parallel
    {
      auto scratch = make();
#pragma omp for schedule(static)
      for (Index i = 0; i < n; ++i) body(scratch, i);
    }
  } else {
    auto scratch = make();
    for (Index i = 0; i < n; ++i) body(scratch, i);
  }
}

} // namespace fluidem
