#include "output/h5md_writer.hpp"
#include "output/hdf5_support.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <utility>
#include <vector>

// H5Pset_file_locking exists from 1.10.7 on the 1.10 branch and from 1.12.1 on.
#if H5_VERS_MAJOR > 1 || (H5_VERS_MAJOR == 1 && H5_VERS_MINOR >= 13) ||                            \
    (H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 12 && H5_VERS_RELEASE >= 1) ||                         \
    (H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 10 && H5_VERS_RELEASE >= 7)
#define FLUIDEM_HAVE_H5P_FILE_LOCKING 1
#endif

namespace fluidem {

namespace {

constexpr std::size_t kChunkCapBytes = std::size_t{1} << 20; // 1 MiB per value chunk
constexpr hsize_t kStepChunk = 512;                          // step/time: 4 KiB chunks

using hdf5::append_frame;
using hdf5::Builder;
using hdf5::check;
using hdf5::check_id;
using hdf5::fail;
using hdf5::Handle;

enum Element : std::size_t {
  kPosition,
  kVelocity,
  kAngularVelocity,
  kRadius,
  kSpecies,
  kId,
  kLayer, // only when the run keeps layers (output.layers > 0)
  kCount
};

struct ElementSpec {
  const char* name;
  const char* value_path; // for error messages
  int components;         // 3 for vectors, 1 for scalars
  hid_t (*file_type)();
  hid_t (*mem_type)();
  std::size_t bytes;
  const char* unit; // nullptr: dimensionless
};

hid_t f64le() {
  return H5T_IEEE_F64LE;
}
hid_t i32le() {
  return H5T_STD_I32LE;
}
hid_t i64le() {
  return H5T_STD_I64LE;
}
hid_t native_double() {
  return H5T_NATIVE_DOUBLE;
}
hid_t native_i32() {
  return H5T_NATIVE_INT32;
}
hid_t native_i64() {
  return H5T_NATIVE_INT64;
}

const ElementSpec kElements[kCount] = {
    {"position", "/particles/all/position/value", 3, f64le, native_double, 8, "m"},
    {"velocity", "/particles/all/velocity/value", 3, f64le, native_double, 8, "m s-1"},
    {"angular_velocity", "/particles/all/angular_velocity/value", 3, f64le, native_double, 8,
     "s-1"},
    {"radius", "/particles/all/radius/value", 1, f64le, native_double, 8, "m"},
    {"species", "/particles/all/species/value", 1, i32le, native_i32, 4, nullptr},
    {"id", "/particles/all/id/value", 1, i64le, native_i64, 8, nullptr},
    {"layer", "/particles/all/layer/value", 1, i32le, native_i32, 4, nullptr},
};

} // namespace

struct H5mdWriter::Impl {
  std::string path;
  std::size_t n = 0;
  std::size_t frames = 0;
  bool closed = false;
  bool layer = false; // the file holds /particles/all/layer
  std::size_t elements() const { return layer ? kCount : kLayer; }
  // Declaration order = reverse close order: the file is closed last.
  Handle file;
  Handle frames_attr;
  Handle step; // shared (hard-linked) by every time-dependent element
  Handle time;
  Handle value[kCount];
  Handle mem_vector;              // [N][3]
  Handle mem_scalar;              // [N]
  Handle mem_one;                 // [1]
  std::vector<double> buffer;     // interleaved xyz, reused every frame
  std::vector<double> kept_times; // resume only

