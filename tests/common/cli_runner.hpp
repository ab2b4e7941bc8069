// Running the real fluidem binary (FLUIDEM_BINARY) from a test: a fresh folder per test, the
// command's exit code, stdout and stderr captured through files, and small text helpers.
// Shared by the tests under tests/unit/app/.
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
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

/// Starts `fluidem ARGS...` in `cwd` with stdout/stderr to cwd/.stdout, .stderr; returns the pid.
inline pid_t start_fluidem(const std::vector<std::string>& args, const fs::path& cwd) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(cwd.c_str()) != 0) ::_exit(127);
    const std::string out = (cwd / ".stdout").string(), err = (cwd / ".stderr").string();
    if (!std::freopen(out.c_str(), "w", stdout) || !std::freopen(err.c_str(), "w", stderr))
      ::_exit(127);
    std::vector<char*> argv;
    std::string bin = FLUIDEM_BINARY;
    argv.push_back(bin.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(bin.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

/// Waits for a process of start_fluidem and collects its exit code (-1: killed) and streams.
inline Result finish(pid_t pid, const fs::path& cwd) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  Result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(cwd / ".stdout");
  r.err = read_file(cwd / ".stderr");
  return r;
}

/// The first column (time) of every row of a CSV file.
inline std::vector<double> series_times(const fs::path& csv) {
  std::istringstream in(read_file(csv));
  std::string line;
  std::vector<double> t;
  std::getline(in, line); // header
  while (std::getline(in, line)) t.push_back(std::stod(line.substr(0, line.find(','))));
  return t;
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
