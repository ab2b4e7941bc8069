// core/parallel.hpp: the loops run every index exactly once, serially or on the threads, and
// parallel_any returns the OR of the bodies' results; the per-thread scratch is made once per
// thread that takes part (once in all when serial); go_parallel asks for threads only when more
// than one is available.
#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include <omp.h>

#include "core/parallel.hpp"

namespace fluidem {
namespace {

class ParallelLoops : public ::testing::Test {
protected:
  void SetUp() override { saved_ = omp_get_max_threads(); }
  void TearDown() override { omp_set_num_threads(saved_); }
  int saved_ = 1;
};

TEST_F(ParallelLoops, EveryIndexOnceSeriallyAndOnTwoThreads) {
  omp_set_num_threads(2);
  for (const bool parallel : {false, true}) {
    std::vector<int> hits(10007, 0);
    parallel_for(hits.size(), parallel, [&](std::size_t i) { ++hits[i]; });
    for (std::size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i], 1) << i;
  }
}

TEST_F(ParallelLoops, ScratchOncePerThread) {
  omp_set_num_threads(2);
  for (const bool parallel : {false, true}) {
    std::atomic<int> made{0};
    std::vector<int> hits(5000, 0);
    parallel_for_with(
        hits.size(), parallel,
        [&] {
          ++made;
          return 0;
        },
        [&](int&, std::size_t i) { ++hits[i]; });
    for (std::size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i], 1) << i;
    if (parallel)
      EXPECT_EQ(made.load(), omp_get_max_threads()); // one per thread of the team
    else
      EXPECT_EQ(made.load(), 1);
  }
}

TEST_F(ParallelLoops, AnyRunsEveryIndexAndReturnsTheOr) {
  omp_set_num_threads(2);
  for (const bool parallel : {false, true}) {
    // true for no index, for the last index only (the second thread's share), for the first
    // only (the first thread's share): every index still runs once.
    for (const long hit : {-1L, 10006L, 0L}) {
      std::vector<int> hits(10007, 0);
      const bool any = parallel_any(hits.size(), parallel, [&](std::size_t i) {
        ++hits[i];
        return static_cast<long>(i) == hit;
      });
      EXPECT_EQ(any, hit >= 0) << "parallel " << parallel << ", hit " << hit;
      for (std::size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i], 1) << i;
    }
  }
}

TEST_F(ParallelLoops, ThreadsOnlyWhenLargeEnoughAndMoreThanOneAvailable) {
  omp_set_num_threads(1);
  EXPECT_FALSE(go_parallel(true));
  omp_set_num_threads(2);
  EXPECT_TRUE(go_parallel(true));
  EXPECT_FALSE(go_parallel(false));
}

} // namespace
} // namespace fluidem
