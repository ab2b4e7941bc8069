#include "app/python_scripts.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fluidem {

namespace fs = std::filesystem;

namespace {

std::string python_interpreter() {
  const char* env = std::getenv("FLUIDEM_PYTHON");
  return env != nullptr && env[0] != '\0' ? env : "/usr/bin/python3";
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

} // namespace

fs::path own_binary_path(const char* argv0) {
  std::error_code ec;
  const fs::path self = fs::canonical("/proc/self/exe", ec);
  if (!ec) return self;
  return fs::absolute(argv0 != nullptr ? fs::path(argv0) : fs::path("fluidem"), ec);
}

fs::path find_python_script_dir(const std::string& script, const char* argv0) {
  std::error_code ec;
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("FLUIDEM_PYTHON_DIR")) candidates.emplace_back(env);
  // This file is <source>/src/app/python_scripts.cpp; CMake compiles it by its absolute path.
  candidates.push_back(fs::path(__FILE__).parent_path().parent_path().parent_path() / "python");
  candidates.push_back(own_binary_path(argv0).parent_path() / ".." / "share" / "fluidem" /
                       "python");
  for (const auto& c : candidates)
    if (fs::exists(c / script, ec)) return c;
  std::string list;
  for (const auto& c : candidates) list += "\n  " + c.string();
  throw InputError(fmt::format("cannot find the script {}; looked in:{}\nset FLUIDEM_PYTHON_DIR "
                               "to the python/ folder of the fluidem sources",
                               script, list));
}

int run_python_script(const fs::path& script, const std::vector<std::string>& args) {
  const std::string python = python_interpreter();
  std::string cmd = quote(python) + " " + quote(script.string());
  for (const auto& a : args) cmd += " " + quote(a);
  std::fflush(stdout);
  const int status = std::system(cmd.c_str());
  const int code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : 1;
  if (code != 0)
    fmt::print(stderr, "error: {} failed (exit code {}): {}\n", script.filename().string(), code,
               cmd);
  return code;
}

int exec_python_script(const fs::path& script, const std::vector<std::string>& args) {
  std::vector<std::string> words{python_interpreter(), script.string()};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  ::execv(argv[0], argv.data());
  fmt::print(stderr, "error: cannot run {} with {}: {}\n", script.string(), words[0],
             std::strerror(errno));
  return 127;
}

} // namespace fluidem
