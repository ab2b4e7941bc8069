#include "output/h5md_reader.hpp"
#include "output/hdf5_support.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace fluidem {

namespace {

using hdf5::check;
using hdf5::check_id;
using hdf5::Handle;

} // namespace

struct H5mdReader::Impl {
  std::string path;
  Handle file;
  std::size_t n = 0;
  std::size_t frames = 0;
  int dimension = 3;
  bool layer = false; // /particles/all/layer present
  H5mdBox box;
  std::vector<double> times;
  std::vector<long> steps;

  [[noreturn]] void bad(const std::string& what) const {
    throw std::runtime_error("'" + path + "' is not a readable fluidem particle file: " + what);
  }

  // Frame k of /particles/all/<name>/value ([F][N][components]) converted to `mem_type`.
  template <class T>
  void read_value(const char* name, int components, hid_t mem_type, std::size_t k,
                  std::vector<T>& out) const {
    const std::string full = std::string("/particles/all/") + name + "/value";
    Handle d = hdf5::open_dataset(file.get(), full, path);
    const std::vector<hsize_t> dims = hdf5::extent(d.get(), path, full);
    const std::size_t rank = components == 3 ? 3 : 2;
    if (dims.size() != rank || dims[1] != n || (rank == 3 && dims[2] != 3) || dims[0] <= k)
      bad(full + " does not have the shape [frames][" + std::to_string(n) + "]" +
          (rank == 3 ? "[3]" : ""));
    out.assign(n * static_cast<std::size_t>(components), T{});
    if (n == 0) return;
    const hsize_t start[3] = {k, 0, 0};
    const hsize_t count[3] = {1, n, 3};
    Handle space{check_id(H5Dget_space(d.get()), path, "get dataspace of", full), H5Sclose};
    check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr), path,
          "select frame in", full);
    const hsize_t mem_dims[2] = {n, 3};
    Handle mem{check_id(H5Screate_simple(static_cast<int>(rank) - 1, mem_dims, nullptr), path,
                        "create dataspace"),
               H5Sclose};
    check(H5Dread(d.get(), mem_type, mem.get(), space.get(), H5P_DEFAULT, out.data()), path,
          "read frame of", full);
  }
};

H5mdReader::H5mdReader(const std::string& path) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.path = path;
  m.file = hdf5::open_for_reading(path, "the particle frames of a run");
  const hid_t f = m.file.get();
  const auto exists = [&](const char* link) {
    const htri_t e = H5Lexists(f, link, H5P_DEFAULT);
    hdf5::hdf5_error_detail(); // clear the stack of a failed lookup
    return e > 0;
  };
  for (const char* link : {"/parameters", "/particles", "/particles/all", "/particles/all/box",
                           "/particles/all/vertex_index", "/particles/all/position"})
    if (!exists(link)) m.bad(std::string("no ") + link);
  {
    Handle parameters = hdf5::open_group(f, "/parameters", path);
    Handle attr = hdf5::open_attr(parameters.get(), "dimension", path);
    std::int32_t dim = 0;
    check(H5Aread(attr.get(), H5T_NATIVE_INT32, &dim), path, "read attribute",
          "/parameters dimension");
    if (dim != 2 && dim != 3) m.bad("/parameters dimension is " + std::to_string(dim));
    m.dimension = dim;
  }
  {
    Handle box = hdf5::open_group(f, "/particles/all/box", path);
    const auto read3 = [&](const char* name) {
      const std::string full = std::string("/particles/all/box/") + name;
      Handle d = hdf5::open_dataset(box.get(), name, path);
      if (hdf5::extent(d.get(), path, full) != std::vector<hsize_t>{3})
        m.bad(full + " does not hold 3 values");
      return hdf5::read_all<double>(d.get(), H5T_NATIVE_DOUBLE, 3, path, full);
    };
    const std::vector<double> edges = read3("edges"), offset = read3("offset");
    const std::vector<std::string> boundary =
        hdf5::read_string_array_attr(box.get(), "boundary", path);
    if (boundary.size() != 3) m.bad("/particles/all/box boundary does not hold 3 strings");
    for (std::size_t d = 0; d < 3; ++d) {
      m.box.lo[d] = offset[d];
      m.box.hi[d] = offset[d] + edges[d];
      m.box.periodic[d] = boundary[d] == "periodic";
    }
  }
  {
    Handle index = hdf5::open_dataset(f, "/particles/all/vertex_index", path);
    const std::vector<hsize_t> dims =
        hdf5::extent(index.get(), path, "/particles/all/vertex_index");
    if (dims.size() != 1) m.bad("/particles/all/vertex_index is not one-dimensional");
    m.n = dims[0];
  }
  // The frames complete in every dataset: the shortest of step, time and each value.
  std::size_t complete = SIZE_MAX;
  const auto frames_of = [&](const std::string& full) {
    if (!exists(full.c_str())) m.bad("no " + full);
    Handle d = hdf5::open_dataset(f, full, path);
    const std::vector<hsize_t> dims = hdf5::extent(d.get(), path, full);
    if (dims.empty()) m.bad(full + " has no frame axis");
    complete = std::min<std::size_t>(complete, dims[0]);
  };
  const char* const names[] = {"position", "velocity", "angular_velocity",
                               "radius",   "species",  "id"};
  for (const char* name : names) frames_of(std::string("/particles/all/") + name + "/value");
  m.layer = exists("/particles/all/layer");
  if (m.layer) frames_of("/particles/all/layer/value");
  frames_of("/particles/all/position/time");
  frames_of("/particles/all/position/step");
  m.frames = complete;
  Handle t = hdf5::open_dataset(f, "/particles/all/position/time", path);
  const std::size_t nt = hdf5::extent(t.get(), path, "/particles/all/position/time")[0];
  m.times =
      hdf5::read_all<double>(t.get(), H5T_NATIVE_DOUBLE, nt, path, "/particles/all/position/time");
  m.times.resize(m.frames);
  Handle s = hdf5::open_dataset(f, "/particles/all/position/step", path);
  const std::size_t ns = hdf5::extent(s.get(), path, "/particles/all/position/step")[0];
  const std::vector<std::int64_t> steps = hdf5::read_all<std::int64_t>(
      s.get(), H5T_NATIVE_INT64, ns, path, "/particles/all/position/step");
  m.steps.assign(steps.begin(), steps.begin() + static_cast<long>(m.frames));
}

