// Reading the gas-field frames of a fields.h5 file written by FieldsWriter (layout in
// fields_writer.hpp): the grid (cells, lower corner, spacing), the frame times, and frame k of a
// scalar field ([z][y][x], x fastest). Opened read-only without file locking (a live run may be
// appending frames). Every failure throws std::runtime_error naming the file and what is wrong:
// it does not exist, is not HDF5, lacks part of the layout, a field has the wrong shape, or the
// field or frame asked for does not exist.
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace fluidem {

class FieldsReader {
public:
  explicit FieldsReader(const std::string& path);
  ~FieldsReader();
  FieldsReader(FieldsReader&&) noexcept;
  FieldsReader& operator=(FieldsReader&&) noexcept;
  FieldsReader(const FieldsReader&) = delete;
  FieldsReader& operator=(const FieldsReader&) = delete;

  const std::array<int, 3>& cells() const;
  const std::array<double, 3>& lo() const;      ///< m
  const std::array<double, 3>& spacing() const; ///< m
  /// Frames complete in /fields/time and every scalar field (a live run may have extended some).
  std::size_t frames() const;
  const std::vector<double>& times() const; ///< s, frames() of them
  bool has_scalar(const std::string& name) const;
  /// Frame k of /fields/<name> into out (cells[0] cells[1] cells[2] values).
  void read_scalar(const std::string& name, std::size_t k, std::vector<double>& out) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace fluidem
