// HDF5 C-API support shared by the output files (particles.h5, fields.h5): errors that name
// the file and the object, an owning handle, and small builders that throw on failure.
// Internal to the output module.
#pragma once
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <hdf5.h>

#include "output/safe_file.hpp"

namespace fluidem::hdf5 {

// The innermost message of the HDF5 error stack (e.g. "unable to open file: ... errno = 2 ...").
inline std::string hdf5_error_detail() {
  std::string detail;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
        auto* s = static_cast<std::string*>(data);
        if (s->empty() && e != nullptr && e->desc != nullptr && e->desc[0] != '\0') *s = e->desc;
        return 0;
      },
      &detail);
  H5Eclear2(H5E_DEFAULT);
  // A failed system call: HDF5's message quotes the system's, keep that one ("No space left on
  // device") with its errno.
  const std::size_t m = detail.find("error message = '");
  if (m != std::string::npos) {
    const std::size_t from = m + 17, to = detail.find('\'', from);
    const std::size_t e = detail.find("errno = ");
    std::string errno_text;
    if (e != std::string::npos) errno_text = detail.substr(e, detail.find(',', e) - e);
    detail = detail.substr(from, to - from) + (errno_text.empty() ? "" : ", " + errno_text);
  }
  return detail;
}

[[noreturn]] inline void fail(const std::string& path, const char* op, const std::string& object) {
  std::string msg = "HDF5 error in '" + path + "': cannot " + op;
  if (!object.empty()) msg += " '" + object + "'";
  const std::string detail = hdf5_error_detail();
  if (!detail.empty()) msg += " (" + detail + ")";
  throw OutputError(msg);
}

inline hid_t check_id(hid_t id, const std::string& path, const char* op,
                      const std::string& object = {}) {
  if (id < 0) fail(path, op, object);
  return id;
}

inline void check(herr_t status, const std::string& path, const char* op,
                  const std::string& object = {}) {
  if (status < 0) fail(path, op, object);
}

// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), closer_(o.closer_) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, H5I_INVALID_HID);
      closer_ = o.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Close now; returns the HDF5 status (0 when nothing was open).
  herr_t reset() {
    herr_t status = 0;
    if (id_ >= 0 && closer_ != nullptr) status = closer_(id_);
    id_ = H5I_INVALID_HID;
    return status;
  }

private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

// Small helpers that create one object and throw on failure.
struct Builder {
  const std::string& path;