  void append_value(Element e, const void* data, hid_t mem_space);
  void init_memory() {
    const Builder b{path};
    const hsize_t vec_dims[2] = {std::max<hsize_t>(n, 1), 3};
    const hsize_t scalar_dims[1] = {std::max<hsize_t>(n, 1)};
    const hsize_t one_dims[1] = {1};
    mem_vector = b.simple_space(2, vec_dims);
    mem_scalar = b.simple_space(1, scalar_dims);
    mem_one = b.simple_space(1, one_dims);
    buffer.resize(3 * n);
  }
  herr_t close_all() {
    herr_t status = 0;
    for (Handle* h : {&mem_one, &mem_scalar, &mem_vector}) status = std::min(status, h->reset());
    for (auto& v : value) status = std::min(status, v.reset());
    status = std::min(status, time.reset());
    status = std::min(status, step.reset());
    status = std::min(status, frames_attr.reset());
    status = std::min(status, file.reset());
    closed = true;
    return status;
  }
  ~Impl() { close_all(); }
};

void H5mdWriter::Impl::append_value(Element e, const void* data, hid_t mem_space) {
  const ElementSpec& spec = kElements[e];
  const hsize_t inner[2] = {n, 3};
  append_frame(value[e].get(), spec.components == 3 ? 3 : 2, inner, frames, spec.mem_type(),
               mem_space, data, path, spec.value_path);
}

H5mdWriter::H5mdWriter(const std::string& path, std::size_t n_particles, int dimension,
                       const std::string& creator_version, const H5mdBox& box,
                       const std::string& author, bool layer, const std::string& run_id)
    : impl_(std::make_unique<Impl>()) {
  if (dimension != 2 && dimension != 3)
    throw std::invalid_argument("H5mdWriter('" + path + "'): dimension must be 2 or 3, not " +
                                std::to_string(dimension));
  // Errors are reported by exceptions; keep HDF5 from dumping its stack on stderr.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);

  Impl& m = *impl_;
  m.path = path;
  m.n = n_particles;
  m.layer = layer;
  const Builder b{m.path};

  Handle fapl{check_id(H5Pcreate(H5P_FILE_ACCESS), path, "create property list"), H5Pclose};
#ifdef FLUIDEM_HAVE_H5P_FILE_LOCKING
  // No lock: a viewer (ParaView, h5py) may open the file while the run appends frames; every frame
  // is flushed, so what it sees is consistent.
  check(H5Pset_file_locking(fapl.get(), false, true), path, "disable file locking");
#endif
  m.file = hdf5::create_file(path, fapl.get());
  const hid_t f = m.file.get();

  { // /h5md
    Handle h5md = b.group(f, "h5md");
    b.int_array_attr(h5md.get(), "version", {1, 1});
    Handle author_group = b.group(h5md.get(), "author");
    std::string who = author;
    if (who.empty()) {
      const char* user = std::getenv("USER");
      who = (user != nullptr && user[0] != '\0') ? user : "unknown";
    }
    b.string_attr(author_group.get(), "name", who);
    Handle creator = b.group(h5md.get(), "creator");
    b.string_attr(creator.get(), "name", "fluidem");
    b.string_attr(creator.get(), "version", creator_version);
    Handle modules = b.group(h5md.get(), "modules");
    Handle units = b.group(modules.get(), "units");
    b.int_array_attr(units.get(), "version", {1, 0});
    b.string_attr(units.get(), "system", "SI");
  }
  { // /parameters
    Handle parameters = b.group(f, "parameters");
    const std::int32_t dim = dimension;
    b.scalar_attr(parameters.get(), "dimension", H5T_STD_I32LE, H5T_NATIVE_INT32, &dim);
    if (!run_id.empty()) b.string_attr(parameters.get(), "run_id", run_id);
  }

  Handle particles = b.group(f, "particles");
  Handle all = b.group(particles.get(), "all");
  const std::int64_t zero = 0;
  m.frames_attr = b.scalar_attr(all.get(), "frames", H5T_STD_I64LE, H5T_NATIVE_INT64, &zero);
  { // box
    Handle box_group = b.group(all.get(), "box");
    const std::int32_t three = 3;
    b.scalar_attr(box_group.get(), "dimension", H5T_STD_I32LE, H5T_NATIVE_INT32, &three);
    std::vector<std::string> boundary;
    for (bool p : box.periodic) boundary.emplace_back(p ? "periodic" : "none");
    b.string_array_attr(box_group.get(), "boundary", boundary);
    const double edges[3] = {box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]};
    b.fixed_dataset(box_group.get(), "edges", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, edges);
    b.fixed_dataset(box_group.get(), "offset", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, box.lo.data());
  }
  { // Polyvertex connectivity for XDMF
    std::vector<std::int64_t> index(n_particles);
    for (std::size_t i = 0; i < n_particles; ++i) index[i] = static_cast<std::int64_t>(i);
    b.fixed_dataset(all.get(), "vertex_index", H5T_STD_I64LE, H5T_NATIVE_INT64, n_particles,
                    index.data());
  }

