// `coupling.smoothing_length` (docs/case-file.md, docs/smoothing.md): absent = 0 (off); a length
// in m from 0 up to the domain's largest extent is read exactly and written back to the resolved
// case (only when on, so that a case without it resolves as before); a negative value, nan, inf,
// a value beyond the domain's largest extent (0.5 m here) and a string are each one InputError
// at the key's line naming the key and what is allowed.
#include <gtest/gtest.h>
#include <string>

#include "core/error.hpp"
#include "io/case_reader.hpp"
#include "io/case_writer.hpp"

#include "../../common/case_error.hpp"

namespace fluidem {
namespace {

// A 2-D coupled bed, 0.15 m wide, 15 mm deep, 0.5 m tall: largest extent 0.5 m.
const std::string kCase = R"([simulation]
dimension = 2
end_time = 1.0

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.15, 0.015, 0.5]

[[species]]
name = "glass"
diameter = 0.0025
density = 2500.0

[[insert]]
species = "glass"
count = 2000

[gas]
cells = [30, 1, 100]
)";

std::string with_key(const std::string& value) {
  return kCase + "\n[coupling]\nsmoothing_length = " + value + "\n";
}

using fluidem::test::error_of;

TEST(SmoothingKey, AbsentIsOffAndNotWritten) {
  const CaseSpec c = read_case_string(kCase, "case.toml");
  EXPECT_EQ(c.coupling.smoothing_length, 0.0);
  EXPECT_EQ(write_case_toml(c).find("smoothing_length"), std::string::npos);
}

TEST(SmoothingKey, ReadAndRoundTrip) {
  for (const std::string v : {"0.01", "0", "0.5", "3e-3"}) {
    SCOPED_TRACE(v);
    const CaseSpec c = read_case_string(with_key(v), "case.toml");
    EXPECT_EQ(c.coupling.smoothing_length, std::stod(v));
    const CaseSpec r = read_case_string(write_case_toml(c), "case.resolved.toml");
    EXPECT_EQ(r.coupling.smoothing_length, c.coupling.smoothing_length);
  }
}

TEST(SmoothingKey, BadValuesAreInputErrorsAtTheKey) {
  // The key's line in with_key(): the last line of the text.
  const std::string text = with_key("1");
  long line = 0;
  for (char ch : text) line += ch == '\n';
  const std::string where = "case.toml:" + std::to_string(line) + ":";
  const std::string allowed =
      "(allowed: 0 (off) or a length in m up to the domain's largest extent, 0.5 m";
  for (const std::string v : {"-0.001", "nan", "inf", "-inf", "0.51", "1"}) {
    SCOPED_TRACE(v);
    const std::string msg = error_of(with_key(v));
    EXPECT_EQ(msg.rfind(where, 0), 0u) << msg;
    EXPECT_NE(msg.find(": coupling.smoothing_length: "), std::string::npos) << msg;
    EXPECT_NE(msg.find("is out of range " + allowed), std::string::npos) << msg;
  }
  const std::string msg = error_of(with_key("\"0.01\""));
  EXPECT_NE(msg.find(": coupling.smoothing_length: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected a number"), std::string::npos) << msg;
}

} // namespace
} // namespace fluidem