  Handle group(hid_t parent, const char* name) const {
    return {check_id(H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), path,
                     "create group", name),
            H5Gclose};
  }

  Handle simple_space(int rank, const hsize_t* dims, const hsize_t* maxdims = nullptr) const {
    return {check_id(H5Screate_simple(rank, dims, maxdims), path, "create dataspace"), H5Sclose};
  }

  Handle string_type(std::size_t length) const {
    Handle t{check_id(H5Tcopy(H5T_C_S1), path, "copy string type"), H5Tclose};
    check(H5Tset_size(t.get(), std::max<std::size_t>(length, 1)), path, "set string size");
    check(H5Tset_strpad(t.get(), H5T_STR_NULLTERM), path, "set string padding");
    return t;
  }

  void string_attr(hid_t obj, const char* name, const std::string& value) const {
    Handle type = string_type(value.size() + 1);
    Handle space{check_id(H5Screate(H5S_SCALAR), path, "create dataspace"), H5Sclose};
    Handle attr{check_id(H5Acreate2(obj, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                         path, "create attribute", name),
                H5Aclose};
    check(H5Awrite(attr.get(), type.get(), value.c_str()), path, "write attribute", name);
  }

  void string_array_attr(hid_t obj, const char* name,
                         const std::vector<std::string>& values) const {
    std::size_t width = 1;
    for (const auto& v : values) width = std::max(width, v.size() + 1);
    std::vector<char> buffer(width * values.size(), '\0');
    for (std::size_t i = 0; i < values.size(); ++i)
      std::copy(values[i].begin(), values[i].end(), buffer.begin() + static_cast<long>(i * width));
    Handle type = string_type(width);
    const hsize_t dims[1] = {values.size()};
    Handle space = simple_space(1, dims);
    Handle attr{check_id(H5Acreate2(obj, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                         path, "create attribute", name),
                H5Aclose};
    check(H5Awrite(attr.get(), type.get(), buffer.data()), path, "write attribute", name);
  }

  void int_array_attr(hid_t obj, const char* name, const std::vector<int>& values) const {
    const hsize_t dims[1] = {values.size()};
    Handle space = simple_space(1, dims);
    Handle attr{
        check_id(H5Acreate2(obj, name, H5T_STD_I32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), path,
                 "create attribute", name),
        H5Aclose};
    check(H5Awrite(attr.get(), H5T_NATIVE_INT, values.data()), path, "write attribute", name);
  }

  Handle scalar_attr(hid_t obj, const char* name, hid_t file_type, hid_t mem_type,
                     const void* value) const {
    Handle space{check_id(H5Screate(H5S_SCALAR), path, "create dataspace"), H5Sclose};
    Handle attr{check_id(H5Acreate2(obj, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                         path, "create attribute", name),
                H5Aclose};
    check(H5Awrite(attr.get(), mem_type, value), path, "write attribute", name);
    return attr;
  }

  void fixed_dataset(hid_t parent, const char* name, hid_t file_type, hid_t mem_type, hsize_t n,
                     const void* data) const {
    const hsize_t dims[1] = {n};
    Handle space = simple_space(1, dims);
    Handle dset{check_id(H5Dcreate2(parent, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                    H5P_DEFAULT),
                         path, "create dataset", name),
                H5Dclose};
    if (n > 0)
      check(H5Dwrite(dset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), path,
            "write dataset", name);
  }

  // A chunked dataset of shape [0, inner...] (rank <= 5) with an unlimited first dimension.
  Handle extendible(hid_t parent, const char* name, hid_t file_type, int rank, const hsize_t* inner,
                    const hsize_t* chunk) const {
    hsize_t dims[5] = {0, 0, 0, 0, 0};
    hsize_t maxdims[5] = {H5S_UNLIMITED, 0, 0, 0, 0};
    for (int d = 1; d < rank; ++d) {
      dims[d] = inner[d - 1];
      // A fixed dimension of size 0 cannot hold a chunk of size >= 1: make it unlimited.
      maxdims[d] = inner[d - 1] > 0 ? inner[d - 1] : H5S_UNLIMITED;
    }
    Handle space = simple_space(rank, dims, maxdims);
    Handle dcpl{check_id(H5Pcreate(H5P_DATASET_CREATE), path, "create property list"), H5Pclose};
    check(H5Pset_chunk(dcpl.get(), rank, chunk), path, "set chunking of", name);
    return {check_id(H5Dcreate2(parent, name, file_type, space.get(), H5P_DEFAULT, dcpl.get(),
                                H5P_DEFAULT),
                     path, "create dataset", name),
            H5Dclose};
  }
};

// Extend the [F][...] dataset `dset` (rank <= 5, `inner` the sizes after the frame axis) to
// frame + 1 frames and write `data` (selected by `mem_space`) as frame `frame`. A frame with no
// elements (an inner size of 0) is only extended.
inline void append_frame(hid_t dset, int rank, const hsize_t* inner, hsize_t frame, hid_t mem_type,
                         hid_t mem_space, const void* data, const std::string& path,
                         const std::string& name) {
  hsize_t dims[5] = {frame + 1, 0, 0, 0, 0};
  hsize_t start[5] = {frame, 0, 0, 0, 0};
  hsize_t count[5] = {1, 0, 0, 0, 0};
  bool empty = false;
  for (int d = 1; d < rank; ++d) {
    dims[d] = count[d] = inner[d - 1];
    empty = empty || inner[d - 1] == 0;
  }
  check(H5Dset_extent(dset, dims), path, "extend dataset", name);
  if (empty) return;
  Handle space{check_id(H5Dget_space(dset), path, "get dataspace of", name), H5Sclose};
  check(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr), path,
        "select frame in", name);
  check(H5Dwrite(dset, mem_type, mem_space, space.get(), H5P_DEFAULT, data), path, "write frame to",
        name);
}

// ---- Resume: reopen an existing file, check it, drop frames written after a checkpoint. ----

// Nothing when `path` is a readable HDF5 file, else what to add to the caller's message: " (the
// library's reason)", or "" when it gives none.
inline std::optional<std::string> not_hdf5(const std::string& path) {
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
  const std::string detail = hdf5_error_detail();
  if (is_hdf5 > 0) return std::nullopt;
  return detail.empty() ? std::string() : " (" + detail + ")";
}

// Open `path` (H5F_ACC_RDONLY or H5F_ACC_RDWR) without file locking: the writers create their
// files so, and a reader must open a file a live run holds for writing.
inline Handle open_unlocked(const std::string& path, unsigned flags, const char* op) {
  Handle fapl{check_id(H5Pcreate(H5P_FILE_ACCESS), path, "create property list"), H5Pclose};
#if H5_VERS_MAJOR > 1 || (H5_VERS_MAJOR == 1 && H5_VERS_MINOR >= 13) ||                            \
    (H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 12 && H5_VERS_RELEASE >= 1) ||                         \
    (H5_VERS_MAJOR == 1 && H5_VERS_MINOR == 10 && H5_VERS_RELEASE >= 7)
  check(H5Pset_file_locking(fapl.get(), false, true), path, "disable file locking");
#endif
  return {check_id(H5Fopen(path.c_str(), flags, fapl.get()), path, op), H5Fclose};
}

// Open the existing file `path` without file locking (as the writers create theirs), read-write
// or read-only. No file, a symbolic link, or not an HDF5 file: std::runtime_error starting with
// `who`.
inline Handle open_existing(const std::string& path, const std::string& who, bool write = true) {
  const safe_file::Kind kind = safe_file::kind(path);
  if (kind == safe_file::Kind::missing)
    throw std::runtime_error(who + ": cannot resume, the file does not exist");
  if (kind != safe_file::Kind::regular)
    throw std::runtime_error(who + ": cannot resume, it is " + safe_file::to_string(kind));
  if (const auto why = not_hdf5(path))
    throw std::runtime_error(who + ": cannot resume, not a readable HDF5 file" + *why);
  return open_unlocked(path, write ? H5F_ACC_RDWR : H5F_ACC_RDONLY,
                       write ? "open file for resume" : "open file");
}

// Open an existing HDF5 file read-only, without file locking (a live run may hold it open for
// writing; it flushes after every frame). std::runtime_error naming `path` when it does not
// exist (`what`: what such a file holds, for the message) or is not a readable HDF5 file.
inline Handle open_for_reading(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw std::runtime_error("'" + path + "': no such file (" + what + ")");
  if (const auto why = not_hdf5(path))
    throw std::runtime_error("'" + path + "' is not a readable HDF5 file" + *why);
  return open_unlocked(path, H5F_ACC_RDONLY, "open file");
}

// Create `path` for writing: an existing regular file there is replaced, anything else (a link,
// dangling or not, a directory) refused; the file is then created exclusively (H5F_ACC_EXCL:
// open(2) with O_EXCL, which never follows a link).
inline Handle create_file(const std::string& path, hid_t fapl) {
  const safe_file::Kind kind = safe_file::kind(path);
  if (kind != safe_file::Kind::missing && kind != safe_file::Kind::regular)
    throw std::runtime_error("cannot create '" + path + "': it is " + safe_file::to_string(kind) +
                             " (fluidem does not write through links or over other files)");
  if (kind == safe_file::Kind::regular) safe_file::remove_quietly(path);
  return {check_id(H5Fcreate(path.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl), path, "create file"),
          H5Fclose};
}

inline Handle open_group(hid_t parent, const std::string& name, const std::string& path) {
  return {check_id(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), path, "open group", name),
          H5Gclose};
}

