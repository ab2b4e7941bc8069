// The checkpoint file (OUT/checkpoint.h5): a flat set of named arrays (names may contain '/',
// stored as HDF5 groups) of double, int64, int32, uint32 or uint8, plus a format tag and a
// checksum over every array, so that a truncated or corrupted file is rejected with a message
// naming the file instead of restarting from garbage.
//
// Writing is atomic: the arrays go to "<path>.tmp", which is flushed to disk (fsync) and then
// renamed over <path>; the checkpoint it replaces is first hard-linked (or copied) to
// "<stem>.prev.h5", so a crash, a full disk or a failed write at any moment leaves the previous
// checkpoint loadable, and a corrupted current one has a fall-back.
// The simulation decides what goes in (src/integrate/simulation_checkpoint.cpp).
#pragma once
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace fluidem {

/// A checkpoint that cannot be read: missing, truncated, corrupted, of another format, or
/// lacking an array (the message names the file and what is wrong).
class CheckpointError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Collects the arrays (copies, or views of the caller's arrays) in memory; commit() writes them
/// atomically.
class CheckpointWriter {
public:
  explicit CheckpointWriter(std::string path) : path_(std::move(path)) {}
  /// Like put, without a copy: `v` must stay alive and unchanged until commit() (the large
  /// arrays of a run: a copy of them all would double the run's memory while it checkpoints).
  template <class T>
  void put_view(const std::string& name, const std::vector<T>& v) {
    Array a;
    a.type = type_code<T>();
    a.count = v.size();
    a.view = reinterpret_cast<const unsigned char*>(v.data());
    a.view_bytes = v.size() * sizeof(T);
    arrays_[name] = std::move(a);
  }
  void put(const std::string& name, const std::vector<double>& v);
  void put(const std::string& name, const std::vector<std::int64_t>& v);
  void put(const std::string& name, const std::vector<std::int32_t>& v);
  void put(const std::string& name, const std::vector<std::uint32_t>& v);
  void put(const std::string& name, const std::vector<std::uint8_t>& v);
  void put_scalar(const std::string& name, double v) { put(name, std::vector<double>{v}); }
  void put_scalar(const std::string& name, std::int64_t v) {
    put(name, std::vector<std::int64_t>{v});
  }
  void put_string(const std::string& name, const std::string& s) {
    put(name, std::vector<std::uint8_t>(s.begin(), s.end()));
  }
  /// Writes <path>.tmp, syncs it, keeps the old <path> as <stem>.prev.h5, renames. Throws
  /// std::runtime_error naming the file (the previous checkpoint is then untouched).
  void commit() const;
  const std::string& path() const { return path_; }

private:
  struct Array {
    int type = 0;                        ///< 0 double, 1 int64, 2 int32, 3 uint32, 4 uint8
    std::vector<unsigned char> bytes;    ///< a copy (put), or
    const unsigned char* view = nullptr; ///< the caller's array (put_view)
    std::size_t view_bytes = 0;
    std::size_t count = 0;
    const unsigned char* data() const { return view ? view : bytes.data(); }
    std::size_t size() const { return view ? view_bytes : bytes.size(); }
  };
  template <class T>
  static constexpr int type_code() {
    if constexpr (std::is_same_v<T, double>)
      return 0;
    else if constexpr (std::is_same_v<T, std::int64_t>)
      return 1;
    else if constexpr (std::is_same_v<T, std::int32_t>)
      return 2;
    else if constexpr (std::is_same_v<T, std::uint32_t>)
      return 3;
    else {
      static_assert(std::is_same_v<T, std::uint8_t>, "checkpoint arrays: double, int64, int32, "
                                                     "uint32 or uint8");
      return 4;
    }
  }
  void put_bytes(const std::string& name, int type, const void* data, std::size_t count,
                 std::size_t size);
  std::string path_;
  std::map<std::string, Array> arrays_;
};

/// Reads every array and verifies the format tag and the checksum in the constructor.
class CheckpointReader {
public:
  explicit CheckpointReader(std::string path);
  bool has(const std::string& name) const { return arrays_.count(name) > 0; }
  std::vector<double> doubles(const std::string& name) const;
  std::vector<std::int64_t> int64s(const std::string& name) const;
  std::vector<std::int32_t> int32s(const std::string& name) const;
  std::vector<std::uint32_t> uint32s(const std::string& name) const;
  std::vector<std::uint8_t> bytes(const std::string& name) const;
  double scalar(const std::string& name) const;
  std::int64_t integer(const std::string& name) const;
  std::string string(const std::string& name) const;
  const std::string& path() const { return path_; }
  /// The names of every array and scalar the file holds, sorted; the stored bytes of one.
  std::vector<std::string> names() const {
    std::vector<std::string> n;
    for (const auto& [name, a] : arrays_) n.push_back(name);
    return n;
  }
  const std::vector<unsigned char>& stored_bytes(const std::string& name) const {
    return arrays_.at(name).bytes;
  }

private:
  struct Array {
    int type = 0;
    std::vector<unsigned char> bytes;
    std::size_t count = 0;
    const unsigned char* data() const { return bytes.data(); }
    std::size_t size() const { return bytes.size(); }
  };
  const Array& get(const std::string& name, int type) const;
  std::string path_;
  std::map<std::string, Array> arrays_;
};

/// "<dir>/checkpoint.prev.h5" for "<dir>/checkpoint.h5".
std::string previous_checkpoint_path(const std::string& path);

} // namespace fluidem
