#include "output/fields_writer.hpp"
#include "output/hdf5_support.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <utility>

// H5Pset_file_locking exists from 1.10.7 on the 1.10 branch and from 1.12.1 on.
#if H5_VERS_MAJOR > 1 || (H5_VERS_MAJOR == 1 && H5_VERS_MINOR >= 13) ||                            \
    (H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 12 && H5_VERS_RELEASE >= 1) ||                         \
    (H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 10 && H5_VERS_RELEASE >= 7)
#define FLUIDEM_HAVE_H5P_FILE_LOCKING 1
#endif

namespace fluidem {

namespace {

// Largest chunk of a field dataset. A whole frame up to this size is one chunk, written straight
// to disk (it is larger than HDF5's default 1 MiB chunk cache) without compression.
constexpr std::size_t kChunkCapBytes = std::size_t{16} << 20;
constexpr hsize_t kStepChunk = 512; // step/time: 4 KiB chunks

using hdf5::append_frame;
using hdf5::Builder;
using hdf5::check;
using hdf5::check_id;
using hdf5::fail;
using hdf5::Handle;

} // namespace

void check_field_grid(const FieldGrid& g, const std::string& who) {
  static const char* const axis = "xyz";
  for (int d = 0; d < 3; ++d) {
    const std::string a(1, axis[d]);
    if (g.cells[d] < 1)
      throw std::invalid_argument(who + ": the grid needs at least one cell along " + a + ", not " +
                                  std::to_string(g.cells[d]));
    if (!std::isfinite(g.lo[d]))
      throw std::invalid_argument(who + ": the grid's lower corner along " + a + " is not finite");
    if (!std::isfinite(g.spacing[d]) || !(g.spacing[d] > 0.0))
      throw std::invalid_argument(who + ": the grid spacing along " + a +
                                  " must be finite and > 0");
  }
}

void check_field_names(const std::vector<std::string>& scalar_names,
                       const std::vector<std::string>& vector_names, const std::string& who) {
  std::set<std::string> seen;
  for (const auto* names : {&scalar_names, &vector_names}) {
    for (const std::string& name : *names) {
      if (name.empty()) throw std::invalid_argument(who + ": empty field name");
      if (name == "step" || name == "time" || name == "." || name == "..")
        throw std::invalid_argument(who + ": '" + name + "' cannot be a field name");
      for (const char c : name) {
        if (c == '/' || c == ':' || c == '|' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
          throw std::invalid_argument(who + ": field name '" + name +
                                      "' contains '/', ':', '|' or a control character");
      }
      if (!seen.insert(name).second)
        throw std::invalid_argument(who + ": field name '" + name + "' given twice");
    }
  }
}

struct FieldsWriter::Impl {
  std::string path;
  FieldGrid grid;
  std::vector<std::string> scalar_names;
  std::vector<std::string> vector_names;
  std::size_t frames = 0;
  bool closed = false;
  hsize_t inner_scalar[3] = {0, 0, 0}; // nz, ny, nx
  hsize_t inner_vector[4] = {0, 0, 0, 3};
  // Declaration order = reverse close order: the file is closed last.
  Handle file;
  Handle frames_attr;
  Handle step;
  Handle time;
  std::vector<Handle> scalars;
  std::vector<Handle> vectors;
  Handle mem_scalar;              // [1][nz][ny][nx]
  Handle mem_vector;              // [1][nz][ny][nx][3]
  Handle mem_one;                 // [1]
  std::vector<double> buffer;     // interleaved xyz, reused every frame
  std::vector<double> kept_times; // resume only

  void init_memory() {
    const Builder b{path};
    const hsize_t nx = static_cast<hsize_t>(grid.cells[0]);
    const hsize_t ny = static_cast<hsize_t>(grid.cells[1]);
    const hsize_t nz = static_cast<hsize_t>(grid.cells[2]);
    inner_scalar[0] = inner_vector[0] = nz;
    inner_scalar[1] = inner_vector[1] = ny;
    inner_scalar[2] = inner_vector[2] = nx;
    // Memory spaces of the frame's own shape: HDF5 then copies whole rows, not element by element.
    const hsize_t scalar_dims[4] = {1, nz, ny, nx};
    const hsize_t vector_dims[5] = {1, nz, ny, nx, 3};
    const hsize_t one_dims[1] = {1};
    mem_scalar = b.simple_space(4, scalar_dims);
    mem_vector = b.simple_space(5, vector_dims);
    mem_one = b.simple_space(1, one_dims);
    if (!vector_names.empty()) buffer.resize(3 * nx * ny * nz);
  }

  herr_t close_all() {
    herr_t status = 0;
    for (Handle* h : {&mem_one, &mem_vector, &mem_scalar}) status = std::min(status, h->reset());
    for (auto& v : vectors) status = std::min(status, v.reset());
    for (auto& s : scalars) status = std::min(status, s.reset());
    for (Handle* h : {&time, &step, &frames_attr, &file}) status = std::min(status, h->reset());
    closed = true;
    return status;
  }
  ~Impl() { close_all(); }
};

FieldsWriter::FieldsWriter(const std::string& path, const FieldGrid& grid,
                           std::vector<std::string> scalar_names,
                           std::vector<std::string> vector_names,
                           const std::string& program_version, const std::string& run_id)
    : impl_(std::make_unique<Impl>()) {
  const std::string who = "FieldsWriter('" + path + "')";
  check_field_grid(grid, who);
  check_field_names(scalar_names, vector_names, who);
  // Errors are reported by exceptions; keep HDF5 from dumping its stack on stderr.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);

  Impl& m = *impl_;
  m.path = path;
  m.grid = grid;
  m.scalar_names = std::move(scalar_names);
  m.vector_names = std::move(vector_names);
  const hsize_t nx = static_cast<hsize_t>(grid.cells[0]);
  const hsize_t ny = static_cast<hsize_t>(grid.cells[1]);
  const hsize_t nz = static_cast<hsize_t>(grid.cells[2]);
  m.inner_scalar[0] = m.inner_vector[0] = nz;
  m.inner_scalar[1] = m.inner_vector[1] = ny;
  m.inner_scalar[2] = m.inner_vector[2] = nx;
  const Builder b{m.path};

  Handle fapl{check_id(H5Pcreate(H5P_FILE_ACCESS), path, "create property list"), H5Pclose};
#ifdef FLUIDEM_HAVE_H5P_FILE_LOCKING
  // No lock: a viewer may open the file while the run appends frames; every frame is flushed.
  check(H5Pset_file_locking(fapl.get(), false, true), path, "disable file locking");
#endif
  m.file = hdf5::create_file(path, fapl.get());
  const hid_t f = m.file.get();
  b.string_attr(f, "creator", "fluidem");
  b.string_attr(f, "version", program_version);
  if (!run_id.empty()) b.string_attr(f, "run_id", run_id);

  { // /grid
    Handle g = b.group(f, "grid");
    const std::int32_t cells[3] = {grid.cells[0], grid.cells[1], grid.cells[2]};
    b.fixed_dataset(g.get(), "cells", H5T_STD_I32LE, H5T_NATIVE_INT32, 3, cells);
    b.fixed_dataset(g.get(), "lo", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, grid.lo.data());
    b.fixed_dataset(g.get(), "spacing", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, grid.spacing.data());
  }

  Handle fields = b.group(f, "fields");
  const std::int64_t zero = 0;
  m.frames_attr = b.scalar_attr(fields.get(), "frames", H5T_STD_I64LE, H5T_NATIVE_INT64, &zero);
  if (!m.scalar_names.empty()) b.string_array_attr(fields.get(), "scalars", m.scalar_names);
  if (!m.vector_names.empty()) b.string_array_attr(fields.get(), "vectors", m.vector_names);
  {
    const hsize_t chunk[1] = {kStepChunk};
    m.step = b.extendible(fields.get(), "step", H5T_STD_I64LE, 1, nullptr, chunk);
    m.time = b.extendible(fields.get(), "time", H5T_IEEE_F64LE, 1, nullptr, chunk);
    b.string_attr(m.time.get(), "unit", "s");
  }
  // Chunk: one frame, or as many whole x-y planes of it as fit in kChunkCapBytes.
  const auto planes = [&](hsize_t components) {
    const hsize_t plane_bytes = nx * ny * components * sizeof(double);
    return std::clamp<hsize_t>(kChunkCapBytes / plane_bytes, 1, nz);
  };
  for (const std::string& name : m.scalar_names) {
    const hsize_t chunk[4] = {1, planes(1), ny, nx};
    m.scalars.push_back(
        b.extendible(fields.get(), name.c_str(), H5T_IEEE_F64LE, 4, m.inner_scalar, chunk));
  }
  for (const std::string& name : m.vector_names) {
    const hsize_t chunk[5] = {1, planes(3), ny, nx, 3};
    m.vectors.push_back(
        b.extendible(fields.get(), name.c_str(), H5T_IEEE_F64LE, 5, m.inner_vector, chunk));
  }

  m.init_memory();
  flush();
}

FieldsWriter::FieldsWriter() : impl_(std::make_unique<Impl>()) {}

namespace {

// Checks the open file `f` against the run (grid, names, run id) and opens its time-dependent
// datasets into `m` (whose path, grid and names are set); returns how many frames every one of
// them holds complete, and sets `longest` to the most any of them holds.
hsize_t open_layout(FieldsWriter::Impl& m, hid_t f, const std::string& who,
                    const std::string& run_id, hsize_t& longest) {
  const std::string& path = m.path;
  const FieldGrid& grid = m.grid;
  const auto mismatch = [&](const std::string& what) {
    throw std::runtime_error(who + ": the file does not match the run: " + what);
  };
  const auto join = [](const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return "[" + s + "]";
  };
  hdf5::check_run_id(f, run_id, path, who);
  { // grid
    Handle g = hdf5::open_group(f, "grid", path);
    const auto read3 = [&](const char* name, hid_t mem_type, auto* out) {
      Handle d = hdf5::open_dataset(g.get(), name, path);
      const std::string full = std::string("/grid/") + name;
      if (hdf5::extent(d.get(), path, full) != std::vector<hsize_t>{3})
        mismatch(full + " does not hold 3 values");
      check(H5Dread(d.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out), path, "read dataset",
            full);
    };
    std::int32_t cells[3] = {0, 0, 0};
    double lo[3] = {0, 0, 0}, spacing[3] = {0, 0, 0};
    read3("cells", H5T_NATIVE_INT32, cells);
    read3("lo", H5T_NATIVE_DOUBLE, lo);
    read3("spacing", H5T_NATIVE_DOUBLE, spacing);
    static const char* const axis = "xyz";
    for (int d = 0; d < 3; ++d) {
      const std::string a(1, axis[d]);
      if (cells[d] != grid.cells[d])
        mismatch("grid cells along " + a + ": " + std::to_string(cells[d]) + " in the file, " +
                 std::to_string(grid.cells[d]) + " in the run");
      if (!hdf5::same_double(lo[d], grid.lo[d]))
        mismatch("grid lower corner along " + a + ": " + std::to_string(lo[d]) + " in the file, " +
                 std::to_string(grid.lo[d]) + " in the run");
      if (!hdf5::same_double(spacing[d], grid.spacing[d]))
        mismatch("grid spacing along " + a + ": " + std::to_string(spacing[d]) + " in the file, " +
                 std::to_string(grid.spacing[d]) + " in the run");
    }
  }
  Handle fields = hdf5::open_group(f, "fields", path);
  { // names, in order (an absent attribute means none)
    const auto names_in_file = [&](const char* attr) {
      const htri_t exists = H5Aexists(fields.get(), attr);
      if (exists < 0) hdf5::fail(path, "look up attribute", std::string("/fields ") + attr);
      return exists > 0 ? hdf5::read_string_array_attr(fields.get(), attr, path)
                        : std::vector<std::string>{};
    };
    const std::vector<std::string> scalars = names_in_file("scalars");
    const std::vector<std::string> vectors = names_in_file("vectors");
    if (scalars != m.scalar_names)
      mismatch("scalar fields " + join(scalars) + " in the file, " + join(m.scalar_names) +
               " in the run");
    if (vectors != m.vector_names)
      mismatch("vector fields " + join(vectors) + " in the file, " + join(m.vector_names) +
               " in the run");
  }
  m.frames_attr = hdf5::open_attr(fields.get(), "frames", path);
  m.step = hdf5::open_dataset(fields.get(), "step", path);
  m.time = hdf5::open_dataset(fields.get(), "time", path);
  const std::vector<hsize_t> step_dims = hdf5::extent(m.step.get(), path, "/fields/step");
  const std::vector<hsize_t> time_dims = hdf5::extent(m.time.get(), path, "/fields/time");
  if (step_dims.size() != 1 || time_dims.size() != 1)
    mismatch("/fields/step and /fields/time must be 1-D");
  hsize_t complete = std::min(step_dims[0], time_dims[0]);
  longest = std::max(step_dims[0], time_dims[0]);
  const auto open_field = [&](const std::string& name, const hsize_t* inner, std::size_t rank) {
    const std::string full = "/fields/" + name;
    Handle d = hdf5::open_dataset(fields.get(), name, path);
    const std::vector<hsize_t> dims = hdf5::extent(d.get(), path, full);
    if (dims.size() != rank + 1 || !std::equal(inner, inner + rank, dims.begin() + 1))
      mismatch(full + " does not have the grid's shape");
    complete = std::min(complete, dims[0]);
    longest = std::max(longest, dims[0]);
    return d;
  };
  m.scalars.clear();
  m.vectors.clear();
  for (const std::string& name : m.scalar_names)
    m.scalars.push_back(open_field(name, m.inner_scalar, 3));
  for (const std::string& name : m.vector_names)
    m.vectors.push_back(open_field(name, m.inner_vector, 4));
  return complete;
}

} // namespace

FieldsWriter FieldsWriter::resume(const std::string& path, const std::vector<double>& frame_times,
                                  const std::string& run_id, const FieldGrid& grid,
                                  std::vector<std::string> scalar_names,
                                  std::vector<std::string> vector_names, bool check_only) {
  const std::string who = "cannot continue '" + path + "'";
  check_field_grid(grid, who);
  check_field_names(scalar_names, vector_names, who);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  FieldsWriter w;
  Impl& m = *w.impl_;
  m.path = path;
  m.grid = grid;
  m.scalar_names = std::move(scalar_names);
  m.vector_names = std::move(vector_names);
  for (std::size_t d = 0; d < 3; ++d)
    m.inner_scalar[d] = m.inner_vector[d] = static_cast<hsize_t>(grid.cells[2 - d]);
  hsize_t keep = 0;
  bool cut = false;
  { // check, read-only: nothing is changed unless everything matches
    Handle file = hdf5::open_existing(path, who, false);
    hsize_t longest = 0;
    const hsize_t complete = open_layout(m, file.get(), who, run_id, longest);
    const std::vector<double> times = hdf5::read_all<double>(
        m.time.get(), H5T_NATIVE_DOUBLE, hdf5::extent(m.time.get(), path, "/fields/time")[0], path,
        "/fields/time");
    keep = hdf5::frames_to_keep(times, complete, frame_times, who);
    cut = longest > keep;
    m.close_all();
    m.closed = false;
  }
  if (check_only) return FieldsWriter();
  if (cut) // the frames written after the checkpoint go, in a copy renamed over the file
    hdf5::edit_copy(path, [&](hid_t f, const std::string& tmp) {
      Impl e;
      e.path = tmp;
      e.grid = m.grid;
      e.scalar_names = m.scalar_names;
      e.vector_names = m.vector_names;
      std::copy(m.inner_scalar, m.inner_scalar + 3, e.inner_scalar);
      std::copy(m.inner_vector, m.inner_vector + 4, e.inner_vector);
      hsize_t longest = 0;
      open_layout(e, f, who, run_id, longest);
      hdf5::shrink_frames(e.step.get(), keep, tmp, "/fields/step");
      hdf5::shrink_frames(e.time.get(), keep, tmp, "/fields/time");
      for (std::size_t s = 0; s < e.scalars.size(); ++s)
        hdf5::shrink_frames(e.scalars[s].get(), keep, tmp, "/fields/" + e.scalar_names[s]);
      for (std::size_t v = 0; v < e.vectors.size(); ++v)
        hdf5::shrink_frames(e.vectors[v].get(), keep, tmp, "/fields/" + e.vector_names[v]);
      const std::int64_t frames64 = static_cast<std::int64_t>(keep);
      check(H5Awrite(e.frames_attr.get(), H5T_NATIVE_INT64, &frames64), tmp, "write attribute",
            "/fields frames");
      e.close_all();
    });
  m.file = hdf5::open_existing(path, who, true);
  hsize_t longest = 0;
  open_layout(m, m.file.get(), who, run_id, longest);
  m.init_memory();
  m.frames = keep;
  m.kept_times = frame_times;
  return w;
}

FieldsWriter::~FieldsWriter() = default;
FieldsWriter::FieldsWriter(FieldsWriter&&) noexcept = default;
FieldsWriter& FieldsWriter::operator=(FieldsWriter&&) noexcept = default;

void FieldsWriter::write_frame(long step, double time, const std::vector<const double*>& scalars,
                               const std::vector<std::array<const double*, 3>>& vectors) {
  if (!impl_ || impl_->closed) throw std::logic_error("FieldsWriter: write_frame after close");
  Impl& m = *impl_;
  const std::string who = "FieldsWriter('" + m.path + "')";
  if (scalars.size() != m.scalar_names.size())
    throw std::invalid_argument(who + ": " + std::to_string(scalars.size()) +
                                " scalar fields given, the file holds " +
                                std::to_string(m.scalar_names.size()));
  if (vectors.size() != m.vector_names.size())
    throw std::invalid_argument(who + ": " + std::to_string(vectors.size()) +
                                " vector fields given, the file holds " +
                                std::to_string(m.vector_names.size()));
  for (std::size_t s = 0; s < scalars.size(); ++s)
    if (scalars[s] == nullptr)
      throw std::invalid_argument(who + ": null data for scalar field '" + m.scalar_names[s] + "'");
  for (std::size_t v = 0; v < vectors.size(); ++v)
    for (const double* c : vectors[v])
      if (c == nullptr)
        throw std::invalid_argument(who + ": null data for vector field '" + m.vector_names[v] +
                                    "'");

  // Fields first, step and time last: a failed frame leaves F unchanged, and the next call
  // overwrites it.
  const hsize_t frame = m.frames;
  for (std::size_t s = 0; s < scalars.size(); ++s)
    append_frame(m.scalars[s].get(), 4, m.inner_scalar, frame, H5T_NATIVE_DOUBLE,
                 m.mem_scalar.get(), scalars[s], m.path, "/fields/" + m.scalar_names[s]);
  const std::size_t n = m.grid.size();
  for (std::size_t v = 0; v < vectors.size(); ++v) {
    const double* const x = vectors[v][0];
    const double* const y = vectors[v][1];
    const double* const z = vectors[v][2];
    double* const out = m.buffer.data();
    for (std::size_t i = 0; i < n; ++i) {
      out[3 * i] = x[i];
      out[3 * i + 1] = y[i];
      out[3 * i + 2] = z[i];
    }
    append_frame(m.vectors[v].get(), 5, m.inner_vector, frame, H5T_NATIVE_DOUBLE,
                 m.mem_vector.get(), out, m.path, "/fields/" + m.vector_names[v]);
  }
  const std::int64_t step64 = step;
  append_frame(m.step.get(), 1, nullptr, frame, H5T_NATIVE_INT64, m.mem_one.get(), &step64, m.path,
               "/fields/step");
  append_frame(m.time.get(), 1, nullptr, frame, H5T_NATIVE_DOUBLE, m.mem_one.get(), &time, m.path,
               "/fields/time");

  ++m.frames;
  const std::int64_t frames64 = static_cast<std::int64_t>(m.frames);
  check(H5Awrite(m.frames_attr.get(), H5T_NATIVE_INT64, &frames64), m.path, "write attribute",
        "/fields frames");
  flush();
}

void FieldsWriter::flush() {
  if (!impl_ || impl_->closed) return;
  check(H5Fflush(impl_->file.get(), H5F_SCOPE_GLOBAL), impl_->path, "flush file");
}

void FieldsWriter::close() {
  if (!impl_ || impl_->closed) return;
  if (impl_->close_all() < 0) fail(impl_->path, "close file", {});
}

std::size_t FieldsWriter::frames() const {
  return impl_ ? impl_->frames : 0;
}
const FieldGrid& FieldsWriter::grid() const {
  static const FieldGrid empty;
  return impl_ ? impl_->grid : empty;
}
const std::vector<std::string>& FieldsWriter::scalar_names() const {
  static const std::vector<std::string> empty;
  return impl_ ? impl_->scalar_names : empty;
}
const std::vector<std::string>& FieldsWriter::vector_names() const {
  static const std::vector<std::string> empty;
  return impl_ ? impl_->vector_names : empty;
}
const std::string& FieldsWriter::path() const {
  static const std::string empty;
  return impl_ ? impl_->path : empty;
}
const std::vector<double>& FieldsWriter::kept_times() const {
  static const std::vector<double> empty;
  return impl_ ? impl_->kept_times : empty;
}

} // namespace fluidem
