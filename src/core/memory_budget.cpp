#include "core/memory_budget.hpp"

#include <unistd.h>

#include <algorithm>

#include <fmt/format.h>

namespace fluidem {

double physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return 0.0;
  return static_cast<double>(pages) * static_cast<double>(page);
}

std::string format_bytes(double bytes) {
  static const char* const units[] = {"kB", "MB", "GB", "TB"};
  double v = bytes / 1e3;
  int u = 0;
  while (u < 3 && v >= 1e3) v /= 1e3, ++u;
  return fmt::format("{:.3g} {}", v, units[u]);
}

void require_memory(const CaseSpec& spec, const std::vector<MemoryShare>& shares,
                    double available) {
  if (!(available > 0.0) || shares.empty()) return;
  double total = 0.0;
  for (const MemoryShare& s : shares) total += s.bytes;
  if (total <= available) return; // (a NaN estimate is refused)
  const auto largest = std::max_element(
      shares.begin(), shares.end(),
      [](const MemoryShare& a, const MemoryShare& b) { return !(a.bytes >= b.bytes); });
  const std::string part = format_bytes(largest->bytes), all = format_bytes(total);
  const std::string whole = part != all ? fmt::format(" (the whole run about {})", all) : "";
  throw InputError(spec.where(largest->key), largest->key,
                   fmt::format("{} needs about {} of memory{}, this machine has {} (allowed: a "
                               "case that fits in the memory)",
                               largest->what, part, whole, format_bytes(available)));
}

void require_memory(const CaseSpec& spec, const std::vector<MemoryShare>& shares) {
  require_memory(spec, shares, physical_memory_bytes());
}

} // namespace fluidem
