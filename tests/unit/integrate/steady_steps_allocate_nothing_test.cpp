// No heap allocation in the time loop [issue 7]: once a run is warm (its neighbour lists, event
// queue, contact and gas-solver scratch sized by the first steps), a time step allocates nothing,
// except where the soft-sphere neighbour list is rebuilt: a build allocates a fixed number of
// arrays (NeighbourList::build releases the previous list and the cell grid after it, so that a
// run holds one list, not two: the memory target of issue 7), and a spatial sort (of either
// engine) a fixed number more, independent of the particle and contact counts. Counted here by
// replacing the global operator new in this test executable (every C++ container, std::function and
// make_unique of the code goes through it), switched on only while the measured steps run; the
// steps are taken in windows of ten, and per window the list builds and sorts are read from the
// simulation. Expected (exact counts of deterministic runs, not timings):
//  - windows without a build or a sort: no operator-new call at all;
//  - windows with builds: at most kPerBuild per build plus kPerSort per sort (measured: 11 per
//    build, 27 more per sort, at 1000 and 6000 particles alike).
// Cases (the time loop's paths):
//  (a) soft spheres (tests/common/random_bed.hpp), Hertz with tangential history and rolling
//      springs, 6000 particles in a closed box on two threads (the threaded list build and
//      contact loop, the folded step), a spatial sort at every fourth build;
//  (b) the same with linear springs, 1000 particles, periodic in x and y, one thread;
//  (c) the hard-sphere engine coupled to the gas: the Hoomans96 bubble bed (2-D, 2400 discs,
//      cases/hoomans96/bubble_orifice.toml; the engine rebuilds its lists every few flow steps,
//      allocating nothing; a spatial sort at every third build);
//  (d) soft spheres coupled to a 3-D gas (ideal gas, Beetstra drag, porous-cube porosity,
//      several particle steps per flow step);
//  (e) (c) with coupling.smoothing_length = 15 mm (the smoothing's work space is kept).
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>

#include "../../common/fold_threshold.hpp"
#include "../../common/random_bed.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};

void* counted_alloc(std::size_t n) noexcept {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1);
  return std::malloc(n == 0 ? 1 : n);
}
void* counted_aligned_alloc(std::size_t n, std::align_val_t a) noexcept {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1);
  const auto al = static_cast<std::size_t>(a);
  return std::aligned_alloc(al, (n + al - 1) / al * al);
}
void* or_throw(void* q) {
  if (q == nullptr) throw std::bad_alloc();
  return q;
}
} // namespace

// Every replaceable allocation function (the nothrow ones too: std::stable_sort's temporary
// buffer uses them), all on malloc/free, so that every delete matches its new (AddressSanitizer
// checks it).
void* operator new(std::size_t n) {
  return or_throw(counted_alloc(n));
}
void* operator new[](std::size_t n) {
  return or_throw(counted_alloc(n));
}
void* operator new(std::size_t n, std::align_val_t a) {
  return or_throw(counted_aligned_alloc(n, a));
}
void* operator new[](std::size_t n, std::align_val_t a) {
  return or_throw(counted_aligned_alloc(n, a));
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  return counted_alloc(n);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  return counted_alloc(n);
}
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_aligned_alloc(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_aligned_alloc(n, a);
}
// The replaced operator new allocates with malloc, so free is the matching release; GCC's
// -Wmismatched-new-delete (at -O1, after inlining into gtest's factories) does not see the
// replacement and warns.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* q) noexcept {
  std::free(q);
}
void operator delete[](void* q) noexcept {
  std::free(q);
}
void operator delete(void* q, std::size_t) noexcept {
  std::free(q);
}
void operator delete[](void* q, std::size_t) noexcept {
  std::free(q);
}
void operator delete(void* q, std::align_val_t) noexcept {
  std::free(q);
}
void operator delete[](void* q, std::align_val_t) noexcept {
  std::free(q);
}
void operator delete(void* q, std::size_t, std::align_val_t) noexcept {
  std::free(q);
}
void operator delete[](void* q, std::size_t, std::align_val_t) noexcept {
  std::free(q);
}
void operator delete(void* q, const std::nothrow_t&) noexcept {
  std::free(q);
}
void operator delete[](void* q, const std::nothrow_t&) noexcept {
  std::free(q);
}
void operator delete(void* q, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(q);
}
void operator delete[](void* q, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(q);
}

