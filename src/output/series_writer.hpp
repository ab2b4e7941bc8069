// Time series of scalars (energies, bed height, ...) as CSV: a header line with the column names,
// then one row per call, each flushed at once so that the file can be plotted while a run goes.
// Numbers: an integral value (|v| < 2^53) is written as an integer ("12", not "12.0"); any other
// value with 10 significant digits ("%.10g"); non-finite values as nan, inf, -inf.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

namespace fluidem {

class SeriesWriter {
public:
  /// Create (truncate) `path` and write the header. Column names must be non-empty and must not
  /// contain ',', '"' or a line break (std::invalid_argument). I/O errors: std::runtime_error.
  SeriesWriter(const std::string& path, std::vector<std::string> columns);
  ~SeriesWriter();
  SeriesWriter(SeriesWriter&& other) noexcept;
  SeriesWriter& operator=(SeriesWriter&& other) noexcept;
  SeriesWriter(const SeriesWriter&) = delete;
  SeriesWriter& operator=(const SeriesWriter&) = delete;

  /// One row; values.size() must equal columns().size() (std::invalid_argument).
  void write_row(const std::vector<double>& values);
  /// Close now, reporting a failed close as std::runtime_error. Idempotent.
  void close();

  const std::vector<std::string>& columns() const { return columns_; }
  const std::string& path() const { return path_; }

  /// How write_row prints one value (exposed for tests).
  static std::string format_value(double v);

private:
  void write_line();

  std::string path_;
  std::vector<std::string> columns_;
  std::FILE* file_ = nullptr;
  std::string line_; // reused for every row
};

} // namespace fluidem
