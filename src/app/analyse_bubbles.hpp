// The bubbles of `fluidem analyse` (docs/analysis.md, "Bubbles"): the voids of every frame of
// OUT/fields.h5 (analysis/bubbles.hpp), followed from frame to frame, into bubbles.csv and
// bubble_frames.csv, and their window means into summary.csv.
#pragma once
#include <filesystem>
#include <vector>

#include "app/analysis_table.hpp"

namespace fluidem {

/// Writes dir/bubbles.csv and dir/bubble_frames.csv from the porosity frames of `fields_path`
/// (all frames) and adds the rows of docs/analysis.md over [t0, t1] to `summary`. Cells with
/// porosity above `void_porosity` are dilute. InputError when the file cannot be read.
void analyse_bubbles(const std::filesystem::path& fields_path, const std::filesystem::path& dir,
                     double t0, double t1, double void_porosity, std::vector<SummaryRow>& summary);

} // namespace fluidem
