// Time series of scalars (energies, bed height, ...) as CSV: a header line with the column names,
// then one row per call, each flushed at once so that the file can be plotted while a run goes.
// Numbers: an integral value (|v| < 2^53) is written as an integer ("12", not "12.0"); any other
// value with 10 significant digits ("%.10g"); non-finite values as nan, inf, -inf.
//
// Resume (continuing a run from a checkpoint, SeriesWriter::resume): the checkpoint records how
// many bytes the run had written and their FNV-1a hash (mark()); the file must start with those
// very bytes (the run's header and rows up to the checkpoint), else it belongs to another run or
// stops short of the checkpoint (a gap) and is refused. Everything after them (rows written
// after the checkpoint, an incomplete last line left by a crash) is dropped: the kept bytes are
// copied to a temporary file, synced and renamed over the file, which write_row then appends to.
// No file is ever written through a symbolic link.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace fluidem {

class SeriesWriter {
public:
  /// What the file holds so far: its size and the FNV-1a hash of its bytes (for checkpoints).
  struct Mark {
    std::uint64_t bytes = 0;
    std::uint64_t hash = 14695981039346656037ull; ///< FNV-1a offset basis: no bytes
  };
  /// Create `path` (a regular file there is replaced; a link or anything else is refused with
  /// OutputError) and write the header. Column names must be non-empty and must not contain
  /// ',', '"' or a line break (std::invalid_argument). I/O errors: OutputError.
  SeriesWriter(const std::string& path, std::vector<std::string> columns);
  /// Continue the existing file `path` after a restart from a checkpoint whose run had written
  /// `mark`: the file must start with exactly those bytes, beginning with `columns` joined by
  /// ',' (std::runtime_error naming the file and what differs: another header, another run's
  /// rows, fewer bytes than the checkpoint's); later bytes are dropped atomically and write_row
  /// appends from there. `check_only`: only check, and return a closed writer. Bad column
  /// names: std::invalid_argument.
  static SeriesWriter resume(const std::string& path, std::vector<std::string> columns,
                             const Mark& mark, bool check_only = false);
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
  /// The bytes written to the file so far (the header included) and their hash.
  const Mark& mark() const { return mark_; }

  /// How write_row prints one value (exposed for tests).
  static std::string format_value(double v);

private:
  SeriesWriter() = default; // for resume()
  void check_columns() const;
  std::string header() const;
  void write_line();

  std::string path_;
  std::vector<std::string> columns_;
  std::FILE* file_ = nullptr;
  std::string line_; // reused for every row
  std::size_t kept_rows_ = 0;
  Mark mark_;
};

} // namespace fluidem
