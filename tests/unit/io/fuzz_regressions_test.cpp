// Inputs found by fuzz/case_reader_fuzz.cpp (tools/ci-fuzz.sh), kept as regression tests: every
// tests/data/fuzz/*.toml must read as a valid case or give an InputError, never crash or throw
// anything else; a valid one must survive the case.resolved.toml round trip (write, read back,
// write again: the same text). The fuzzer's checks, as a test the normal and ASan builds run.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "io/case_reader.hpp"
#include "io/case_writer.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;

/// What reading a case gave: valid, or the InputError message.
struct Outcome {
  bool valid = false;
  std::string error;
};

/// Reads `text` as the fuzzer does; a valid case must survive the resolved round trip.
Outcome read_like_the_fuzzer(const std::string& text) {
  Outcome out;
  CaseSpec spec;
  try {
    spec = read_case_string(text, "fuzz.toml");
  } catch (const InputError& e) {
    out.error = e.what();
    return out;
  }
  out.valid = true;
  const std::string resolved = write_case_toml(spec);
  CaseSpec again;
  EXPECT_NO_THROW(again = read_case_string(resolved, "fuzz.toml")) << resolved;
  EXPECT_EQ(write_case_toml(again), resolved);
  return out;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<fs::path> fuzz_inputs() {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(FLUIDEM_SOURCE_DIR) / "tests" / "data" / "fuzz";
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".toml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(FuzzRegressions, EveryFoundInputReadsOrGivesAnInputError) {
  const std::vector<fs::path> files = fuzz_inputs();
  ASSERT_FALSE(files.empty());
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.filename().string());
    // Any other exception fails the test; a crash fails it too.
    const Outcome o = read_like_the_fuzzer(slurp(f));
    EXPECT_TRUE(o.valid || !o.error.empty());
  }
}

// Valid to the reader before, then signed integer overflows in particle insertion under
// `fluidem check` (insertion.cpp: 2000 * count attempts; cell coordinates of an infinite width).
TEST(FuzzRegressions, OverflowingCountAndDomainWidthAreInputErrors) {
  const fs::path dir = fs::path(FLUIDEM_SOURCE_DIR) / "tests" / "data" / "fuzz";
  const std::pair<const char*, const char*> cases[] = {
      {"insert_count_int64_max.toml", "insert[0].count: 9223372036854775807 is out of range"},
      {"domain_width_overflows.toml", "domain.hi: the width hi[0] - lo[0]"}};
  for (const auto& [file, message] : cases) {
    SCOPED_TRACE(file);
    const Outcome o = read_like_the_fuzzer(slurp(dir / file));
    EXPECT_FALSE(o.valid);
    EXPECT_NE(o.error.find(message), std::string::npos) << o.error;
  }
}

} // namespace
} // namespace fluidem
