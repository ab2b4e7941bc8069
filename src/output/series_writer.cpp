#include "output/series_writer.hpp"

#include "output/safe_file.hpp"

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
  // A new file: whatever regular file was there goes, a link is refused (never written through).
  const safe_file::Kind kind = safe_file::kind(path_);
  if (kind != safe_file::Kind::missing && kind != safe_file::Kind::regular)
    throw OutputError("cannot create '" + path_ + "': it is " + safe_file::to_string(kind) +
                      " (fluidem does not write through links or over other files)");
  file_ = safe_file::create_exclusive(path_);
  line_ = header();
  write_line();
}

std::string SeriesWriter::header() const {
  std::string h;
  for (std::size_t i = 0; i < columns_.size(); ++i) h += (i > 0 ? "," : "") + columns_[i];
  return h;
}

SeriesWriter SeriesWriter::resume(const std::string& path, std::vector<std::string> columns,
                                  const Mark& mark, bool check_only) {
  SeriesWriter w;
  w.path_ = path;
  w.columns_ = std::move(columns);
  w.check_columns();
  const std::string who = "cannot continue '" + path + "'";
  std::string text;
  try {
    text = safe_file::read_all(path);
  } catch (const OutputError& e) {
    throw std::runtime_error(who + ": " + e.what());
  }
  const std::string header = w.header() + "\n";
  if (text.compare(0, header.size(), header) != 0) {
    const std::string first = text.substr(0, text.find('\n'));
    throw std::runtime_error(who + ": its header '" + first + "' is not the run's, '" + w.header() +
                             "'");
  }
  if (text.size() < mark.bytes) {
    const std::size_t last = text.rfind('\n', text.empty() ? 0 : text.size() - 2);
    const std::string last_row = text.substr(last == std::string::npos ? 0 : last + 1);
    throw std::runtime_error(who + ": it holds " + std::to_string(text.size()) +
                             " bytes (its last row '" + last_row.substr(0, last_row.find('\n')) +
                             "'), the checkpoint's run had written " + std::to_string(mark.bytes) +
                             ": the outputs do not reach the checkpoint, continuing them would "
                             "leave a gap");
  }
  if (mark.bytes < header.size() ||
      safe_file::fnv1a(std::string_view(text).substr(0, mark.bytes)) != mark.hash ||
      text[mark.bytes - 1] != '\n')
    throw std::runtime_error(who + ": its rows up to the checkpoint are not those the "
                                   "checkpoint's run wrote (the file holds another run's rows)");
  if (check_only) return SeriesWriter();
  try {
    safe_file::cut(path, mark.bytes); // atomically: a copy of the kept rows renamed over it
    w.file_ = safe_file::open_append(path);
  } catch (const OutputError& e) {
    throw std::runtime_error(who + ": " + e.what());
  }
  w.mark_ = mark;
  w.kept_rows_ = static_cast<std::size_t>(
      std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(mark.bytes), '\n') - 1);
  return w;
}

SeriesWriter::~SeriesWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

SeriesWriter::SeriesWriter(SeriesWriter&& o) noexcept
    : path_(std::move(o.path_)), columns_(std::move(o.columns_)),
      file_(std::exchange(o.file_, nullptr)), line_(std::move(o.line_)), kept_rows_(o.kept_rows_),
      mark_(o.mark_) {}

SeriesWriter& SeriesWriter::operator=(SeriesWriter&& o) noexcept {
  if (this != &o) {
    if (file_ != nullptr) std::fclose(file_);
    path_ = std::move(o.path_);
    columns_ = std::move(o.columns_);
    file_ = std::exchange(o.file_, nullptr);
    line_ = std::move(o.line_);
    kept_rows_ = o.kept_rows_;
    mark_ = o.mark_;
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
  safe_file::write_all(file_, line_, path_);
  mark_.bytes += line_.size();
  mark_.hash = safe_file::fnv1a(line_, mark_.hash);
}

void SeriesWriter::close() {
  if (file_ == nullptr) return;
  std::FILE* f = std::exchange(file_, nullptr);
  if (std::fclose(f) != 0)
    throw OutputError("cannot close '" + path_ + "': " + std::strerror(errno));
}

} // namespace fluidem
