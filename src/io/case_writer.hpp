// The case-file writer: CaseSpec -> complete TOML (case.resolved.toml), every key written with
// its value or default, so read_case_string() gives back the identical CaseSpec.
#pragma once
#include <string>

#include "core/case_spec.hpp"

namespace fluidem {

/// The whole case as TOML text. Doubles are written in the shortest form that reads back to the
/// same bits; insert file paths are written as stored (absolute after read_case_*).
std::string write_case_toml(const CaseSpec& spec);

/// Shortest decimal text that reads back to exactly `x`, always a TOML float (e.g. "1.0",
/// "0.30000000000000004", "1e-07", "inf", "nan").
std::string format_double(double x);

} // namespace fluidem
