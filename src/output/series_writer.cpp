#include "output/series_writer.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
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

SeriesWriter::SeriesWriter(const std::string& path, std::vector<std::string> columns)
    : path_(path), columns_(std::move(columns)) {
  if (columns_.empty()) throw std::invalid_argument("SeriesWriter('" + path_ + "'): no columns");
  for (const auto& c : columns_) {
    if (c.empty() || c.find_first_of(",\"\r\n") != std::string::npos)
      throw std::invalid_argument("SeriesWriter('" + path_ + "'): bad column name '" + c +
                                  "' (must be non-empty, without ',', '\"' or a line break)");
  }
  file_ = std::fopen(path_.c_str(), "wb");
  if (file_ == nullptr)
    throw std::runtime_error("cannot create '" + path_ + "': " + std::strerror(errno));
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i > 0) line_ += ',';
    line_ += columns_[i];
  }
  write_line();
}

SeriesWriter::~SeriesWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

SeriesWriter::SeriesWriter(SeriesWriter&& o) noexcept
    : path_(std::move(o.path_)), columns_(std::move(o.columns_)),
      file_(std::exchange(o.file_, nullptr)), line_(std::move(o.line_)) {}

SeriesWriter& SeriesWriter::operator=(SeriesWriter&& o) noexcept {
  if (this != &o) {
    if (file_ != nullptr) std::fclose(file_);
    path_ = std::move(o.path_);
    columns_ = std::move(o.columns_);
    file_ = std::exchange(o.file_, nullptr);
    line_ = std::move(o.line_);
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
