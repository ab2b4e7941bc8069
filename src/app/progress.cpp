#include "app/progress.hpp"

#include <unistd.h>

#include <fmt/format.h>

namespace fluidem {

ProgressDisplay::ProgressDisplay(std::FILE* out)
    : out_(out), terminal_(isatty(fileno(out)) != 0), start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void ProgressDisplay::operator()(const RunStatus& s) {
  const auto now = std::chrono::steady_clock::now();
  if (step_at_start_ < 0) { // the first call marks the start: rate and ETA count from here
    step_at_start_ = s.step;
    start_ = last_ = now;
    return;
  }
  const double since_last = std::chrono::duration<double>(now - last_).count();
  const bool done = s.step >= s.total_steps;
  if (since_last < (terminal_ ? 0.5 : 10.0) && !done) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double steps = static_cast<double>(s.step - step_at_start_);
  const double rate = elapsed > 0 ? steps * static_cast<double>(s.particles) / elapsed : 0.0;
  const double left = static_cast<double>(s.total_steps - s.step);
  const double eta = steps > 0 ? left * elapsed / steps : 0.0;
  const auto line = fmt::format("t = {:.4f} / {:.4f} s  {:5.1f}%  {:.3g} particle-steps/s  "
                                "ETA {:.0f} s",
                                s.time, s.end_time,
                                100.0 * static_cast<double>(s.step) /
                                    static_cast<double>(std::max(1L, s.total_steps)),
                                rate, eta);
  if (terminal_)
    fmt::print(out_, "\r{}\x1b[K", line);
  else
    fmt::print(out_, "{}\n", line);
  std::fflush(out_);
  printed_ = true;
}

void ProgressDisplay::finish() {
  if (terminal_ && printed_) fmt::print(out_, "\n");
  std::fflush(out_);
}

} // namespace fluidem
