#include "app/analysis_table.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fluidem {

int Table::column(const std::string& name) const {
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c] == name) return static_cast<int>(c);
  return -1;
}

Table read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in)
    throw InputError(fmt::format("cannot read '{}': {}", path.string(), std::strerror(errno)));
  Table t;
  std::string line;
  if (!std::getline(in, line)) throw InputError(fmt::format("'{}' is empty", path.string()));
  {
    std::istringstream h(line);
    std::string c;
    while (std::getline(h, c, ',')) t.columns.push_back(c);
  }
  if (t.columns.empty() || t.columns[0] != "time")
    throw InputError(fmt::format("'{}': the first column is not 'time'", path.string()));
  t.data.resize(t.columns.size());
  for (long n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    std::vector<double> row;
    const char* s = line.c_str();
    while (true) {
      char* end = nullptr;
      row.push_back(std::strtod(s, &end));
      if (end == s) break;
      s = end;
      if (*s != ',') break;
      ++s;
    }
    if (row.size() != t.columns.size() || *s != '\0') {
      if (in.peek() == EOF) break; // an incomplete last line of a live run
      throw InputError(
          fmt::format("'{}' line {}: not {} numbers", path.string(), n, t.columns.size()));
    }
    for (std::size_t c = 0; c < row.size(); ++c) t.data[c].push_back(row[c]);
  }
  return t;
}

std::ofstream open_out(const std::filesystem::path& p) {
  std::ofstream f(p);
  if (!f) throw InputError(fmt::format("cannot write '{}': {}", p.string(), std::strerror(errno)));
  return f;
}

std::string g(double v) {
  return fmt::format("{:.10g}", v);
}

} // namespace fluidem
