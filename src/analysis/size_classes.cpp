#include "analysis/size_classes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fluidem {

std::size_t SizeClasses::of(double d) const {
  return static_cast<std::size_t>(std::upper_bound(bounds.begin(), bounds.end(), d) -
                                  bounds.begin());
}

SizeClasses size_classes(const std::vector<double>& diameters, int bins) {
  if (diameters.empty() || bins < 1)
    throw std::invalid_argument("size_classes: no diameters, or bins < 1");
  std::vector<double> sorted = diameters;
  std::sort(sorted.begin(), sorted.end());
  std::vector<double> distinct = sorted;
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  SizeClasses c;
  c.distinct = distinct.size() <= kMaxDistinctSizes;
  if (c.distinct) {
    c.bounds.assign(distinct.begin() + 1, distinct.end());
  } else {
    const std::size_t n = sorted.size();
    for (int k = 1; k < bins; ++k) {
      const double b = sorted[static_cast<std::size_t>(k) * n / static_cast<std::size_t>(bins)];
      if (c.bounds.empty() || b > c.bounds.back()) c.bounds.push_back(b); // (ties merge classes)
    }
  }
  const std::size_t m = c.bounds.size() + 1;
  c.d_min.assign(m, sorted.back());
  c.d_max.assign(m, sorted.front());
  c.count.assign(m, 0);
  for (const double d : sorted) {
    const std::size_t k = c.of(d);
    c.d_min[k] = std::min(c.d_min[k], d);
    c.d_max[k] = std::max(c.d_max[k], d);
    ++c.count[k];
  }
  return c;
}

double volume_weighted_median_diameter(const std::vector<double>& diameters, bool two_d) {
  if (diameters.empty()) throw std::invalid_argument("volume_weighted_median_diameter: empty");
  std::vector<double> sorted = diameters;
  std::sort(sorted.begin(), sorted.end());
  const double p = two_d ? 2.0 : 3.0;
  double total = 0.0;
  for (const double d : sorted) total += std::pow(d, p);
  double sum = 0.0;
  for (const double d : sorted) {
    sum += std::pow(d, p);
    if (sum >= 0.5 * total) return d;
  }
  return sorted.back();
}

} // namespace fluidem