  for (std::size_t e = 0; e < m.elements(); ++e) {
    const ElementSpec& spec = kElements[e];
    Handle group = b.group(all.get(), spec.name);
    if (e == 0) {
      const hsize_t chunk[1] = {kStepChunk};
      m.step = b.extendible(group.get(), "step", H5T_STD_I64LE, 1, nullptr, chunk);
      m.time = b.extendible(group.get(), "time", H5T_IEEE_F64LE, 1, nullptr, chunk);
      b.string_attr(m.time.get(), "unit", "s");
    } else { // H5MD allows elements to share step and time through hard links
      check(
          H5Lcreate_hard(all.get(), "position/step", group.get(), "step", H5P_DEFAULT, H5P_DEFAULT),
          path, "link", "step");
      check(
          H5Lcreate_hard(all.get(), "position/time", group.get(), "time", H5P_DEFAULT, H5P_DEFAULT),
          path, "link", "time");
    }
    const std::size_t per_particle = static_cast<std::size_t>(spec.components) * spec.bytes;
    const hsize_t chunk_n =
        std::clamp<hsize_t>(kChunkCapBytes / per_particle, 1, std::max<hsize_t>(n_particles, 1));
    if (spec.components == 3) {
      const hsize_t inner[2] = {n_particles, 3};
      const hsize_t chunk[3] = {1, chunk_n, 3};
      m.value[e] = b.extendible(group.get(), "value", spec.file_type(), 3, inner, chunk);
    } else {
      const hsize_t inner[1] = {n_particles};
      const hsize_t chunk[2] = {1, chunk_n};
      m.value[e] = b.extendible(group.get(), "value", spec.file_type(), 2, inner, chunk);
    }
    if (spec.unit != nullptr) b.string_attr(m.value[e].get(), "unit", spec.unit);
  }

  m.init_memory();
  flush();
}

H5mdWriter::H5mdWriter() : impl_(std::make_unique<Impl>()) {}

