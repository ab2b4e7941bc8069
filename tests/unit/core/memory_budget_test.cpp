// The one rule that refuses a case too big for the machine (core/memory_budget.hpp): the shares
// of a run together against the available memory, the error at the key of the largest share
// with its estimate, the whole run's and the machine's. The shares themselves are what runs
// measured (integrate/memory_estimate.cpp); the user-visible refusals (a gas grid, a continuum
// grid) are tested with the real binary in app/bad_input_test.cpp.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "core/memory_budget.hpp"

namespace fluidem {
namespace {

CaseSpec located() {
  CaseSpec spec;
  spec.source_file = "case.toml";
  spec.locations["gas.cells"] = SourceLocation{"case.toml", 12, 1};
  spec.locations["insert[0].count"] = SourceLocation{"case.toml", 7, 1};
  return spec;
}

std::string refusal(const std::vector<MemoryShare>& shares, double available) {
  try {
    require_memory(located(), shares, available);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MemoryBudget, FitsOrNamesTheLargestShare) {
  const std::vector<MemoryShare> shares = {{"insert[0].count", "1e+06 particles", 1e9},
                                           {"gas.cells", "the gas grid of 4e+07 cells", 3e10}};
  EXPECT_EQ(refusal(shares, 4e10), ""); // 31 GB in 40
  EXPECT_EQ(refusal(shares, 3.1e10), "");
  EXPECT_EQ(refusal(shares, 3.0e10),
            "case.toml:12:1: gas.cells: the gas grid of 4e+07 cells needs about 30 GB of memory "
            "(the whole run about 31 GB), this machine has 30 GB (allowed: a case that fits in "
            "the memory)");
}

TEST(MemoryBudget, TheSharesAreSummed) {
  // Each fits alone; together they do not.
  const std::vector<MemoryShare> shares = {{"insert[0].count", "8e+06 particles", 8e9},
                                           {"gas.cells", "the gas grid of 1e+07 cells", 7.5e9}};
  const std::string msg = refusal(shares, 1e10);
  EXPECT_NE(msg.find("insert[0].count: 8e+06 particles needs about 8 GB of memory (the whole run "
                     "about 15.5 GB), this machine has 10 GB"),
            std::string::npos)
      << msg;
}

TEST(MemoryBudget, UnknownMemoryChecksNothingButANaNIsRefused) {
  const std::vector<MemoryShare> huge = {{"gas.cells", "a grid", 1e300}};
  EXPECT_EQ(refusal(huge, 0.0), "");
  EXPECT_NE(refusal({{"gas.cells", "a grid", std::nan("")}}, 1e9), "");
  EXPECT_GT(physical_memory_bytes(), 0.0); // Linux: sysconf(_SC_PHYS_PAGES)
}

TEST(MemoryBudget, FormatBytes) {
  EXPECT_EQ(format_bytes(512.0), "0.512 kB");
  EXPECT_EQ(format_bytes(2.5e6), "2.5 MB");
  EXPECT_EQ(format_bytes(7.5e12), "7.5 TB");
  EXPECT_EQ(format_bytes(3e15), "3e+03 TB");
}

} // namespace
} // namespace fluidem
