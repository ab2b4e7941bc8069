// The InputError of reading a case text, for the tests of the case reader's keys.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/case_reader.hpp"

namespace fluidem::test {

/// The InputError message of reading `text` as "case.toml" (with `overrides` as --set gives
/// them), or "" and a test failure if it reads. The message must be one line (the CLI prints it
/// as one).
inline std::string error_of(const std::string& text,
                            const std::vector<std::string>& overrides = {}) {
  try {
    (void)read_case_string(text, "case.toml", overrides);
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "message is not one line: " << msg;
    return msg;
  }
  ADD_FAILURE() << "expected an InputError for:\n" << text;
  return "";
}

} // namespace fluidem::test