namespace {

// Checks the open file `f` against the run and opens its time-dependent datasets into `m`;
// returns how many frames every one of them holds complete, and sets `longest` to the most any
// of them holds.
hsize_t open_layout(H5mdWriter::Impl& m, hid_t f, const std::string& who, int dimension,
                    const H5mdBox& box, bool layer, const std::string& run_id, hsize_t& longest) {
  const std::string& path = m.path;
  const std::size_t n_particles = m.n;
  const auto mismatch = [&](const std::string& what) {
    throw std::runtime_error(who + ": the file does not match the run: " + what);
  };
  { // dimension and run id
    Handle parameters = hdf5::open_group(f, "parameters", path);
    Handle attr = hdf5::open_attr(parameters.get(), "dimension", path);
    std::int32_t dim = 0;
    check(H5Aread(attr.get(), H5T_NATIVE_INT32, &dim), path, "read attribute",
          "/parameters dimension");
    if (dim != dimension)
      mismatch("dimension " + std::to_string(dim) + " in the file, " + std::to_string(dimension) +
               " in the run");
    hdf5::check_run_id(parameters.get(), run_id, path, who);
  }
  Handle all = hdf5::open_group(f, "/particles/all", path);
  { // box
    Handle box_group = hdf5::open_group(all.get(), "box", path);
    const auto read3 = [&](const char* name) {
      Handle d = hdf5::open_dataset(box_group.get(), name, path);
      const std::string full = std::string("/particles/all/box/") + name;
      if (hdf5::extent(d.get(), path, full) != std::vector<hsize_t>{3})
        mismatch(full + " does not hold 3 values");
      return hdf5::read_all<double>(d.get(), H5T_NATIVE_DOUBLE, 3, path, full);
    };
    const std::vector<double> edges = read3("edges");
    const std::vector<double> offset = read3("offset");
    const std::vector<std::string> boundary =
        hdf5::read_string_array_attr(box_group.get(), "boundary", path);
    static const char* const axis = "xyz";
    for (std::size_t d = 0; d < 3; ++d) {
      const std::string a(1, axis[d]);
      if (!hdf5::same_double(offset[d], box.lo[d]))
        mismatch("box lower corner along " + a + ": " + std::to_string(offset[d]) +
                 " in the file, " + std::to_string(box.lo[d]) + " in the run");
      const double run_edge = box.hi[d] - box.lo[d];
      if (!hdf5::same_double(edges[d], run_edge))
        mismatch("box size along " + a + ": " + std::to_string(edges[d]) + " in the file, " +
                 std::to_string(run_edge) + " in the run");
      const std::string run_boundary = box.periodic[d] ? "periodic" : "none";
      if (boundary.size() != 3 || boundary[d] != run_boundary)
        mismatch("box boundary along " + a + ": '" + (boundary.size() == 3 ? boundary[d] : "?") +
                 "' in the file, '" + run_boundary + "' in the run");
    }
  }
  { // particle count
    Handle index = hdf5::open_dataset(all.get(), "vertex_index", path);
    const std::vector<hsize_t> dims = hdf5::extent(index.get(), path, kH5mdVertexIndexPath);
    if (dims.size() != 1 || dims[0] != n_particles)
      mismatch(std::to_string(dims.empty() ? 0 : dims[0]) + " particles in the file, " +
               std::to_string(n_particles) + " in the run");
  }

  m.frames_attr = hdf5::open_attr(all.get(), "frames", path);
  m.step = hdf5::open_dataset(all.get(), "position/step", path);
  m.time = hdf5::open_dataset(all.get(), "position/time", path);
  const std::vector<hsize_t> step_dims =
      hdf5::extent(m.step.get(), path, "/particles/all/position/step");
  const std::vector<hsize_t> time_dims =
      hdf5::extent(m.time.get(), path, "/particles/all/position/time");
  if (step_dims.size() != 1 || time_dims.size() != 1)
    mismatch("/particles/all/position/step and time must be 1-D");
  hsize_t complete = std::min(step_dims[0], time_dims[0]);
  longest = std::max(step_dims[0], time_dims[0]);
  { // layers: the file holds them exactly when the run keeps them
    const htri_t has = H5Lexists(all.get(), "layer", H5P_DEFAULT);
    hdf5::hdf5_error_detail(); // clear the stack of a failed lookup
    if ((has > 0) != layer)
      mismatch(std::string(has > 0 ? "the file holds" : "the file lacks") +
               " /particles/all/layer, the run " + (layer ? "keeps" : "does not keep") +
               " layers (output.layers)");
    m.layer = layer;
  }
  for (std::size_t e = 0; e < m.elements(); ++e) {
    const ElementSpec& spec = kElements[e];
    m.value[e] = hdf5::open_dataset(all.get(), std::string(spec.name) + "/value", path);
    const std::vector<hsize_t> dims = hdf5::extent(m.value[e].get(), path, spec.value_path);
    const std::vector<hsize_t> inner = spec.components == 3 ? std::vector<hsize_t>{n_particles, 3}
                                                            : std::vector<hsize_t>{n_particles};
    if (dims.size() != inner.size() + 1 ||
        !std::equal(inner.begin(), inner.end(), dims.begin() + 1))
      mismatch(std::string(spec.value_path) + " does not hold " + std::to_string(n_particles) +
               " particles per frame");
    complete = std::min(complete, dims[0]);
    longest = std::max(longest, dims[0]);
  }
  return complete;
}

} // namespace

