// Nearest valid key for an unknown one (case-file keys, --set keys, enumeration names).
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace fluidem {

/// Levenshtein edit distance (insertions, deletions, substitutions, each costing 1).
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate with the smallest edit distance to `key` (the first one on a tie), or "" when
/// there are no candidates.
std::string nearest_key(std::string_view key, const std::vector<std::string>& candidates);

} // namespace fluidem
