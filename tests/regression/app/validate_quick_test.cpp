// `fluidem validate --quick` as CI runs it: every shipped seed case of the report runs in its
// short version, `fluidem analyse` and `fluidem plot` succeed on it, and every compared quantity
// is extracted (exit 0). The report lists each quantity of fluidem_validate.py --list once, with
// a finite value, marked as not comparable (quick), and the cases that cannot be run with their
// reason. The numbers themselves are checked by the full report (label validation) and by the
// physics tests of each module; here a run that breaks, or an output the report needs that
// disappears, fails.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <regex>
#include <sstream>

#include "../../common/cli_runner.hpp"

namespace {

using fluidem::test::contains;
using fluidem::test::fluidem;
using fluidem::test::read_file;
using fluidem::test::Result;
using fluidem::test::run_command;
using fluidem::test::TempDir;

TEST(ValidateQuick, EveryCaseRunsAndEveryQuantityIsExtracted) {
  TempDir dir("fluidem_validate_quick");
  const Result list = fluidem({"validate", "--quick", "--list"}, dir.path);
  ASSERT_EQ(list.code, 0) << list.err;
  int quantities = 0;
  {
    std::istringstream in(list.out);
    for (std::string line; std::getline(in, line);) quantities += line.rfind("quantity ", 0) == 0;
  }
  ASSERT_GE(quantities, 10) << list.out;

  const Result r = fluidem({"validate", "--quick", "--work", "work", "--threads", "2"}, dir.path);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const std::string report = read_file(dir.path / "work" / "README.md");
  EXPECT_TRUE(contains(report, "QUICK RUNS")) << report;
  // One table row per quantity, each with a number in the fluidem column and "n/a (quick)".
  int rows = 0;
  const std::regex row(R"(\| n/a \(quick\) \|)");
  for (auto it = std::sregex_iterator(report.begin(), report.end(), row);
       it != std::sregex_iterator(); ++it)
    ++rows;
  EXPECT_EQ(rows, quantities) << report;
  EXPECT_FALSE(contains(report, "not computed")) << report;
  EXPECT_FALSE(contains(report, "## Failures")) << report;
  EXPECT_TRUE(contains(report, "Table 4.2")) << "the Chang08 bubbling case's reason is missing";
  // The pictures beside the report are PNG files.
  const auto png = read_file(dir.path / "work" / "pictures" / "bubble_orifice_snapshot.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(ValidateQuick, BadArgumentsAreClear) {
  TempDir dir("fluidem_validate_args");
  const Result r = fluidem({"validate", "--quick", "--only", "no_such_case"}, dir.path);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "no run matches")) << r.err;
  EXPECT_TRUE(contains(r.err, "bubble_orifice")) << r.err; // the list of runs
}

} // namespace
