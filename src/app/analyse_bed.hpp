// The bed quantities of `fluidem analyse` (docs/analysis.md, "Bed"): pressure drop against the
// bed weight, bed height and expansion, collision rate, the energy balance of a run without gas,
// and the settled area fraction of a 2-D bed [Hoomans96 §5.1].
#pragma once
#include <filesystem>
#include <vector>

#include "app/analysis_table.hpp"

namespace fluidem {

/// Adds the rows named in docs/analysis.md to `summary` from OUT/series.csv over [t0, t1] and
/// the first and last frames of OUT/particles.h5 (masses from OUT/case.resolved.toml). A
/// quantity whose inputs the run lacks (no gas: no pressure drop) is left out, with a line on
/// stdout. InputError when series.csv has no row in the window.
void analyse_bed(const std::filesystem::path& out, double t0, double t1,
                 std::vector<SummaryRow>& summary);

} // namespace fluidem
