// `fluidem validate [--quick]`: runs the seeds' cases and writes the validation report
// (python/fluidem_validate.py does the work; docs/validation/README.md is its full report).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace fluidem {

struct ValidateCommand {
  CLI::App* command = nullptr;
  bool quick = false;
  bool list = false;
  bool reuse = false;
  bool resume = false;
  bool park = false;
  bool report_only = false;
  bool long_cases = false;
  std::string work, report, cases, archive;
  std::vector<std::string> only;
  int threads = 0;
  bool selected() const { return command->parsed(); }
  /// Runs the script with this binary; returns its exit code.
  int run(const char* argv0) const;
};
std::unique_ptr<ValidateCommand> add_validate_command(CLI::App& app);

} // namespace fluidem
