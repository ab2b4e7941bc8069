// Time series of scalars (energies, bed height, ...) as CSV: a header line with the column names,
// then one row per call, each flushed at once so that the file can be plotted while a run goes.
// Numbers: an integral value (|v| < 2^53) is written as an integer ("12", not "12.0"); any other
// value with 10 significant digits ("%.10g"); non-finite values as nan, inf, -inf.
//
// Resume (continuing a run from a checkpoint, SeriesWriter::resume): the header of the existing
// file must equal the run's columns; the leading rows whose first column (the time) is <= t_keep
// are kept byte for byte, everything after them (rows written after the checkpoint, and an
// incomplete last line left by a crash mid-write) is dropped. The file is rewritten atomically (a
// temporary file next to it, synced, then renamed over it) and write_row appends from there.
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
  /// Continue the existing file `path` after a restart from a checkpoint: check that its header
  /// is `columns` joined by ',' (else std::runtime_error naming the file, with both headers), keep
  /// the leading complete rows whose first column is <= t_keep (the caller passes the checkpoint
  /// time plus half a time step), drop the rest and any incomplete last line (no '\n'), rewrite
  /// the file atomically (`path` + ".resume.tmp", then a rename), and append from there.
  /// std::runtime_error naming the file: it does not exist or cannot be read or rewritten; it has
  /// no complete header line; a complete kept line does not have columns.size() fields or its
  /// first field is not a number (the message gives the line number). Bad column names, NaN
  /// t_keep: std::invalid_argument.
  static SeriesWriter resume(const std::string& path, std::vector<std::string> columns,
                             double t_keep);
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
  /// After resume(): how many data rows were kept (0 for a new file).
  std::size_t kept_rows() const { return kept_rows_; }

  /// How write_row prints one value (exposed for tests).
  static std::string format_value(double v);

private:
  SeriesWriter() = default; // for resume()
  void check_columns() const;
  void write_line();

  std::string path_;
  std::vector<std::string> columns_;
  std::FILE* file_ = nullptr;
  std::string line_; // reused for every row
  std::size_t kept_rows_ = 0;
};

} // namespace fluidem
