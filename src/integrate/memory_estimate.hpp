// What a run will hold in memory, estimated from the case before anything is allocated (one rule
// refuses it: core/memory_budget.hpp). The per-cell sizes are what whole runs measured (maximum
// resident size against the cell count; the numbers are in memory_estimate.cpp).
#pragma once
#include <optional>
#include <vector>

#include "core/case_spec.hpp"
#include "core/memory_budget.hpp"

namespace fluidem {

/// The shares known from the case alone: the particles (`particles` when they are known, else
/// what the [[insert]] blocks ask for), the species tables, the gas grid, the continuum grid.
std::vector<MemoryShare> case_memory_shares(const CaseSpec& spec,
                                            std::optional<double> particles = std::nullopt);

} // namespace fluidem
