// The small file helpers of `fluidem analyse`: a CSV of numbers as written by SeriesWriter
// (series.csv, probes.csv), the rows of summary.csv, and number formatting.
#pragma once
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fluidem {

/// A CSV whose first column is `time`: a header line, then rows of numbers.
struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> data; ///< data[column][row]
  /// Index of column `name`, or -1.
  int column(const std::string& name) const;
};

/// Read a CSV written by SeriesWriter. An incomplete last line (a live run) is left out; any
/// other malformed line, a missing file or a first column other than `time` is an InputError.
Table read_csv(const std::filesystem::path& path);

/// One row of OUT/analysis/summary.csv.
struct SummaryRow {
  std::string name;
  double value;
  std::string unit;
};

/// Open `p` for writing; InputError naming it when that fails.
std::ofstream open_out(const std::filesystem::path& p);

/// A number with 10 significant digits, as every analysis file writes them.
std::string g(double v);

} // namespace fluidem