H5mdReader::~H5mdReader() = default;
H5mdReader::H5mdReader(H5mdReader&&) noexcept = default;
H5mdReader& H5mdReader::operator=(H5mdReader&&) noexcept = default;

std::size_t H5mdReader::frames() const {
  return impl_->frames;
}
std::size_t H5mdReader::n_particles() const {
  return impl_->n;
}
int H5mdReader::dimension() const {
  return impl_->dimension;
}
const H5mdBox& H5mdReader::box() const {
  return impl_->box;
}
const std::vector<double>& H5mdReader::times() const {
  return impl_->times;
}
const std::vector<long>& H5mdReader::steps() const {
  return impl_->steps;
}
bool H5mdReader::has_layer() const {
  return impl_->layer;
}
const std::string& H5mdReader::path() const {
  return impl_->path;
}

void H5mdReader::read_frame(std::size_t k, ParticleStore& out) const {
  const Impl& m = *impl_;
  if (k >= m.frames)
    throw std::runtime_error("'" + m.path + "': frame " + std::to_string(k) +
                             " does not exist (the file holds " + std::to_string(m.frames) +
                             " frames)");
  const std::size_t n = m.n;
  out.resize(n);
  std::vector<double> v;
  const auto vec3 = [&](const char* name, std::vector<double>& a, std::vector<double>& b,
                        std::vector<double>& c) {
    m.read_value(name, 3, H5T_NATIVE_DOUBLE, k, v);
    for (std::size_t i = 0; i < n; ++i) {
      a[i] = v[3 * i];
      b[i] = v[3 * i + 1];
      c[i] = v[3 * i + 2];
    }
  };
  vec3("position", out.x, out.y, out.z);
  vec3("velocity", out.vx, out.vy, out.vz);
  vec3("angular_velocity", out.wx, out.wy, out.wz);
  m.read_value("radius", 1, H5T_NATIVE_DOUBLE, k, out.radius);
  m.read_value("species", 1, H5T_NATIVE_INT32, k, out.species);
  m.read_value("id", 1, H5T_NATIVE_INT64, k, out.id);
  if (m.layer)
    m.read_value("layer", 1, H5T_NATIVE_INT32, k, out.layer);
  else
    out.layer.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double r = out.radius[i];
    out.mass[i] = sphere_mass(r, 1.0);
    out.inv_mass[i] = out.mass[i] > 0.0 ? 1.0 / out.mass[i] : 0.0;
    const double inertia = 0.4 * out.mass[i] * r * r;
    out.inv_inertia[i] = inertia > 0.0 ? 1.0 / inertia : 0.0;
  }
}

} // namespace fluidem
