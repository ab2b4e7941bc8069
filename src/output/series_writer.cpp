#include "output/series_writer.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace fluidem {

namespace {

constexpr double kExactIntegerLimit = 9007199254740992.0; // 2^53

// Append the text of v to out without allocating (beyond out's own growth).
void append_value(std::string& out, double v) {
  char buf[40];
  int len = 0;
  if (std::isnan(v)) {
    len = std::snprintf(buf, sizeof buf, "nan");
  } else if (std::isinf(v)) {
    len = std::snprintf(buf, sizeof buf, v > 0 ? "inf" : "-inf");
  } else if (v == std::trunc(v) && std::fabs(v) < kExactIntegerLimit) {
    len = std::snprintf(buf, sizeof buf, "%lld", static_cast<long long>(v));
  } else {
    len = std::snprintf(buf, sizeof buf, "%.10g", v);
  }
  out.append(buf, static_cast<std::size_t>(len));
}

} // namespace

std::string SeriesWriter::format_value(double v) {
  std::string s;
  append_value(s, v);
  return s;
}

void SeriesWriter::check_columns() const {
  if (columns_.empty()) throw std::invalid_argument("SeriesWriter('" + path_ + "'): no columns");
  for (const auto& c : columns_) {
    if (c.empty() || c.find_first_of(",\"\r\n") != std::string::npos)
      throw std::invalid_argument("SeriesWriter('" + path_ + "'): bad column name '" + c +
                                  "' (must be non-empty, without ',', '\"' or a line break)");
  }
}

SeriesWriter::SeriesWriter(const std::string& path, std::vector<std::string> columns)
    : path_(path), columns_(std::move(columns)) {
  check_columns();
  file_ = std::fopen(path_.c_str(), "wb");
  if (file_ == nullptr)
    throw std::runtime_error("cannot create '" + path_ + "': " + std::strerror(errno));
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i > 0) line_ += ',';
    line_ += columns_[i];
  }
  write_line();
}

SeriesWriter SeriesWriter::resume(const std::string& path, std::vector<std::string> columns,
                                  double t_keep) {
  SeriesWriter w;
  w.path_ = path;
  w.columns_ = std::move(columns);
  w.check_columns();
  const std::string who = "SeriesWriter::resume('" + path + "')";
  if (std::isnan(t_keep)) throw std::invalid_argument(who + ": t_keep is NaN");

  std::string text;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(who + ": cannot read the file: " + std::strerror(errno));
    std::ostringstream s;
    s << in.rdbuf();
    if (in.bad()) throw std::runtime_error(who + ": cannot read the file");
    text = std::move(s).str();
  }
  std::string header;
  for (std::size_t i = 0; i < w.columns_.size(); ++i) header += (i > 0 ? "," : "") + w.columns_[i];
  const std::size_t header_end = text.find('\n');
  if (header_end == std::string::npos)
    throw std::runtime_error(who + ": the file has no complete header line");
  if (text.compare(0, header_end, header) != 0)
    throw std::runtime_error(who + ": the header does not match the run: '" +
                             text.substr(0, header_end) + "' in the file, '" + header +
                             "' in the run");

  // Keep whole lines up to the first row later than t_keep; a last line without '\n' is a row
  // cut short by a crash and goes too.
  std::size_t keep_end = header_end + 1;
  std::size_t line_number = 1;
  while (keep_end < text.size()) {
    const std::size_t eol = text.find('\n', keep_end);
    if (eol == std::string::npos) break; // incomplete last line
    ++line_number;
    const std::string_view line(text.data() + keep_end, eol - keep_end);
    const std::size_t fields =
        static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
    const std::string first(line.substr(0, line.find(',')));
    char* end = nullptr;
    const double t = first.empty() ? 0.0 : std::strtod(first.c_str(), &end);
    if (fields != w.columns_.size() || first.empty() || end != first.c_str() + first.size())
      throw std::runtime_error(who + ": line " + std::to_string(line_number) + " is not a row of " +
                               std::to_string(w.columns_.size()) + " numbers: '" +
                               std::string(line) + "'");
    if (!(t <= t_keep)) break;
    keep_end = eol + 1;
    ++w.kept_rows_;
  }

  // Rewrite atomically: the kept part into a temporary file, synced, renamed over the original;
  // the temporary's stream then goes on appending.
  const std::string tmp = path + ".resume.tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr)
    throw std::runtime_error(who + ": cannot create '" + tmp + "': " + std::strerror(errno));
  const bool ok = std::fwrite(text.data(), 1, keep_end, f) == keep_end && std::fflush(f) == 0 &&
                  ::fsync(::fileno(f)) == 0;
  const int write_errno = errno;
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int e = ok ? errno : write_errno;
    std::fclose(f);
    std::remove(tmp.c_str());
    throw std::runtime_error(who + ": cannot rewrite the file: " + std::strerror(e));
  }
  w.file_ = f;
  return w;
}

SeriesWriter::~SeriesWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

SeriesWriter::SeriesWriter(SeriesWriter&& o) noexcept
    : path_(std::move(o.path_)), columns_(std::move(o.columns_)),
      file_(std::exchange(o.file_, nullptr)), line_(std::move(o.line_)), kept_rows_(o.kept_rows_) {}

SeriesWriter& SeriesWriter::operator=(SeriesWriter&& o) noexcept {
  if (this != &o) {
    if (file_ != nullptr) std::fclose(file_);
    path_ = std::move(o.path_);
    columns_ = std::move(o.columns_);
    file_ = std::exchange(o.file_, nullptr);
    line_ = std::move(o.line_);
    kept_rows_ = o.kept_rows_;
  }
  return *this;
}

void SeriesWriter::write_row(const std::vector<double>& values) {
  if (file_ == nullptr) throw std::logic_error("SeriesWriter('" + path_ + "'): write after close");
  if (values.size() != columns_.size())
    throw std::invalid_argument("SeriesWriter('" + path_ + "'): row has " +
                                std::to_string(values.size()) + " values, expected " +
                                std::to_string(columns_.size()));
  line_.clear();
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) line_ += ',';
    append_value(line_, values[i]);
  }
  write_line();
}

void SeriesWriter::write_line() {
  line_ += '\n';
  if (std::fwrite(line_.data(), 1, line_.size(), file_) != line_.size() || std::fflush(file_) != 0)
    throw std::runtime_error("cannot write '" + path_ + "': " + std::strerror(errno));
}

void SeriesWriter::close() {
  if (file_ == nullptr) return;
  std::FILE* f = std::exchange(file_, nullptr);
  if (std::fclose(f) != 0)
    throw std::runtime_error("cannot close '" + path_ + "': " + std::strerror(errno));
}

} // namespace fluidem
