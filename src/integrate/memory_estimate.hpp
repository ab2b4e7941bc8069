// What a run will hold in memory, estimated from the case before anything is allocated (one rule
// refuses it: core/memory_budget.hpp). The per-cell sizes are what whole runs measured (maximum
// resident size against the cell count; the numbers are in memory_estimate.cpp).
#pragma once
#include <optional>
#include <vector>

#include "core/case_spec.hpp"
#include "core/memory_budget.hpp"
#include "neighbour/neighbour_list.hpp"

namespace fluidem {

/// The shares known from the case alone: the particles (`particles` when they are known, else
/// what the [[insert]] blocks ask for), the species tables, the gas grid, the continuum grid.
std::vector<MemoryShare> case_memory_shares(const CaseSpec& spec,
                                            std::optional<double> particles = std::nullopt);

/// The share of the cell grid the neighbour lists bin particles in (cells at least `cell_size`
/// wide over the domain). InputError (key domain.hi) when the grid has more cells than its
/// 32-bit cell index counts.
MemoryShare cell_grid_share(const CaseSpec& spec, const BoxGeometry& box, double cell_size);

} // namespace fluidem
