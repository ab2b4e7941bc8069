// libFuzzer target for the case-file reader: the input bytes are a case file. It is read and
// validated as `fluidem check` does before it builds the Simulation (read_case_string: TOML
// parse + every key and range check + gas::validate), then written back as case.resolved.toml
// and read again, which must give the same case (case_writer.hpp's promise).
//
// InputError is the expected outcome for bad input. Anything else is a finding: another
// exception, a failed round trip (both abort here), a crash, a sanitizer report, a hang.
//
// The Simulation is not built: it inserts the particles and allocates the gas grid (a fuzzed
// case asks for 1e9 particles or 1e6^3 cells), and it would pull hypre, MPI and HDF5 into the
// instrumented build. Run: tools/ci-fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "core/error.hpp"
#include "io/case_reader.hpp"
#include "io/case_writer.hpp"

namespace {

/// Longer inputs are not interesting for a case file and only slow the search down.
constexpr std::size_t kMaxInputBytes = 64 * 1024;

/// The name the case is read under; relative insert file paths resolve against the current
/// folder.
constexpr const char* kSourceName = "fuzz.toml";

[[noreturn]] void finding(const char* what, const std::string& detail) {
  std::fprintf(stderr, "case_reader_fuzz: %s\n%s\n", what, detail.c_str());
  std::abort();
}

/// Reads `text`; true with `out` set when it is a valid case, false on InputError. Any other
/// exception is a finding.
bool read(const std::string& text, fluidem::CaseSpec& out) {
  try {
    out = fluidem::read_case_string(text, kSourceName);
    return true;
  } catch (const fluidem::InputError&) {
    return false;
  } catch (const std::exception& e) {
    finding("exception other than InputError", e.what());
  } catch (...) {
    finding("exception other than InputError", "(not a std::exception)");
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxInputBytes) return -1; // not added to the corpus
  const std::string text(reinterpret_cast<const char*>(data), size);
  fluidem::CaseSpec spec;
  if (!read(text, spec)) return 0;

  // A valid case: its resolved form must read back to the same case.
  std::string resolved;
  try {
    resolved = fluidem::write_case_toml(spec);
  } catch (const std::exception& e) {
    finding("write_case_toml threw on a valid case", e.what());
  }
  fluidem::CaseSpec again;
  try {
    again = fluidem::read_case_string(resolved, kSourceName);
  } catch (const std::exception& e) {
    finding("the resolved case does not read back", std::string(e.what()) + "\n" + resolved);
  }
  const std::string twice = fluidem::write_case_toml(again);
  if (twice != resolved)
    finding("the resolved case reads back to a different case",
            "first:\n" + resolved + "\nsecond:\n" + twice);
  return 0;
}
