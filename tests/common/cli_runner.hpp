// Running the real fluidem binary (FLUIDEM_BINARY) from a test: a fresh folder per test, the
// command's exit code, stdout and stderr captured through files, and small text helpers.
// Shared by the tests under tests/unit/app/.
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>
#include <vector>

namespace fluidem::test {

namespace fs = std::filesystem;

/// A fresh folder per test (tests may run in parallel under ctest -j), removed afterwards.
struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& prefix = "fluidem_cli") {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path = fs::temp_directory_path() / (prefix + "_" + std::string(info->test_suite_name()) + "_" +
                                        info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = path / name;
    std::ofstream(p) << text;
    return p;
  }
};

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Single-quoted for /bin/sh.
inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct Result {
  int code = -1;
  std::string out, err;
};

/// Runs a shell command in `cwd`, capturing both streams through files.
inline Result run_command(const std::string& command, const fs::path& cwd) {
  const fs::path out = cwd / ".stdout", err = cwd / ".stderr";
  const std::string cmd = "cd " + quote(cwd.string()) + " && " + command + " > " +
                          quote(out.string()) + " 2> " + quote(err.string());
  const int status = std::system(cmd.c_str());
  Result r;
  r.code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

/// Runs `fluidem ARGS...` in `cwd`.
inline Result fluidem(const std::vector<std::string>& args, const fs::path& cwd) {
  std::string cmd = quote(FLUIDEM_BINARY);
  for (const auto& a : args) cmd += " " + quote(a);
  return run_command(cmd, cwd);
}

inline bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

/// `text` with the first `from` replaced by `to` (a test failure if `from` is missing).
inline std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "not in the text: " << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

} // namespace fluidem::test