H5mdWriter H5mdWriter::resume(const std::string& path, const std::vector<double>& frame_times,
                              const std::string& run_id, std::size_t n_particles, int dimension,
                              const H5mdBox& box, bool layer, bool check_only) {
  const std::string who = "cannot continue '" + path + "'";
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  H5mdWriter w;
  Impl& m = *w.impl_;
  m.path = path;
  m.n = n_particles;
  hsize_t keep = 0;
  bool cut = false;
  { // check, read-only: nothing is changed unless everything matches
    Handle file = hdf5::open_existing(path, who, false);
    hsize_t longest = 0;
    const hsize_t complete =
        open_layout(m, file.get(), who, dimension, box, layer, run_id, longest);
    const std::vector<double> times = hdf5::read_all<double>(
        m.time.get(), H5T_NATIVE_DOUBLE, hdf5::extent(m.time.get(), path, "time")[0], path,
        "/particles/all/position/time");
    keep = hdf5::frames_to_keep(times, complete, frame_times, who);
    cut = longest > keep;
    m.close_all();
    m.closed = false;
  }
  if (check_only) return H5mdWriter();
  if (cut) // the frames written after the checkpoint go, in a copy renamed over the file
    hdf5::edit_copy(path, [&](hid_t f, const std::string& tmp) {
      Impl e;
      e.path = tmp;
      e.n = n_particles;
      hsize_t longest = 0;
      open_layout(e, f, who, dimension, box, layer, run_id, longest);
      hdf5::shrink_frames(e.step.get(), keep, tmp, "/particles/all/position/step");
      hdf5::shrink_frames(e.time.get(), keep, tmp, "/particles/all/position/time");
      for (std::size_t k = 0; k < e.elements(); ++k)
        hdf5::shrink_frames(e.value[k].get(), keep, tmp, kElements[k].value_path);
      const std::int64_t frames64 = static_cast<std::int64_t>(keep);
      check(H5Awrite(e.frames_attr.get(), H5T_NATIVE_INT64, &frames64), tmp, "write attribute",
            "/particles/all frames");
      e.close_all();
    });
  m.file = hdf5::open_existing(path, who, true);
  hsize_t longest = 0;
  open_layout(m, m.file.get(), who, dimension, box, layer, run_id, longest);
  m.frames = keep;
  m.kept_times = frame_times;
  m.init_memory();
  return w;
}

H5mdWriter::~H5mdWriter() = default;
H5mdWriter::H5mdWriter(H5mdWriter&&) noexcept = default;
H5mdWriter& H5mdWriter::operator=(H5mdWriter&&) noexcept = default;

