#include "output/checkpoint_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>

#include "output/hdf5_support.hpp"
#include "output/safe_file.hpp"

namespace fluidem {

namespace {

namespace fs = std::filesystem;
using hdf5::check;
using hdf5::check_id;
using hdf5::Handle;

constexpr const char* kFormat = "fluidem-checkpoint/1";

hid_t file_type(int type) {
  switch (type) {
  case 0:
    return H5T_IEEE_F64LE;
  case 1:
    return H5T_STD_I64LE;
  case 2:
    return H5T_STD_I32LE;
  case 3:
    return H5T_STD_U32LE;
  default:
    return H5T_STD_U8LE;
  }
}

hid_t mem_type(int type) {
  switch (type) {
  case 0:
    return H5T_NATIVE_DOUBLE;
  case 1:
    return H5T_NATIVE_INT64;
  case 2:
    return H5T_NATIVE_INT32;
  case 3:
    return H5T_NATIVE_UINT32;
  default:
    return H5T_NATIVE_UINT8;
  }
}

std::size_t type_size(int type) {
  static const std::size_t sizes[5] = {8, 8, 4, 4, 1};
  return sizes[type];
}

/// FNV-1a, 64 bit, continued from h.
std::uint64_t fnv1a(std::uint64_t h, const void* data, std::size_t n) {
  const auto* b = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h ^= b[i];
    h *= 1099511628211ULL;
  }
  return h;
}

/// Checksum over the names, types, counts and bytes of all arrays in name order.
template <class Map>
std::uint64_t checksum(const Map& arrays) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const auto& [name, a] : arrays) {
    h = fnv1a(h, name.data(), name.size());
    const unsigned char t = static_cast<unsigned char>(a.type);
    h = fnv1a(h, &t, 1);
    const std::uint64_t c = a.count;
    h = fnv1a(h, &c, sizeof c);
    h = fnv1a(h, a.data(), a.size());
  }
  return h;
}

/// Silences HDF5's own error printing while alive (errors are reported by exceptions).
class QuietHdf5 {
public:
  QuietHdf5() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

} // namespace

std::string previous_checkpoint_path(const std::string& path) {
  fs::path p(path);
  return (p.parent_path() / (p.stem().string() + ".prev" + p.extension().string())).string();
}

void CheckpointWriter::put_bytes(const std::string& name, int type, const void* data,
                                 std::size_t count, std::size_t size) {
  Array a;
  a.type = type;
  a.count = count;
  a.bytes.resize(count * size);
  if (count > 0) std::memcpy(a.bytes.data(), data, count * size);
  arrays_[name] = std::move(a);
}

void CheckpointWriter::put(const std::string& name, const std::vector<double>& v) {
  put_bytes(name, 0, v.data(), v.size(), sizeof(double));
}
void CheckpointWriter::put(const std::string& name, const std::vector<std::int64_t>& v) {
  put_bytes(name, 1, v.data(), v.size(), sizeof(std::int64_t));
}
void CheckpointWriter::put(const std::string& name, const std::vector<std::int32_t>& v) {
  put_bytes(name, 2, v.data(), v.size(), sizeof(std::int32_t));
}
void CheckpointWriter::put(const std::string& name, const std::vector<std::uint32_t>& v) {
  put_bytes(name, 3, v.data(), v.size(), sizeof(std::uint32_t));
}
void CheckpointWriter::put(const std::string& name, const std::vector<std::uint8_t>& v) {
  put_bytes(name, 4, v.data(), v.size(), 1);
}