inline Handle open_dataset(hid_t parent, const std::string& name, const std::string& path) {
  return {check_id(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), path, "open dataset", name),
          H5Dclose};
}

inline Handle open_attr(hid_t obj, const std::string& name, const std::string& path) {
  return {check_id(H5Aopen(obj, name.c_str(), H5P_DEFAULT), path, "open attribute", name),
          H5Aclose};
}

// The current dimensions of a dataset.
inline std::vector<hsize_t> extent(hid_t dset, const std::string& path, const std::string& name) {
  Handle space{check_id(H5Dget_space(dset), path, "get dataspace of", name), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(path, "get rank of", name);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0)
    fail(path, "get dimensions of", name);
  return dims;
}

// The whole of a 1-D (or, with `n` set, any) dataset converted to `mem_type`.
template <class T>
std::vector<T> read_all(hid_t dset, hid_t mem_type, std::size_t n, const std::string& path,
                        const std::string& name) {
  std::vector<T> out(n);
  if (n > 0)
    check(H5Dread(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), path, "read dataset",
          name);
  return out;
}

// A fixed-length string array attribute (as Builder::string_array_attr writes it).
inline std::vector<std::string> read_string_array_attr(hid_t obj, const char* name,
                                                       const std::string& path) {
  Handle attr = open_attr(obj, name, path);
  Handle type{check_id(H5Aget_type(attr.get()), path, "get type of attribute", name), H5Tclose};
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) != 0)
    throw std::runtime_error("'" + path + "': attribute '" + name +
                             "' is not a fixed-length string array");
  const std::size_t width = H5Tget_size(type.get());
  Handle space{check_id(H5Aget_space(attr.get()), path, "get dataspace of attribute", name),
               H5Sclose};
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0 || width == 0) fail(path, "get size of attribute", name);
  std::vector<char> buffer(width * static_cast<std::size_t>(count) + 1, '\0');
  check(H5Aread(attr.get(), type.get(), buffer.data()), path, "read attribute", name);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
    const char* s = buffer.data() + i * width;
    out.emplace_back(s, std::find(s, s + width, '\0'));
  }
  return out;
}

