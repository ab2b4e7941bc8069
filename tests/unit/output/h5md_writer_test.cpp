// H5mdWriter: write small synthetic trajectories, read them back with the HDF5 C API and check the
// H5MD layout, shapes, types and values (bitwise); then run python/fluidem_plot.py on the result.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "output/h5md_reader.hpp"
#include "output/h5md_writer.hpp"
#include "output/series_writer.hpp"

namespace fs = std::filesystem;
using fluidem::H5mdBox;
using fluidem::H5mdWriter;
using fluidem::ParticleStore;

namespace {

// A fresh directory per test, removed afterwards.
class TempDir {
public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("fluidem_h5md_" + std::to_string(::getpid()) + "_" +
                                         info->test_suite_name() + "_" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    if (std::getenv("FLUIDEM_KEEP_TEST_FILES") != nullptr) return;
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }

private:
  fs::path path_;
};

// Frame k of a synthetic run: awkward doubles so that a bitwise comparison means something.
ParticleStore make_frame(std::size_t n, int k, bool three_d = false) {
  ParticleStore p;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) + 0.1 * k;
    const double r = 1e-3 * (1.0 + 0.25 * static_cast<double>(i % 3));
    const double y = three_d ? 2e-3 * std::cos(3.0 * s) : 0.0;
    p.add({1e-2 * std::sin(s) + 0.02, y, 0.01 + 3e-3 * static_cast<double>(i) + 1e-4 * k},
          {std::cos(s) / 3.0, three_d ? 0.1 * s : 0.0, -std::sin(s) / 7.0}, r, 2500.0,
          static_cast<std::int32_t>(i % 3), 1000 + static_cast<std::int64_t>(i));
    p.wx.back() = 1.0 / (s + 1.0);
    p.wy.back() = -std::sqrt(s + 2.0);
    p.wz.back() = std::exp(-s);
  }
  return p;
}

// --- reading back with the C API ---------------------------------------------------------------

struct Dataset {
  std::vector<hsize_t> dims;
  hid_t type_class = -1;
  std::size_t type_size = 0;
  bool type_signed = false;
};

Dataset info(hid_t file, const char* path) {
  Dataset d;
  const hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
  EXPECT_GE(ds, 0) << path;
  if (ds < 0) return d;
  const hid_t space = H5Dget_space(ds);
  const int rank = H5Sget_simple_extent_ndims(space);
  d.dims.resize(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space, d.dims.data(), nullptr);
  const hid_t type = H5Dget_type(ds);
  d.type_class = H5Tget_class(type);
  d.type_size = H5Tget_size(type);
  d.type_signed = d.type_class == H5T_INTEGER && H5Tget_sign(type) == H5T_SGN_2;
  H5Tclose(type);
  H5Sclose(space);
  H5Dclose(ds);
  return d;
}