void CheckpointWriter::commit() const {
  const std::string tmp = safe_file::temporary_for(path_);
  try {
    {
      QuietHdf5 quiet;
      const hdf5::Builder b{tmp};
      Handle file = hdf5::create_file(tmp, H5P_DEFAULT); // exclusive: never through a link
      b.string_attr(file.get(), "format", kFormat);
      const std::uint64_t sum = checksum(arrays_);
      b.scalar_attr(file.get(), "checksum", H5T_STD_U64LE, H5T_NATIVE_UINT64, &sum);
      Handle lcpl{check_id(H5Pcreate(H5P_LINK_CREATE), tmp, "create property list"), H5Pclose};
      check(H5Pset_create_intermediate_group(lcpl.get(), 1), tmp, "set property");
      // No modification times in the objects: the same state gives the same bytes.
      Handle dcpl{check_id(H5Pcreate(H5P_DATASET_CREATE), tmp, "create property list"), H5Pclose};
      check(H5Pset_obj_track_times(dcpl.get(), 0), tmp, "set property");
      for (const auto& [name, a] : arrays_) {
        const hsize_t dims[1] = {a.count};
        Handle space = b.simple_space(1, dims);
        Handle dset{check_id(H5Dcreate2(file.get(), name.c_str(), file_type(a.type), space.get(),
                                        lcpl.get(), dcpl.get(), H5P_DEFAULT),
                             tmp, "create dataset", name),
                    H5Dclose};
        if (a.count > 0)
          check(H5Dwrite(dset.get(), mem_type(a.type), H5S_ALL, H5S_ALL, H5P_DEFAULT, a.data()),
                tmp, "write dataset", name);
      }
      check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), tmp, "flush file");
      check(file.reset(), tmp, "close file");
    }
    safe_file::sync_close(safe_file::open_read(tmp), tmp);
  } catch (...) { // a full disk, say: the previous checkpoint stays as it was, no temporary left
    safe_file::remove_quietly(tmp);
    throw;
  }
  if (safe_file::kind(path_) == safe_file::Kind::regular) {
    const std::string prev = previous_checkpoint_path(path_);
    safe_file::remove_quietly(prev);
    std::error_code ec;
    fs::create_hard_link(path_, prev, ec); // (link(2) does not follow links)
    if (ec) {
      safe_file::remove_quietly(prev);
      safe_file::copy(path_, prev);
    }
  }
  safe_file::rename_over(tmp, path_); // atomic: <path> is always a complete checkpoint
}

CheckpointReader::CheckpointReader(std::string path) : path_(std::move(path)) {
  const std::string prev = previous_checkpoint_path(path_);
  const std::string hint = fs::exists(prev) && prev != path_
                               ? " (the previous checkpoint is " + prev + ")"
                               : std::string();
  auto bad = [&](const std::string& what) {
    return CheckpointError("checkpoint '" + path_ + "' " + what + hint);
  };
  if (!fs::exists(path_)) throw bad("does not exist");
  std::error_code size_ec;
  const auto file_bytes = fs::file_size(path_, size_ec);
  if (size_ec) throw bad("cannot be read: " + size_ec.message());
  QuietHdf5 quiet;
  if (H5Fis_hdf5(path_.c_str()) <= 0)
    throw bad("is not a readable HDF5 file (truncated or corrupted)");
  Handle file{H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  if (!file.valid()) throw bad("cannot be opened (truncated or corrupted)");
  // Format tag.
  {
    if (H5Aexists(file.get(), "format") <= 0) throw bad("is not a fluidem checkpoint");
    Handle attr{H5Aopen(file.get(), "format", H5P_DEFAULT), H5Aclose};
    Handle type{H5Aget_type(attr.get()), H5Tclose};
    const std::size_t n = attr.valid() && type.valid() ? H5Tget_size(type.get()) : 0;
    std::string s(n, '\0');
    if (n == 0 || H5Aread(attr.get(), type.get(), s.data()) < 0)
      throw bad("has an unreadable format tag");
    s.resize(std::strlen(s.c_str()));
    if (s != kFormat) throw bad("has format '" + s + "', expected '" + kFormat + "'");
  }
  std::uint64_t stored = 0;
  {
    Handle attr{H5Aopen(file.get(), "checksum", H5P_DEFAULT), H5Aclose};
    if (!attr.valid() || H5Aread(attr.get(), H5T_NATIVE_UINT64, &stored) < 0)
      throw bad("has no checksum");
  }
  // Every dataset, by its path.
  std::vector<std::string> names;
  const herr_t visited = H5Ovisit(
      file.get(), H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
        if (info->type == H5O_TYPE_DATASET)
          static_cast<std::vector<std::string>*>(data)->push_back(name);
        return 0;
      },
      &names);
  if (visited < 0) throw bad("cannot be listed (corrupted)");
  for (const std::string& name : names) {
    Handle dset{H5Dopen2(file.get(), name.c_str(), H5P_DEFAULT), H5Dclose};
    Handle type{dset.valid() ? H5Dget_type(dset.get()) : H5I_INVALID_HID, H5Tclose};
    Handle space{dset.valid() ? H5Dget_space(dset.get()) : H5I_INVALID_HID, H5Sclose};
    if (!type.valid() || !space.valid()) throw bad("has an unreadable array '" + name + "'");
    int t = -1;
    const H5T_class_t cls = H5Tget_class(type.get());
    const std::size_t size = H5Tget_size(type.get());
    if (cls == H5T_FLOAT && size == 8) t = 0;
    if (cls == H5T_INTEGER) {
      const bool sign = H5Tget_sign(type.get()) == H5T_SGN_2;
      if (size == 8 && sign) t = 1;
      if (size == 4 && sign) t = 2;
      if (size == 4 && !sign) t = 3;
      if (size == 1 && !sign) t = 4;
    }
    if (t < 0) throw bad("has array '" + name + "' of an unknown type");
    const hssize_t count = H5Sget_simple_extent_npoints(space.get());
    if (count < 0) throw bad("has an unreadable array '" + name + "'");
    // Uncompressed arrays cannot hold more bytes than the file (a corrupted size would
    // otherwise ask for any amount of memory).
    if (static_cast<double>(count) * static_cast<double>(type_size(t)) >
        static_cast<double>(file_bytes))
      throw bad("is corrupted: array '" + name + "' claims more data than the file holds");
    Array a;
    a.type = t;
    a.count = static_cast<std::size_t>(count);
    a.bytes.resize(a.count * type_size(t));
    if (a.count > 0 &&
        H5Dread(dset.get(), mem_type(t), H5S_ALL, H5S_ALL, H5P_DEFAULT, a.bytes.data()) < 0)
      throw bad("has an unreadable array '" + name + "' (truncated or corrupted)");
    arrays_[name] = std::move(a);
  }
  if (checksum(arrays_) != stored)
    throw bad("is corrupted: its checksum does not match its contents");
}

