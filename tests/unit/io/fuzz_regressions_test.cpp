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

// Issue 32, item 10: an insert file that is a directory or a device was "file not found". (The
// other inputs of items 9-10 in the corpus read as valid cases: what they ask for is refused
// when the run is set up, app/bad_input_test.cpp.)
TEST(FuzzRegressions, InsertFileThatIsNotARegularFileSaysWhatItIs) {
  const fs::path dir = fs::path(FLUIDEM_SOURCE_DIR) / "tests" / "data" / "fuzz";
  const std::pair<const char*, const char*> cases[] = {
      {"insert_file_directory.toml", "is a directory, not a file (allowed: a LAMMPS data file"},
      {"insert_file_dev_zero.toml",
       "insert[0].file: /dev/zero is a character device, not a regular file"}};
  for (const auto& [file, message] : cases) {
    SCOPED_TRACE(file);
    const Outcome o = read_like_the_fuzzer(slurp(dir / file));
    EXPECT_FALSE(o.valid);
    EXPECT_NE(o.error.find(message), std::string::npos) << o.error;
  }
  for (const char* file : {"memory_gas_cells_1e10.toml", "memory_continuum_cells_1e10.toml",
                           "memory_domain_1000m_cell_grid.toml", "species_1000_unused.toml",
                           "insert_random_100000_discs.toml", "species_diameter_1e-300.toml",
                           "contact_stiffness_1e300.toml"}) {
    SCOPED_TRACE(file);
    EXPECT_TRUE(read_like_the_fuzzer(slurp(dir / file)).valid);
  }
}

} // namespace
} // namespace fluidem
