// A case that cannot fit in this machine's memory is bad input, refused before anything is
// allocated (not a std::bad_alloc after seconds of allocation). Each grid and table estimates its
// share from the case (the particles, the species tables, the gas and continuum grids, the
// neighbour-list cell grid); one rule compares their sum with the physical memory and names the
// key of the largest share with its estimate.
#pragma once
#include <string>
#include <vector>

#include "core/case_spec.hpp"

namespace fluidem {

/// What one grid or table of a run needs, and which case key sets its size.
struct MemoryShare {
  std::string key;  ///< e.g. "gas.cells"; its location in the case is named in the error
  std::string what; ///< e.g. "the gas grid of 1e+10 cells"
  double bytes = 0; ///< estimate
};

/// Physical memory of this machine, bytes (0 when it cannot be found).
double physical_memory_bytes();

/// "1.23 GB" (kB to TB): a byte count as a message shows it.
std::string format_bytes(double bytes);

/// InputError at the key of the largest share when the shares together need more than
/// `available` bytes (no check when available <= 0, i.e. unknown).
void require_memory(const CaseSpec& spec, const std::vector<MemoryShare>& shares, double available);
/// The same against this machine's physical memory.
void require_memory(const CaseSpec& spec, const std::vector<MemoryShare>& shares);

} // namespace fluidem