void H5mdWriter::write_frame(long step, double time, const ParticleStore& p,
                             const std::vector<std::uint32_t>* order) {
  if (!impl_ || impl_->closed) throw std::logic_error("H5mdWriter: write_frame after close");
  Impl& m = *impl_;
  const std::size_t n = m.n;
  for (const std::size_t size :
       {p.x.size(), p.y.size(), p.z.size(), p.vx.size(), p.vy.size(), p.vz.size(), p.wx.size(),
        p.wy.size(), p.wz.size(), p.radius.size(), p.species.size(), p.id.size(),
        m.layer ? p.layer.size() : n}) {
    if (size != n)
      throw std::invalid_argument("H5mdWriter('" + m.path + "'): frame has " +
                                  std::to_string(size) + " particles, the file holds " +
                                  std::to_string(n));
  }

  if (order && order->size() != n)
    throw std::invalid_argument("H5mdWriter('" + m.path + "'): the frame order has " +
                                std::to_string(order->size()) + " entries for " +
                                std::to_string(n) + " particles");

  const std::int64_t step64 = step;
  append_frame(m.step.get(), 1, nullptr, m.frames, H5T_NATIVE_INT64, m.mem_one.get(), &step64,
               m.path, "/particles/all/position/step");
  append_frame(m.time.get(), 1, nullptr, m.frames, H5T_NATIVE_DOUBLE, m.mem_one.get(), &time,
               m.path, "/particles/all/position/time");

  const auto at = [order](std::size_t k) { return order ? (*order)[k] : k; };
  const auto interleave = [&](const std::vector<double>& a, const std::vector<double>& b,
                              const std::vector<double>& c) {
    double* out = m.buffer.data();
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = at(k);
      out[3 * k] = a[i];
      out[3 * k + 1] = b[i];
      out[3 * k + 2] = c[i];
    }
    return static_cast<const void*>(out);
  };
  // A scalar array in frame order: the array itself, or gathered into `scratch`.
  const auto in_order = [&](const auto& a, auto& scratch) {
    if (!order) return static_cast<const void*>(a.data());
    scratch.resize(n);
    for (std::size_t k = 0; k < n; ++k) scratch[k] = a[at(k)];
    return static_cast<const void*>(scratch.data());
  };
  m.append_value(kPosition, interleave(p.x, p.y, p.z), m.mem_vector.get());
  m.append_value(kVelocity, interleave(p.vx, p.vy, p.vz), m.mem_vector.get());
  m.append_value(kAngularVelocity, interleave(p.wx, p.wy, p.wz), m.mem_vector.get());
  std::vector<double> radius;
  std::vector<std::int32_t> ints;
  std::vector<std::int64_t> ids;
  m.append_value(kRadius, in_order(p.radius, radius), m.mem_scalar.get());
  m.append_value(kSpecies, in_order(p.species, ints), m.mem_scalar.get());
  m.append_value(kId, in_order(p.id, ids), m.mem_scalar.get());
  if (m.layer) m.append_value(kLayer, in_order(p.layer, ints), m.mem_scalar.get());
  // The charges (constant during a run), once, as a time-independent element in frame order.
  const bool charged =
      std::any_of(p.charge.begin(), p.charge.end(), [](double q) { return q != 0.0; });
  if (charged && p.charge.size() == n &&
      H5Lexists(m.file.get(), "/particles/all/charge", H5P_DEFAULT) == 0) {
    const Builder b{m.path};
    const hsize_t dims[1] = {n};
    Handle space = b.simple_space(1, dims);
    Handle set{check_id(H5Dcreate2(m.file.get(), "/particles/all/charge", H5T_IEEE_F64LE,
                                   space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                        m.path, "create dataset", "/particles/all/charge"),
               H5Dclose};
    std::vector<double> charge;
    check(H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                   in_order(p.charge, charge)),
          m.path, "write", "/particles/all/charge");
    b.string_attr(set.get(), "unit", "C");
  }

  ++m.frames;
  const std::int64_t frames64 = static_cast<std::int64_t>(m.frames);
  check(H5Awrite(m.frames_attr.get(), H5T_NATIVE_INT64, &frames64), m.path, "write attribute",
        "/particles/all frames");
  flush();
}

void H5mdWriter::flush() {
  if (!impl_ || impl_->closed) return;
  check(H5Fflush(impl_->file.get(), H5F_SCOPE_GLOBAL), impl_->path, "flush file");
}

void H5mdWriter::close() {
  if (!impl_ || impl_->closed) return;
  if (impl_->close_all() < 0) fail(impl_->path, "close file", {});
}

std::size_t H5mdWriter::frames() const {
  return impl_ ? impl_->frames : 0;
}
std::size_t H5mdWriter::n_particles() const {
  return impl_ ? impl_->n : 0;
}
const std::string& H5mdWriter::path() const {
  static const std::string empty;
  return impl_ ? impl_->path : empty;
}
const std::vector<double>& H5mdWriter::kept_times() const {
  static const std::vector<double> empty;
  return impl_ ? impl_->kept_times : empty;
}

} // namespace fluidem
