#include "output/fields_reader.hpp"
#include "output/hdf5_support.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace fluidem {

using hdf5::check;
using hdf5::check_id;
using hdf5::Handle;

struct FieldsReader::Impl {
  std::string path;
  Handle file;
  std::array<int, 3> cells{};
  std::array<double, 3> lo{}, spacing{};
  std::vector<double> times;
  std::vector<std::string> scalars;

  [[noreturn]] void bad(const std::string& what) const {
    throw std::runtime_error("'" + path + "' is not a readable fluidem field file: " + what);
  }
  bool exists(const std::string& link) const {
    const htri_t e = H5Lexists(file.get(), link.c_str(), H5P_DEFAULT);
    hdf5::hdf5_error_detail(); // clear the stack of a failed lookup
    return e > 0;
  }
  // The frames of a [F][nz][ny][nx] scalar field, after checking its shape.
  std::size_t scalar_frames(const std::string& name) const {
    const std::string full = "/fields/" + name;
    Handle d = hdf5::open_dataset(file.get(), full, path);
    const std::vector<hsize_t> dims = hdf5::extent(d.get(), path, full);
    if (dims.size() != 4 || dims[1] != static_cast<hsize_t>(cells[2]) ||
        dims[2] != static_cast<hsize_t>(cells[1]) || dims[3] != static_cast<hsize_t>(cells[0]))
      bad(full + " does not have the shape [frames][" + std::to_string(cells[2]) + "][" +
          std::to_string(cells[1]) + "][" + std::to_string(cells[0]) + "]");
    return static_cast<std::size_t>(dims[0]);
  }
};

FieldsReader::FieldsReader(const std::string& path) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.path = path;
  m.file = hdf5::open_for_reading(path, "the gas-field frames of a run");
  for (const char* link :
       {"/grid", "/grid/cells", "/grid/lo", "/grid/spacing", "/fields", "/fields/time"})
    if (!m.exists(link)) m.bad(std::string("no ") + link);
  const hid_t f = m.file.get();
  const auto three = [&](const char* name, hid_t type, void* out) {
    Handle d = hdf5::open_dataset(f, name, path);
    if (hdf5::extent(d.get(), path, name) != std::vector<hsize_t>{3})
      m.bad(std::string(name) + " does not hold 3 values");
    check(H5Dread(d.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out), path, "read dataset", name);
  };
  std::int32_t cells[3] = {0, 0, 0};
  three("/grid/cells", H5T_NATIVE_INT32, cells);
  three("/grid/lo", H5T_NATIVE_DOUBLE, m.lo.data());
  three("/grid/spacing", H5T_NATIVE_DOUBLE, m.spacing.data());
  for (int d = 0; d < 3; ++d) {
    if (cells[d] < 1) m.bad("/grid/cells holds " + std::to_string(cells[d]));
    if (!(m.spacing[static_cast<std::size_t>(d)] > 0.0)) m.bad("/grid/spacing is not > 0");
    m.cells[static_cast<std::size_t>(d)] = cells[d];
  }
  Handle fields = hdf5::open_group(f, "/fields", path);
  if (H5Aexists(fields.get(), "scalars") > 0)
    m.scalars = hdf5::read_string_array_attr(fields.get(), "scalars", path);
  hdf5::hdf5_error_detail();
  Handle t = hdf5::open_dataset(f, "/fields/time", path);
  const std::vector<hsize_t> td = hdf5::extent(t.get(), path, "/fields/time");
  if (td.size() != 1) m.bad("/fields/time is not 1-D");
  std::size_t frames = static_cast<std::size_t>(td[0]);
  for (const std::string& s : m.scalars) frames = std::min(frames, m.scalar_frames(s));
  m.times = hdf5::read_all<double>(t.get(), H5T_NATIVE_DOUBLE, static_cast<std::size_t>(td[0]),
                                   path, "/fields/time");
  m.times.resize(frames);
}

FieldsReader::~FieldsReader() = default;
FieldsReader::FieldsReader(FieldsReader&&) noexcept = default;
FieldsReader& FieldsReader::operator=(FieldsReader&&) noexcept = default;

const std::array<int, 3>& FieldsReader::cells() const {
  return impl_->cells;
}
const std::array<double, 3>& FieldsReader::lo() const {
  return impl_->lo;
}
const std::array<double, 3>& FieldsReader::spacing() const {
  return impl_->spacing;
}
std::size_t FieldsReader::frames() const {
  return impl_->times.size();
}
const std::vector<double>& FieldsReader::times() const {
  return impl_->times;
}
bool FieldsReader::has_scalar(const std::string& name) const {
  return std::find(impl_->scalars.begin(), impl_->scalars.end(), name) != impl_->scalars.end();
}

void FieldsReader::read_scalar(const std::string& name, std::size_t k,
                               std::vector<double>& out) const {
  const Impl& m = *impl_;
  if (!has_scalar(name)) m.bad("no scalar field '" + name + "'");
  if (k >= frames())
    m.bad("frame " + std::to_string(k) + " asked for, " + std::to_string(frames()) + " held");
  const std::string full = "/fields/" + name;
  Handle d = hdf5::open_dataset(m.file.get(), full, m.path);
  const hsize_t nz = static_cast<hsize_t>(m.cells[2]), ny = static_cast<hsize_t>(m.cells[1]),
                nx = static_cast<hsize_t>(m.cells[0]);
  out.assign(static_cast<std::size_t>(nx * ny * nz), 0.0);
  const hsize_t start[4] = {k, 0, 0, 0}, count[4] = {1, nz, ny, nx};
  Handle space{check_id(H5Dget_space(d.get()), m.path, "get dataspace of", full), H5Sclose};
  check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr), m.path,
        "select frame in", full);
  const hsize_t mem_dims[3] = {nz, ny, nx};
  Handle mem{check_id(H5Screate_simple(3, mem_dims, nullptr), m.path, "create dataspace"),
             H5Sclose};
  check(H5Dread(d.get(), H5T_NATIVE_DOUBLE, mem.get(), space.get(), H5P_DEFAULT, out.data()),
        m.path, "read frame of", full);
}

} // namespace fluidem
