// The case-file reader: TOML text -> validated CaseSpec (docs/case-file.md is the reference).
// Every bad input is one InputError line "file:line:column: key: what is wrong (what is allowed)".
#pragma once
#include <string>
#include <vector>

#include "core/case_spec.hpp"

namespace fluidem {

/// Reads the case file at `path`, applies the command-line `overrides` ("section.key=value", as
/// given to --set) and validates the result. Relative insert file paths are resolved against the
/// folder of `path` and stored absolute. Throws InputError.
CaseSpec read_case_file(const std::string& path, const std::vector<std::string>& overrides = {});

/// As read_case_file, for case text already in memory; `source_name` is the file name used in
/// messages and CaseSpec::source_file, and its folder resolves relative insert file paths (the
/// current folder when it has none).
CaseSpec read_case_string(const std::string& text, const std::string& source_name,
                          const std::vector<std::string>& overrides = {});

} // namespace fluidem