namespace fluidem {
namespace {

constexpr long kPerBuild = 12, kPerSort = 32;

struct Window {
  long builds = 0, sorts = 0, allocations = 0;
};

/// Steps `windows` windows of 10 steps on `threads` threads after `warm` steps; per window the
/// list builds, the spatial sorts and the operator-new calls during its steps.
std::vector<Window> count_allocations(Simulation& sim, long warm, int windows, int threads) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  sim.advance(warm);
  std::vector<Window> out;
  out.reserve(static_cast<std::size_t>(windows));
  for (int k = 0; k < windows; ++k) {
    const long b0 = sim.neighbour_builds(), s0 = sim.spatial_sorts();
    allocations.store(0);
    counting.store(true);
    sim.advance(10);
    counting.store(false);
    out.push_back({sim.neighbour_builds() - b0, sim.spatial_sorts() - s0, allocations.load()});
  }
  omp_set_num_threads(saved);
  return out;
}

/// The expectations above; `need_builds`: the windows must include builds (and windows without).
void expect_steady(const std::vector<Window>& w, bool need_builds) {
  int quiet = 0, building = 0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    if (w[k].builds == 0 && w[k].sorts == 0) {
      ++quiet;
      EXPECT_EQ(w[k].allocations, 0) << "window " << k << " (no list build)";
    } else {
      ++building;
      EXPECT_LE(w[k].allocations, kPerBuild * w[k].builds + kPerSort * w[k].sorts)
          << "window " << k << ": " << w[k].builds << " builds, " << w[k].sorts << " sorts";
    }
  }
  EXPECT_GT(quiet, 0);
  if (need_builds) {
    EXPECT_GT(building, 0);
  }
}

TEST(SteadySteps, ThreadedSoftSpheresAllocateOnlyAtListBuilds) {
  // A spatial sort at every fourth list build, so that the windows include sorts; the folded
  // step on this sparse bed too (its threshold lowered).
  const test::FoldThreshold fold_always(0.0);
  Simulation sim(read_case_string(
      test::random_bed(6000, "[0.08, 0.08, 0.06]", "hertz",
                       "rolling = \"spring_dashpot\"\n[neighbour]\nsort_interval = 4\n"),
      "alloc.toml"));
  const long folded = sim.folded_steps();
  expect_steady(count_allocations(sim, 200, 30, 2), true);
  EXPECT_GT(sim.folded_steps(), folded); // the folded step ran among the measured ones
}

TEST(SteadySteps, PeriodicLinearSpringsAllocateOnlyAtListBuilds) {
  Simulation sim(read_case_string(
      test::random_bed(1000, "[0.04, 0.04, 0.04]\nperiodic = [true, true, false]", "linear",
                       "stiffness = 2000.0\n[neighbour]\nsort_interval = 4\n"),
      "alloc.toml"));
  expect_steady(count_allocations(sim, 200, 30, 1), true);
}

TEST(SteadySteps, HardSphereBubbleBedAllocatesOnlyAtSorts) {
  // A spatial sort at every third list build, so that some windows have one and some not
  // (neighbour_builds() counts the soft-sphere lists only: the hard-sphere builds are held to
  // no allocation at all).
  Simulation sim(
      read_case_file(std::string(FLUIDEM_SOURCE_DIR) + "/cases/hoomans96/bubble_orifice.toml",
                     {"neighbour.sort_interval=3"}));
  expect_steady(count_allocations(sim, 30, 8, 1), true);
  ASSERT_NE(sim.hard_sphere(), nullptr);
  EXPECT_GT(sim.hard_sphere()->stats().collisions, 0);
}

TEST(SteadySteps, SmoothedCouplingFieldsAllocateNothing) {
  // (e) the bubble bed of (c) with coupling.smoothing_length (coupling/smoothing.hpp: the work
  // space is kept between flow steps).
  Simulation sim(
      read_case_file(std::string(FLUIDEM_SOURCE_DIR) + "/cases/hoomans96/bubble_orifice.toml",
                     {"coupling.smoothing_length=0.015"}));
  const std::vector<Window> w = count_allocations(sim, 30, 5, 1);
  for (std::size_t k = 0; k < w.size(); ++k) {
    if (w[k].sorts == 0) {
      EXPECT_EQ(w[k].allocations, 0) << "window " << k;
    }
  }
}

TEST(SteadySteps, SoftSpheresInA3DGasAllocateOnlyAtListBuilds) {
  // The random bed with a gas section after its [contact].
  Simulation sim(read_case_string(test::random_bed(1500, "[0.04, 0.04, 0.12]", "hertz", R"(
[gas]
cells = [4, 4, 12]
time_step = 1e-4
viscosity = 1.8e-5
[gas.boundary.bottom]
type = "inflow"
velocity = 1.5
[gas.boundary.top]
type = "pressure"
pressure = 101325.0
[coupling]
drag = "beetstra"
porosity = "porous_cube"
)"),
                                  "alloc_gas.toml"));
  expect_steady(count_allocations(sim, 100, 30, 1), true);
}

} // namespace
} // namespace fluidem
