// SIGINT / SIGTERM / SIGUSR1 during a run: the first signal asks the run to stop after the
// current step (it then writes a checkpoint and flushes its outputs); a second one ends the
// process at once with exit code 128 + signal. SIGUSR1 is for runs under mpirun: Open MPI's
// mpirun forwards it to every rank and waits for them, where on SIGINT or SIGTERM it kills the
// ranks one second after forwarding (odls_base_sigkill_timeout), before a large checkpoint is
// written (docs/parallel.md).
#pragma once
#include <atomic>

namespace fluidem {

/// Installs the handlers (sigaction) and returns the flag they set: 0 until a signal arrives,
/// then its number. `announce`: the first signal prints that the run stops after this step (a
/// run on several ranks announces it on the root only: mpirun forwards the signal to each).
const std::atomic<int>& install_stop_handlers(bool announce = true);
/// Puts the default handlers back.
void remove_stop_handlers();

} // namespace fluidem