template <class T>
std::vector<T> read_all(hid_t file, const char* path, hid_t mem_type) {
  const hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
  EXPECT_GE(ds, 0) << path;
  if (ds < 0) return {};
  const hid_t space = H5Dget_space(ds);
  std::vector<T> out(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  if (!out.empty()) {
    EXPECT_GE(H5Dread(ds, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), 0) << path;
  }
  H5Sclose(space);
  H5Dclose(ds);
  return out;
}

std::string read_string_attr(hid_t file, const char* object, const char* name) {
  const hid_t attr = H5Aopen_by_name(file, object, name, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(attr, 0) << object << " @" << name;
  if (attr < 0) return {};
  const hid_t type = H5Aget_type(attr);
  EXPECT_EQ(H5Tget_class(type), H5T_STRING);
  EXPECT_FALSE(H5Tis_variable_str(type));
  std::vector<char> buf(H5Tget_size(type) + 1, '\0');
  EXPECT_GE(H5Aread(attr, type, buf.data()), 0);
  H5Tclose(type);
  H5Aclose(attr);
  return std::string(buf.data());
}

std::vector<std::string> read_string_array_attr(hid_t file, const char* object, const char* name) {
  const hid_t attr = H5Aopen_by_name(file, object, name, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(attr, 0) << object << " @" << name;
  if (attr < 0) return {};
  const hid_t type = H5Aget_type(attr);
  const hid_t space = H5Aget_space(attr);
  const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
  const std::size_t width = H5Tget_size(type);
  std::vector<char> buf(n * width + 1, '\0');
  EXPECT_GE(H5Aread(attr, type, buf.data()), 0);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n; ++i)
    out.emplace_back(buf.data() + i * width, strnlen(buf.data() + i * width, width));
  H5Sclose(space);
  H5Tclose(type);
  H5Aclose(attr);
  return out;
}

template <class T>
std::vector<T> read_attr(hid_t file, const char* object, const char* name, hid_t mem_type) {
  const hid_t attr = H5Aopen_by_name(file, object, name, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(attr, 0) << object << " @" << name;
  if (attr < 0) return {};
  const hid_t space = H5Aget_space(attr);
  std::vector<T> out(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  EXPECT_GE(H5Aread(attr, mem_type, out.data()), 0);
  H5Sclose(space);
  H5Aclose(attr);
  return out;
}

bool bitwise_equal(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Exit status of a shell command (-1 if it did not exit normally).
int run(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1 || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

bool python_has_plot_modules() {
  static const bool ok = run(std::string(FLUIDEM_PYTHON) +
                             " -c 'import h5py, numpy, matplotlib' >/dev/null 2>&1") == 0;
  return ok;
}

std::string plot_script() {
  return std::string(FLUIDEM_SOURCE_DIR) + "/python/fluidem_plot.py";
}

constexpr std::size_t kN = 7;
constexpr int kFrames = 3;
const long kSteps[kFrames] = {0, 250, 500};
const double kTimes[kFrames] = {0.0, 2.5e-4 / 3.0, 5.0e-4 + 1e-19};

// Write the standard 7-particle, 3-frame file.
void write_standard(const std::string& path, bool three_d = false) {
  H5mdBox box;
  box.lo = {0.0, -0.005, 0.0};
  box.hi = {0.04, 0.005, 0.1};
  box.periodic = {true, false, false};
  H5mdWriter w(path, kN, three_d ? 3 : 2, "0.1.0-test", box, "Test Author");
  for (int k = 0; k < kFrames; ++k) w.write_frame(kSteps[k], kTimes[k], make_frame(kN, k, three_d));
  EXPECT_EQ(w.frames(), static_cast<std::size_t>(kFrames));
}

} // namespace

TEST(H5mdWriter, WritesH5mdMetadata) {
  TempDir dir;
  const std::string path = dir.file("particles.h5");
  write_standard(path);

  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(read_attr<int>(f, "/h5md", "version", H5T_NATIVE_INT), (std::vector<int>{1, 1}));
  EXPECT_EQ(read_string_attr(f, "/h5md/author", "name"), "Test Author");
  EXPECT_EQ(read_string_attr(f, "/h5md/creator", "name"), "fluidem");
  EXPECT_EQ(read_string_attr(f, "/h5md/creator", "version"), "0.1.0-test");
  EXPECT_EQ(read_attr<int>(f, "/h5md/modules/units", "version", H5T_NATIVE_INT),
            (std::vector<int>{1, 0}));
  EXPECT_EQ(read_string_attr(f, "/h5md/modules/units", "system"), "SI");
  EXPECT_EQ(read_attr<int>(f, "/parameters", "dimension", H5T_NATIVE_INT), (std::vector<int>{2}));

  EXPECT_EQ(read_attr<int>(f, "/particles/all/box", "dimension", H5T_NATIVE_INT),
            (std::vector<int>{3}));
  EXPECT_EQ(read_string_array_attr(f, "/particles/all/box", "boundary"),
            (std::vector<std::string>{"periodic", "none", "none"}));
  EXPECT_EQ(read_all<double>(f, "/particles/all/box/edges", H5T_NATIVE_DOUBLE),
            (std::vector<double>{0.04, 0.01, 0.1}));
  EXPECT_EQ(read_all<double>(f, "/particles/all/box/offset", H5T_NATIVE_DOUBLE),
            (std::vector<double>{0.0, -0.005, 0.0}));
  EXPECT_EQ(read_attr<std::int64_t>(f, "/particles/all", "frames", H5T_NATIVE_INT64),
            (std::vector<std::int64_t>{kFrames}));
  EXPECT_EQ(read_string_attr(f, "/particles/all/position/value", "unit"), "m");
  EXPECT_EQ(read_string_attr(f, "/particles/all/velocity/value", "unit"), "m s-1");
  EXPECT_EQ(read_string_attr(f, "/particles/all/position/time", "unit"), "s");

  const auto index = read_all<std::int64_t>(f, fluidem::kH5mdVertexIndexPath, H5T_NATIVE_INT64);
  ASSERT_EQ(index.size(), kN);
  for (std::size_t i = 0; i < kN; ++i) EXPECT_EQ(index[i], static_cast<std::int64_t>(i));
  H5Fclose(f);
}

TEST(H5mdWriter, ShapesTypesAndStepTime) {
  TempDir dir;
  const std::string path = dir.file("particles.h5");
  write_standard(path);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);

  const std::vector<hsize_t> vec_dims{kFrames, kN, 3};
  const std::vector<hsize_t> scalar_dims{kFrames, kN};
  for (const char* name : {"position", "velocity", "angular_velocity"}) {
    const Dataset d = info(f, (std::string("/particles/all/") + name + "/value").c_str());
    EXPECT_EQ(d.dims, vec_dims) << name;
    EXPECT_EQ(d.type_class, H5T_FLOAT) << name;
    EXPECT_EQ(d.type_size, 8u) << name;
  }
  Dataset d = info(f, "/particles/all/radius/value");
  EXPECT_EQ(d.dims, scalar_dims);
  EXPECT_EQ(d.type_class, H5T_FLOAT);
  EXPECT_EQ(d.type_size, 8u);
  d = info(f, "/particles/all/species/value");
  EXPECT_EQ(d.dims, scalar_dims);
  EXPECT_EQ(d.type_class, H5T_INTEGER);
  EXPECT_EQ(d.type_size, 4u);
  EXPECT_TRUE(d.type_signed);
  d = info(f, "/particles/all/id/value");
  EXPECT_EQ(d.dims, scalar_dims);
  EXPECT_EQ(d.type_class, H5T_INTEGER);
  EXPECT_EQ(d.type_size, 8u);

  for (const char* name : {"position", "velocity", "angular_velocity", "radius", "species", "id"}) {
    const std::string g = std::string("/particles/all/") + name;
    const Dataset s = info(f, (g + "/step").c_str());
    EXPECT_EQ(s.dims, (std::vector<hsize_t>{kFrames})) << name;
    EXPECT_EQ(s.type_class, H5T_INTEGER);
    EXPECT_EQ(s.type_size, 8u);
    const auto steps = read_all<std::int64_t>(f, (g + "/step").c_str(), H5T_NATIVE_INT64);
    const auto times = read_all<double>(f, (g + "/time").c_str(), H5T_NATIVE_DOUBLE);
    ASSERT_EQ(steps.size(), static_cast<std::size_t>(kFrames));
    ASSERT_EQ(times.size(), static_cast<std::size_t>(kFrames));
    for (int k = 0; k < kFrames; ++k) {
      EXPECT_EQ(steps[k], kSteps[k]) << name;
      EXPECT_TRUE(bitwise_equal(times[k], kTimes[k])) << name;
    }
  }

  // Value datasets: unlimited first dimension, one frame per chunk.
  const hid_t ds = H5Dopen2(f, "/particles/all/position/value", H5P_DEFAULT);
  const hid_t space = H5Dget_space(ds);
  hsize_t maxdims[3];
  H5Sget_simple_extent_dims(space, nullptr, maxdims);
  EXPECT_EQ(maxdims[0], H5S_UNLIMITED);
  const hid_t dcpl = H5Dget_create_plist(ds);
  hsize_t chunk[3];
  ASSERT_EQ(H5Pget_chunk(dcpl, 3, chunk), 3);
  EXPECT_EQ(chunk[0], 1u);
  EXPECT_EQ(chunk[1], kN);
  EXPECT_EQ(chunk[2], 3u);
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Dclose(ds);
  H5Fclose(f);
}

TEST(H5mdWriter, ValuesRoundTripBitwise) {
  TempDir dir;
  const std::string path = dir.file("particles.h5");
  write_standard(path, /*three_d=*/true);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const auto pos = read_all<double>(f, "/particles/all/position/value", H5T_NATIVE_DOUBLE);
  const auto vel = read_all<double>(f, "/particles/all/velocity/value", H5T_NATIVE_DOUBLE);
  const auto ang = read_all<double>(f, "/particles/all/angular_velocity/value", H5T_NATIVE_DOUBLE);
  const auto rad = read_all<double>(f, "/particles/all/radius/value", H5T_NATIVE_DOUBLE);
  const auto spc = read_all<std::int32_t>(f, "/particles/all/species/value", H5T_NATIVE_INT32);
  const auto ids = read_all<std::int64_t>(f, "/particles/all/id/value", H5T_NATIVE_INT64);
  H5Fclose(f);
  ASSERT_EQ(pos.size(), kFrames * kN * 3);
  ASSERT_EQ(rad.size(), kFrames * kN);

  int mismatches = 0;
  for (int k = 0; k < kFrames; ++k) {
    const ParticleStore p = make_frame(kN, k, true);
    for (std::size_t i = 0; i < kN; ++i) {
      const std::size_t v = (static_cast<std::size_t>(k) * kN + i) * 3;
      const std::size_t s = static_cast<std::size_t>(k) * kN + i;
      const double expect[9] = {p.x[i],  p.y[i],  p.z[i],  p.vx[i], p.vy[i],
                                p.vz[i], p.wx[i], p.wy[i], p.wz[i]};
      const double got[9] = {pos[v],     pos[v + 1], pos[v + 2], vel[v],    vel[v + 1],
                             vel[v + 2], ang[v],     ang[v + 1], ang[v + 2]};
      for (int c = 0; c < 9; ++c) mismatches += bitwise_equal(got[c], expect[c]) ? 0 : 1;
      mismatches += bitwise_equal(rad[s], p.radius[i]) ? 0 : 1;
      mismatches += spc[s] == p.species[i] ? 0 : 1;
      mismatches += ids[s] == p.id[i] ? 0 : 1;
    }
  }
  EXPECT_EQ(mismatches, 0);
}

// Charged particles: their charges (constant during a run) are written once, with the first
// frame, in the frame's order, as the time-independent element /particles/all/charge (unit C);
// an uncharged store writes none.
TEST(H5mdWriter, ChargesAreWrittenOnceInFrameOrder) {
  TempDir dir;
  const std::string charged = dir.file("charged.h5"), neutral = dir.file("neutral.h5");
  {
    H5mdWriter w(charged, kN, 2, "test");
    ParticleStore p = make_frame(kN, 0);
    for (std::size_t i = 0; i < kN; ++i) p.charge[i] = 1e-12 * (static_cast<double>(i) - 2.5);
    std::vector<std::uint32_t> order(kN);
    for (std::size_t k = 0; k < kN; ++k) order[k] = static_cast<std::uint32_t>(kN - 1 - k);
    w.write_frame(0, 0.0, p, &order);
    w.write_frame(1, 0.1, p, &order);
    H5mdWriter n(neutral, kN, 2, "test");
    n.write_frame(0, 0.0, make_frame(kN, 0));
  }
  const hid_t f = H5Fopen(charged.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const auto q = read_all<double>(f, "/particles/all/charge", H5T_NATIVE_DOUBLE);
  H5Fclose(f);
  ASSERT_EQ(q.size(), kN);
  for (std::size_t k = 0; k < kN; ++k)
    EXPECT_EQ(q[k], 1e-12 * (static_cast<double>(kN - 1 - k) - 2.5)) << k;
  const hid_t g = H5Fopen(neutral.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_EQ(H5Lexists(g, "/particles/all/charge", H5P_DEFAULT), 0);
  H5Fclose(g);
}

TEST(H5mdWriter, FileIsReadableWhileTheRunGoesOn) {
  TempDir dir;
  const std::string path = dir.file("particles.h5");
  H5mdWriter w(path, kN, 2, "test");
  w.write_frame(0, 0.0, make_frame(kN, 0));
  w.write_frame(10, 0.5, make_frame(kN, 1));
  // Another process (with its own HDF5 and file locking) opens the file the writer still holds.
  if (!python_has_plot_modules()) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy";
  const std::string check =
      std::string(FLUIDEM_PYTHON) + " -c \"import h5py, sys; f = h5py.File(sys.argv[1], 'r'); " +
      "a = f['particles/all']; " +
      "sys.exit(0 if a['position/value'].shape == (2, 7, 3) and a.attrs['frames'] == 2 " +
      "and list(a['id/step'][:]) == [0, 10] else 1)\" '" + path + "'";
  EXPECT_EQ(run(check), 0);
}

TEST(H5mdWriter, LargeFramesAreChunkedAtAboutOneMebibyte) {
  TempDir dir;
  const std::string path = dir.file("big.h5");
  const std::size_t n = 100000; // 2.4 MB of positions per frame
  {
    H5mdWriter w(path, n, 3, "test");
    ParticleStore p;
    p.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      p.x[i] = static_cast<double>(i);
      p.id[i] = static_cast<std::int64_t>(i);
    }
    w.write_frame(7, 1.0, p);
  }
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t ds = H5Dopen2(f, "/particles/all/position/value", H5P_DEFAULT);
  const hid_t dcpl = H5Dget_create_plist(ds);
  hsize_t chunk[3];
  ASSERT_EQ(H5Pget_chunk(dcpl, 3, chunk), 3);
  EXPECT_EQ(chunk[0], 1u);
  EXPECT_LE(chunk[1] * chunk[2] * 8, 1u << 20);
  EXPECT_GE(chunk[1] * chunk[2] * 8, (1u << 20) - 24);
  H5Pclose(dcpl);
  H5Dclose(ds);
  const auto x = read_all<double>(f, "/particles/all/position/value", H5T_NATIVE_DOUBLE);
  ASSERT_EQ(x.size(), 3 * n);
  EXPECT_EQ(x[3 * (n - 1)], static_cast<double>(n - 1));
  EXPECT_EQ(info(f, "/particles/all/id/value").dims, (std::vector<hsize_t>{1, n}));
  H5Fclose(f);
}

TEST(H5mdWriter, ZeroParticles) {
  TempDir dir;
  const std::string path = dir.file("empty.h5");
  {
    H5mdWriter w(path, 0, 2, "test");
    const ParticleStore p;
    w.write_frame(0, 0.0, p);
    w.write_frame(1, 0.1, p);
    w.close();
    EXPECT_THROW(w.write_frame(2, 0.2, p), std::logic_error);
  }
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(info(f, "/particles/all/position/value").dims, (std::vector<hsize_t>{2, 0, 3}));
  EXPECT_EQ(info(f, "/particles/all/position/step").dims, (std::vector<hsize_t>{2}));
  H5Fclose(f);
}

TEST(H5mdWriter, WrongParticleCountThrows) {
  TempDir dir;
  H5mdWriter w(dir.file("p.h5"), kN, 2, "test");
  EXPECT_THROW(w.write_frame(0, 0.0, make_frame(kN + 1, 0)), std::invalid_argument);
  EXPECT_THROW(H5mdWriter(dir.file("q.h5"), 3, 4, "test"), std::invalid_argument);
}

TEST(H5mdWriter, FrameOrderWritesTheGivenRowsAndIsChecked) {
  // write_frame(..., order): row k is particle order[k] (the simulation passes its store's
  // indices in ascending id after a spatial sort); a wrong-sized order writes nothing.
  TempDir dir;
  const std::string path = dir.file("p.h5");
  const ParticleStore p = make_frame(kN, 0, true);
  std::vector<std::uint32_t> order(kN);
  for (std::size_t k = 0; k < kN; ++k) order[k] = static_cast<std::uint32_t>(kN - 1 - k);
  {
    H5mdWriter w(path, kN, 3, "test");
    const std::vector<std::uint32_t> short_order(kN - 1);
    EXPECT_THROW(w.write_frame(0, 0.0, p, &short_order), std::invalid_argument);
    w.write_frame(0, 0.0, p, &order);
    EXPECT_EQ(w.frames(), 1u);
  }
  const fluidem::H5mdReader r(path);
  ASSERT_EQ(r.frames(), 1u);
  ParticleStore f;
  r.read_frame(0, f);
  for (std::size_t k = 0; k < kN; ++k) {
    const std::size_t i = order[k];
    EXPECT_EQ(f.id[k], p.id[i]);
    EXPECT_EQ(f.x[k], p.x[i]);
    EXPECT_EQ(f.wz[k], p.wz[i]);
    EXPECT_EQ(f.radius[k], p.radius[i]);
    EXPECT_EQ(f.species[k], p.species[i]);
  }
}

TEST(H5mdWriter, HdfErrorThrowsNamingFileAndOperation) {
  TempDir dir;
  const std::string path = dir.file("no/such/dir/particles.h5");
  try {
    H5mdWriter w(path, kN, 2, "test");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("create file"), std::string::npos) << what;
  }
}

TEST(H5mdWriter, MoveKeepsWriting) {
  TempDir dir;
  const std::string path = dir.file("moved.h5");
  {
    H5mdWriter a(path, kN, 2, "test");
    a.write_frame(0, 0.0, make_frame(kN, 0));
    H5mdWriter b(std::move(a));
    b.write_frame(1, 0.1, make_frame(kN, 1));
    EXPECT_EQ(b.frames(), 2u);
    EXPECT_EQ(b.path(), path);
  }
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(info(f, "/particles/all/radius/value").dims, (std::vector<hsize_t>{2, kN}));
  H5Fclose(f);
}

// --- the snapshot picture -----------------------------------------------------------------------

namespace {

void write_series(const std::string& path) {
  fluidem::SeriesWriter s(path, {"time", "e_kin", "e_rot", "e_pot", "e_el", "e_dsp", "steps"});
  for (int k = 0; k < 20; ++k) {
    const double t = 0.01 * k;
    s.write_row({t, 1.0 / (1.0 + k), 0.1 / (1.0 + k), 2.0 - 0.01 * k, 1e-3, 0.05 * k, 100.0 * k});
  }
}

bool is_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  return in.gcount() == 8 && std::memcmp(magic, "\x89PNG\r\n\x1a\n", 8) == 0;
}

} // namespace

TEST(FluidemPlot, DrawsSnapshotWithEnergies) {
  if (!python_has_plot_modules()) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy/matplotlib";
  TempDir dir;
  write_standard(dir.file("particles.h5"));
  write_series(dir.file("series.csv"));
  const std::string cmd = std::string(FLUIDEM_PYTHON) + " '" + plot_script() + "' '" +
                          dir.path().string() + "' > '" + dir.file("plot.log") + "' 2>&1";
  ASSERT_EQ(run(cmd), 0) << std::ifstream(dir.file("plot.log")).rdbuf();
  const std::string png = dir.file("snapshot.png");
  ASSERT_TRUE(fs::exists(png));
  EXPECT_GT(fs::file_size(png), 1000u);
  EXPECT_TRUE(is_png(png));
}

TEST(FluidemPlot, ThreeDimensionalSpeedColouringAndChosenFrame) {
  if (!python_has_plot_modules()) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy/matplotlib";
  TempDir dir;
  write_standard(dir.file("particles.h5"), /*three_d=*/true);
  const std::string out = dir.file("first.png");
  for (const char* colour : {"speed", "id", "species"}) {
    fs::remove(out);
    const std::string cmd = std::string(FLUIDEM_PYTHON) + " '" + plot_script() + "' '" +
                            dir.path().string() + "' --frame 0 --color-by " + colour + " --out '" +
                            out + "' > '" + dir.file("plot.log") + "' 2>&1";
    ASSERT_EQ(run(cmd), 0) << colour << ": " << std::ifstream(dir.file("plot.log")).rdbuf();
    EXPECT_TRUE(is_png(out)) << colour;
    EXPECT_GT(fs::file_size(out), 1000u) << colour;
  }
  EXPECT_FALSE(fs::exists(dir.file("snapshot.png")));
  // A frame that does not exist is bad input.
  const std::string bad = std::string(FLUIDEM_PYTHON) + " '" + plot_script() + "' '" +
                          dir.path().string() + "' --frame 3 >/dev/null 2>&1";
  EXPECT_EQ(run(bad), 2);
}

TEST(FluidemPlot, MissingFileExitsWithTwo) {
  if (!python_has_plot_modules()) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy/matplotlib";
  TempDir dir;
  const std::string cmd = std::string(FLUIDEM_PYTHON) + " '" + plot_script() + "' '" +
                          dir.path().string() + "' > '" + dir.file("plot.log") + "' 2>&1";
  EXPECT_EQ(run(cmd), 2);
  std::ifstream log(dir.file("plot.log"));
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("particles.h5"), std::string::npos) << text;
}
