#include "app/validate.hpp"

#include "app/python_scripts.hpp"

namespace fluidem {

int ValidateCommand::run(const char* argv0) const {
  const auto dir = find_python_script_dir("fluidem_validate.py", argv0);
  std::vector<std::string> args{"--fluidem", own_binary_path(argv0).string()};
  if (quick) args.emplace_back("--quick");
  if (list) args.emplace_back("--list");
  if (reuse) args.emplace_back("--reuse");
  if (resume) args.emplace_back("--resume");
  if (park) args.emplace_back("--park");
  if (report_only) args.emplace_back("--report-only");
  if (long_cases) args.emplace_back("--long");
  if (!work.empty()) args.insert(args.end(), {"--work", work});
  if (!report.empty()) args.insert(args.end(), {"--report", report});
  if (!cases.empty()) args.insert(args.end(), {"--cases", cases});
  if (!archive.empty()) args.insert(args.end(), {"--archive", archive});
  for (const auto& o : only) args.insert(args.end(), {"--only", o});
  if (threads > 0) args.insert(args.end(), {"--threads", std::to_string(threads)});
  return exec_python_script(dir / "fluidem_validate.py", args);
}

std::unique_ptr<ValidateCommand> add_validate_command(CLI::App& app) {
  auto c = std::make_unique<ValidateCommand>();
  c->command = app.add_subcommand(
      "validate", "Run the seeds' cases and compare with the published numbers: writes "
                  "docs/validation/README.md (--quick: short runs, report in the work folder)");
  c->command->add_flag("--quick", c->quick,
                       "Short runs (minutes): checks that every case runs; numbers not "
                       "comparable with the papers");
  c->command->add_flag("--list", c->list, "List the runs and the compared quantities");
  c->command->add_flag("--reuse", c->reuse,
                       "Keep the runs in the work folder that completed with the same command "
                       "(re-analyse them only)");
  c->command->add_flag("--resume", c->resume,
                       "Continue the runs of the work folder that were stopped (Ctrl-C, "
                       "SIGTERM, a lost machine) from their last checkpoint: long runs in "
                       "pieces, their wall times added up (implies --reuse); also a long run "
                       "parked in the archive by another machine (--park)");
  c->command->add_flag("--park", c->park,
                       "Run nothing: keep each stopped long run of the work folder in the "
                       "archive (its checkpoint and small outputs, ARCHIVE/<run>.parked), so "
                       "that --resume continues it in a fresh checkout on another machine");
  c->command->add_flag("--long", c->long_cases,
                       "Also the full-size cases (40,000-72,600 particles, the 17 s loop): "
                       "hours of wall time each");
  c->command->add_flag("--report-only", c->report_only,
                       "Run nothing: the report from the finished runs of the work folder");
  c->command->add_option("--work", c->work,
                         "Folder of the runs (default out/validation or out/validation-quick)");
  c->command->add_option("--report", c->report, "Report file (Markdown)");
  c->command->add_option("--cases", c->cases,
                         "The case folders and their reference.toml files (default: cases/ of "
                         "the source tree)");
  c->command->add_option("--archive", c->archive,
                         "Folder of the finished full-size runs' small outputs and records "
                         "(default docs/validation/runs): a long run is copied there when it "
                         "finishes; --reuse and --report-only take long runs from there");
  c->command->add_option("--only", c->only, "Only the runs whose name contains this text");
  c->command->add_option("--threads,-t", c->threads, "OpenMP threads per run")
      ->check(CLI::PositiveNumber);
  return c;
}

} // namespace fluidem
