// The full validation report (`fluidem validate`), label validation (outside CI: about an hour
// on two cores). Writes the report into a temporary folder and checks that every run completed
// and every quantity was computed; the published comparison itself is the report's content
// (agreement yes/no per row, with reasons), regenerated into docs/validation/README.md by
// running `fluidem validate` from the source tree. Set FLUIDEM_VALIDATION_REPORT to a path to
// keep this run's report there.
#include <gtest/gtest.h>

#include <cstdlib>

#include "../../common/cli_runner.hpp"

namespace {

using fluidem::test::contains;
using fluidem::test::fluidem;
using fluidem::test::read_file;
using fluidem::test::Result;
using fluidem::test::run_command;
using fluidem::test::TempDir;

TEST(ValidateFull, EveryCaseRunsAndEveryQuantityIsComputed) {
  TempDir dir("fluidem_validate_full");
  const char* keep = std::getenv("FLUIDEM_VALIDATION_REPORT");
  const std::string report = keep != nullptr ? keep : (dir.path / "README.md").string();
  const Result r = fluidem({"validate", "--work", "work", "--report", report}, dir.path);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const std::string text = read_file(report);
  EXPECT_FALSE(contains(text, "not computed")) << text;
  EXPECT_FALSE(contains(text, "## Failures")) << text;
  EXPECT_TRUE(contains(text, "**yes**")) << text;
}

// `fluidem validate --long`: the full-size cases as well (hours each: 40,000 to 72,600
// particles, the 17 s spouted-bed loop). Set FLUIDEM_VALIDATION_WORK to a folder to keep (and,
// with --reuse, continue) the runs there.
TEST(ValidateFull, TheFullSizeCasesRunAndAreCompared) {
  TempDir dir("fluidem_validate_long");
  const char* keep = std::getenv("FLUIDEM_VALIDATION_REPORT");
  const char* work = std::getenv("FLUIDEM_VALIDATION_WORK");
  const std::string report = keep != nullptr ? keep : (dir.path / "README.md").string();
  const Result r = fluidem({"validate", "--long", "--reuse", "--work",
                            work != nullptr ? std::string(work) : (dir.path / "work").string(),
                            "--report", report},
                           dir.path);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const std::string text = read_file(report);
  EXPECT_FALSE(contains(text, "not computed")) << text;
  EXPECT_FALSE(contains(text, "not run: a full-size case")) << text;
}

} // namespace
