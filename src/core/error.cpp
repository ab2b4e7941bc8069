#include "core/error.hpp"

namespace fluidem {

std::string SourceLocation::str() const {
  std::string s = file.empty() ? std::string("<case>") : file;
  if (line > 0) {
    s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
  }
  return s;
}

InputError::InputError(const SourceLocation& where, const std::string& key, const std::string& what)
    : std::runtime_error(where.str() + ": " + (key.empty() ? std::string() : key + ": ") + what) {}

} // namespace fluidem
