// A warning for threaded runs on a busy machine. The parallel loops end in barriers: each step
// waits for its slowest thread, and a thread the operating system has descheduled for another
// process holds all the others: such a run can be several times slower than one thread
// (bench/RESULTS.md). fluidem cannot fix that, but it can say so at the start of the run instead
// of leaving the user with a mysteriously slow run.
#pragma once
#include <optional>
#include <string>

namespace fluidem {

/// The warning for a run of `threads` OpenMP threads on `cores` cores while other processes keep
/// `busy` cores busy, or nothing: warned when threads > 1 and the free cores do not hold them
/// all (busy + threads > cores + 0.5).
std::optional<std::string> busy_machine_warning(double busy, int cores, int threads);

/// Cores kept busy by other processes, measured from /proc/stat over `window` milliseconds
/// while this thread sleeps, minus this process's own CPU time in the window (/proc/self/stat:
/// its idle OpenMP threads may still spin after the set-up's parallel loops, and spin throughout
/// under OMP_WAIT_POLICY=active). A load average would count the last minute, including this
/// run's own set-up or the run before it in a script. Nothing where there is no /proc/stat.
std::optional<double> busy_cores(int window_ms);

} // namespace fluidem
