#include "app/signals.hpp"

#include <csignal>
#include <unistd.h>

namespace fluidem {

namespace {

std::atomic<int> g_stop{0};
std::atomic<bool> g_announce{true};
static_assert(std::atomic<int>::is_always_lock_free, "the signal flag must be lock-free");
static_assert(std::atomic<bool>::is_always_lock_free, "the announce flag must be lock-free");

extern "C" void on_stop_signal(int sig) {
  int expected = 0;
  if (!g_stop.compare_exchange_strong(expected, sig)) {
    // Second signal: abort now (async-signal-safe calls only).
    static const char msg[] = "\nfluidem: second signal, aborting without a checkpoint\n";
    const ssize_t ignored = ::write(2, msg, sizeof msg - 1);
    (void)ignored;
    ::_exit(128 + sig);
  }
  if (!g_announce.load()) return;
  static const char msg[] = "\nfluidem: stopping after this step (writing a checkpoint; press "
                            "Ctrl-C again to abort at once)\n";
  const ssize_t ignored = ::write(2, msg, sizeof msg - 1);
  (void)ignored;
}

void set_handler(int sig, void (*handler)(int)) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  sigaction(sig, &sa, nullptr);
}

} // namespace

const std::atomic<int>& install_stop_handlers(bool announce) {
  g_stop.store(0);
  g_announce.store(announce);
  set_handler(SIGINT, on_stop_signal);
  set_handler(SIGTERM, on_stop_signal);
  set_handler(SIGUSR1, on_stop_signal);
  return g_stop;
}

void remove_stop_handlers() {
  set_handler(SIGINT, SIG_DFL);
  set_handler(SIGTERM, SIG_DFL);
  set_handler(SIGUSR1, SIG_DFL);
}

} // namespace fluidem
