// The busy-machine warning (app/busy_machine.hpp): threads > 1 on cores that other processes
// keep busy (busy + threads > cores + 0.5) get a warning naming the busy cores and a thread count
// that fits; one thread, or free cores, get none. The busy cores measured from /proc/stat lie in
// [0, cores] and see another process spinning (the reference: one core's worth).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/busy_machine.hpp"

namespace fluidem {
namespace {

TEST(BusyMachine, WarnsOnlyWhenTheThreadsDoNotFitOnFreeCores) {
  EXPECT_FALSE(busy_machine_warning(0.1, 2, 2));  // idle machine
  EXPECT_FALSE(busy_machine_warning(12.0, 2, 1)); // one thread: nothing to wait for
  EXPECT_FALSE(busy_machine_warning(0.4, 2, 2));  // 2.4 <= 2.5
  EXPECT_FALSE(busy_machine_warning(1.2, 8, 4));  // free cores enough
  const auto w = busy_machine_warning(3.2, 2, 2);
  ASSERT_TRUE(w);
  EXPECT_NE(w->find("3.2 of 2 cores"), std::string::npos) << *w;
  EXPECT_NE(w->find("--threads 1"), std::string::npos) << *w;
  const auto v = busy_machine_warning(4.6, 8, 8); // about 5 of 8 cores busy: 3 free
  ASSERT_TRUE(v);
  EXPECT_NE(v->find("--threads 3"), std::string::npos) << *v;
}

TEST(BusyMachine, MeasuresACoreKeptBusy) {
  if (!std::filesystem::exists("/proc/stat")) GTEST_SKIP() << "no /proc/stat";
  const auto idle = busy_cores(100);
  ASSERT_TRUE(idle);
  const double cores = std::max(1u, std::thread::hardware_concurrency());
  EXPECT_GE(*idle, 0.0);
  EXPECT_LE(*idle, cores);
  // Another process spinning through the window: at least ~one core busy (0.7 leaves room for
  // the scheduler), whatever else runs. (A process, not a thread: this process's own CPU time
  // is left out of the count.)
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    volatile double x = 0.0;
    for (;;) x = x + 1.0; // until killed
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(50)); // the child is running
  const auto busy = busy_cores(300);
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);
  ASSERT_TRUE(busy);
  EXPECT_GE(*busy, 0.7);
}

} // namespace
} // namespace fluidem
