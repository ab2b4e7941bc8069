#include "app/busy_machine.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <fmt/format.h>

namespace fluidem {

std::optional<std::string> busy_machine_warning(double busy, int cores, int threads) {
  if (threads <= 1 || !(busy + threads > cores + 0.5)) return std::nullopt;
  return fmt::format("warning: the machine is busy ({:.1f} of {} cores in use by other "
                     "processes): with {} threads every step waits for the slowest, and a thread "
                     "that loses its core stalls the others; --threads {} may well be faster",
                     busy, cores, threads, std::max(1, cores - static_cast<int>(busy + 0.5)));
}

namespace {
/// Idle and total jiffies of all cores (/proc/stat, first line), or nothing.
std::optional<std::array<double, 2>> cpu_times() {
  std::ifstream f("/proc/stat");
  std::string cpu;
  if (!(f >> cpu) || cpu != "cpu") return std::nullopt;
  // user nice system idle iowait irq softirq steal (guest time is already in user)
  std::array<double, 8> t{};
  for (double& v : t)
    if (!(f >> v)) return std::nullopt;
  double total = 0.0;
  for (const double v : t) total += v;
  return std::array<double, 2>{t[3] + t[4], total};
}
/// CPU time of this process (user + system, all its threads), in the jiffies of /proc/stat
/// (fields 14 and 15 of /proc/self/stat, after the command name in parentheses), or 0.
double own_cpu_time() {
  std::ifstream f("/proc/self/stat");
  std::string line;
  if (!std::getline(f, line)) return 0.0;
  const auto close = line.rfind(')');
  if (close == std::string::npos) return 0.0;
  std::istringstream rest(line.substr(close + 1));
  std::string field;
  double utime = 0.0, stime = 0.0;
  for (int k = 3; k <= 13; ++k) rest >> field; // state .. cmajflt
  if (!(rest >> utime >> stime)) return 0.0;
  return utime + stime;
}
} // namespace

std::optional<double> busy_cores(int window_ms) {
  const auto a = cpu_times();
  const double own_a = own_cpu_time();
  std::this_thread::sleep_for(std::chrono::milliseconds(window_ms));
  const auto b = cpu_times();
  const double own_b = own_cpu_time();
  if (!a || !b || !((*b)[1] > (*a)[1])) return std::nullopt;
  const double total = (*b)[1] - (*a)[1];
  const double busy_fraction = (total - ((*b)[0] - (*a)[0]) - (own_b - own_a)) / total;
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return std::clamp(busy_fraction, 0.0, 1.0) * cores;
}

} // namespace fluidem
