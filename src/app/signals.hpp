// SIGINT / SIGTERM during a run: the first signal asks the run to stop after the current step
// (it then writes a checkpoint and flushes its outputs); a second one ends the process at once
// with exit code 128 + signal.
#pragma once
#include <atomic>

namespace fluidem {

/// Installs the handlers (sigaction) and returns the flag they set: 0 until a signal arrives,
/// then its number.
const std::atomic<int>& install_stop_handlers();
/// Puts the default handlers back.
void remove_stop_handlers();

} // namespace fluidem