// Shrink the frame axis (the first) of `dset` to `frames` (chunked datasets only; the chunks past
// the new end are freed, a partly cut chunk keeps its allocation).
inline void shrink_frames(hid_t dset, hsize_t frames, const std::string& path,
                          const std::string& name) {
  std::vector<hsize_t> dims = extent(dset, path, name);
  if (dims.empty() || dims[0] == frames) return;
  dims[0] = frames;
  check(H5Dset_extent(dset, dims.data()), path, "shrink dataset", name);
}

// How many leading frames a resumed file keeps: exactly the frames the checkpoint's run had
// written (`expected`, their times), which the file must hold complete (`complete`: the frames
// every time-dependent dataset holds) with bitwise the same times. Otherwise std::runtime_error
// starting with `who`: the file stops short of the checkpoint (a gap), or holds other frames
// (the output of another run).
inline hsize_t frames_to_keep(const std::vector<double>& times, hsize_t complete,
                              const std::vector<double>& expected, const std::string& who) {
  const auto at = [](const std::vector<double>& t, std::size_t k) {
    return std::to_string(t[k]) + " s";
  };
  const hsize_t have = std::min<hsize_t>(complete, times.size());
  if (have < expected.size())
    throw std::runtime_error(
        who + ": the file holds " + std::to_string(have) + " complete frames" +
        (have > 0 ? " (the last at t = " + at(times, have - 1) + ")" : std::string()) +
        ", the checkpoint's run had written " + std::to_string(expected.size()) +
        " (the last at t = " + at(expected, expected.size() - 1) +
        "): the outputs do not reach the checkpoint, continuing them would leave a gap");
  for (std::size_t k = 0; k < expected.size(); ++k)
    if (times[k] != expected[k])
      throw std::runtime_error(who + ": frame " + std::to_string(k) + " is at t = " + at(times, k) +
                               " in the file and at t = " + at(expected, k) +
                               " in the checkpoint's record: the file holds another run's frames");
  return expected.size();
}

// A scalar string attribute (as Builder::string_attr writes it); empty when there is none.
inline std::string read_string_attr(hid_t obj, const char* name, const std::string& path) {
  if (H5Aexists(obj, name) <= 0) {
    hdf5_error_detail(); // clear the stack of the lookup
    return {};
  }
  Handle attr = open_attr(obj, name, path);
  Handle type{check_id(H5Aget_type(attr.get()), path, "get type of attribute", name), H5Tclose};
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) != 0)
    throw std::runtime_error("'" + path + "': attribute '" + name +
                             "' is not a fixed-length string");
  std::vector<char> buffer(H5Tget_size(type.get()) + 1, '\0');
  check(H5Aread(attr.get(), type.get(), buffer.data()), path, "read attribute", name);
  return std::string(buffer.data());
}

// The run id attribute of `obj` must be `run_id` (std::runtime_error starting with `who`).
inline void check_run_id(hid_t obj, const std::string& run_id, const std::string& path,
                         const std::string& who) {
  const std::string in_file = read_string_attr(obj, "run_id", path);
  if (in_file != run_id)
    throw std::runtime_error(
        who + ": the file belongs to " +
        (in_file.empty() ? std::string("a run without an id") : "run " + in_file) +
        ", the checkpoint to run " + run_id + ": it cannot be continued by this checkpoint");
}

// Drops frames from the existing file `path` without ever leaving it half-edited: a copy
// ("<path>.resume.tmp") is edited by `edit(file)`, flushed, synced and renamed over `path`.
template <class Edit>
void edit_copy(const std::string& path, Edit&& edit) {
  const std::string tmp = path + ".resume.tmp";
  safe_file::copy(path, tmp);
  try {
    Handle file = open_existing(tmp, "resume", true);
    edit(file.get(), tmp);
    check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), tmp, "flush file");
    check(file.reset(), tmp, "close file");
    safe_file::sync_close(safe_file::open_read(tmp), tmp);
  } catch (...) {
    safe_file::remove_quietly(tmp);
    throw;
  }
  safe_file::rename_over(tmp, path);
}

// a == b up to rounding (for grid and box geometry written as doubles and read back).
inline bool same_double(double a, double b) {
  return std::fabs(a - b) <= 1e-12 * std::max({1e-300, std::fabs(a), std::fabs(b)}) || (a == b);
}

} // namespace fluidem::hdf5
