// Size classes of a bed, for the analyses per particle size (docs/analysis.md): a bed of a few
// distinct diameters (species of distinct diameters, a discrete size distribution: at most
// kMaxDistinctSizes of them) has one class per diameter; a bed of more (a continuous size
// distribution) has `bins` classes of equal particle counts, split at the order statistics
// d_(k n / bins) of its sorted diameters (quantile classes: equal counts give every class the
// same statistical weight). And the volume-weighted median diameter, where a continuous bed is
// split into "small" and "large" for the degree of segregation (analysis/segregation.hpp).
#pragma once
#include <cstddef>
#include <vector>

namespace fluidem {

inline constexpr std::size_t kMaxDistinctSizes = 8;
inline constexpr int kSizeBins = 4; ///< equal-count classes of a continuous distribution

struct SizeClasses {
  /// Lower bounds of the classes 1.. (class k: bounds[k-1] <= d < bounds[k]), ascending.
  std::vector<double> bounds;
  std::vector<double> d_min, d_max; ///< the smallest and largest diameter in each class, m
  std::vector<long> count;          ///< particles in each class
  bool distinct = false;            ///< one class per distinct diameter
  std::size_t size() const { return count.size(); }
  /// The class of diameter d.
  std::size_t of(double d) const;
};

/// The classes of `diameters` (m, any order, not empty); bins >= 1.
SizeClasses size_classes(const std::vector<double>& diameters, int bins = kSizeBins);

/// The diameter d_50,3 below which half the solids volume lies (the smallest diameter whose
/// cumulative volume, smallest first, reaches half the total [Allen 1997, §4.7]): volumes d^3,
/// or disc areas d^2 when two_d. `diameters` not empty.
double volume_weighted_median_diameter(const std::vector<double>& diameters, bool two_d);

} // namespace fluidem
