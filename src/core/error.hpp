// Errors that name what was wrong. InputError -> exit code 2, InstabilityError -> exit code 3,
// OutputError -> exit code 4.
#pragma once
#include <stdexcept>
#include <string>

namespace fluidem {

/// Where a value came from: a case file position, or a command-line override.
struct SourceLocation {
  std::string file; ///< case file path, or "--set" for a command-line override
  long line = 0;    ///< 1-based; 0 when unknown
  long column = 0;  ///< 1-based; 0 when unknown
  std::string str() const;
};

/// Bad input: a malformed case file, an unknown key, a value out of range, a bad command line.
/// The message is one sentence: "file:line:col: key: what is wrong (what is allowed)".
class InputError : public std::runtime_error {
public:
  InputError(const SourceLocation& where, const std::string& key, const std::string& what);
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

/// A run that went unstable (NaN, excessive overlap, particle escaping the domain).
class InstabilityError : public std::runtime_error {
public:
  explicit InstabilityError(const std::string& message) : std::runtime_error(message) {}
};

/// An output that could not be written while the run went (a full disk, an I/O error, a file
/// that vanished or became a link): the run stops; the last good checkpoint is kept.
class OutputError : public std::runtime_error {
public:
  explicit OutputError(const std::string& message) : std::runtime_error(message) {}
};

} // namespace fluidem