const CheckpointReader::Array& CheckpointReader::get(const std::string& name, int type) const {
  auto it = arrays_.find(name);
  if (it == arrays_.end())
    throw CheckpointError("checkpoint '" + path_ + "' lacks '" + name +
                          "' (written by another fluidem version or for another case?)");
  if (it->second.type != type)
    throw CheckpointError("checkpoint '" + path_ + "': '" + name + "' has the wrong type");
  return it->second;
}

namespace {
template <class T, class A>
std::vector<T> as_vector(const A& a) {
  std::vector<T> v(a.count);
  if (a.count > 0) std::memcpy(v.data(), a.bytes.data(), a.count * sizeof(T));
  return v;
}
} // namespace

std::vector<double> CheckpointReader::doubles(const std::string& name) const {
  return as_vector<double>(get(name, 0));
}
std::vector<std::int64_t> CheckpointReader::int64s(const std::string& name) const {
  return as_vector<std::int64_t>(get(name, 1));
}
std::vector<std::int32_t> CheckpointReader::int32s(const std::string& name) const {
  return as_vector<std::int32_t>(get(name, 2));
}
std::vector<std::uint32_t> CheckpointReader::uint32s(const std::string& name) const {
  return as_vector<std::uint32_t>(get(name, 3));
}
std::vector<std::uint8_t> CheckpointReader::bytes(const std::string& name) const {
  return as_vector<std::uint8_t>(get(name, 4));
}
double CheckpointReader::scalar(const std::string& name) const {
  const auto v = doubles(name);
  if (v.size() != 1)
    throw CheckpointError("checkpoint '" + path_ + "': '" + name + "' is not a scalar");
  return v[0];
}
std::int64_t CheckpointReader::integer(const std::string& name) const {
  const auto v = int64s(name);
  if (v.size() != 1)
    throw CheckpointError("checkpoint '" + path_ + "': '" + name + "' is not a scalar");
  return v[0];
}
std::string CheckpointReader::string(const std::string& name) const {
  const auto v = bytes(name);
  return std::string(v.begin(), v.end());
}

} // namespace fluidem
