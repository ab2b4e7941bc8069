// H5mdReader: frames written with H5mdWriter (awkward doubles, 3-D, several species, ids not
// equal to indices) read back bitwise; the box, dimension, times and steps as written; frames
// cut short in one dataset (a live run) are not counted; every bad input is an error naming the
// file.
#include <gtest/gtest.h>
#include <hdf5.h>
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

namespace fs = std::filesystem;
using fluidem::H5mdBox;
using fluidem::H5mdReader;
using fluidem::H5mdWriter;
using fluidem::ParticleStore;

namespace {

class TempDir {
public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("fluidem_h5mdr_" + std::to_string(::getpid()) + "_" +
                                         info->test_suite_name() + "_" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
  fs::path path_;
};

// Frame k of a synthetic 3-D run; every value differs from particle to particle and frame to frame.
ParticleStore make_frame(std::size_t n, int k) {
  ParticleStore p;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) + 0.1 * k;
    p.add({1e-2 * std::sin(s) + 0.02, 2e-3 * std::cos(3.0 * s), 0.01 + 3e-3 * s / 7.0},
          {std::cos(s) / 3.0, 0.1 * s, -std::sin(s) / 7.0},
          1e-3 * (1.0 + 0.25 * static_cast<double>(i % 3)), 2500.0,
          static_cast<std::int32_t>(i % 3), 1000 + 7 * static_cast<std::int64_t>(i));
    p.wx.back() = 1.0 / (s + 1.0);
    p.wy.back() = -std::sqrt(s + 2.0);
    p.wz.back() = std::exp(-s);
  }
  return p;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

H5mdBox test_box() {
  H5mdBox box;
  box.lo = {-0.01, 0.0, 0.0};
  box.hi = {0.05, 0.004, 0.1};
  box.periodic = {true, false, false};
  return box;
}

} // namespace

TEST(H5mdReader, ReadsBackEveryFrameBitwise) {
  TempDir dir;
  const std::string path = dir.file("particles.h5");
  const std::size_t n = 17;
  const int frames = 4;
  {
    H5mdWriter w(path, n, 3, "test", test_box());
    for (int k = 0; k < frames; ++k) w.write_frame(100 * k + 3, 0.01 * k + 1e-7, make_frame(n, k));
  }
  const H5mdReader r(path);
  ASSERT_EQ(r.frames(), static_cast<std::size_t>(frames));
  EXPECT_EQ(r.n_particles(), n);
  EXPECT_EQ(r.dimension(), 3);
  for (int d = 0; d < 3; ++d) {
    EXPECT_DOUBLE_EQ(r.box().lo[d], test_box().lo[d]); // the file stores lo and hi - lo
    EXPECT_NEAR(r.box().hi[d], test_box().hi[d], 1e-15);
    EXPECT_EQ(r.box().periodic[d], test_box().periodic[d]);
  }
  ParticleStore p;
  for (int k = 0; k < frames; ++k) {
    EXPECT_EQ(r.times()[k], 0.01 * k + 1e-7);
    EXPECT_EQ(r.steps()[k], 100 * k + 3);
    r.read_frame(static_cast<std::size_t>(k), p);
    const ParticleStore e = make_frame(n, k);
    ASSERT_EQ(p.size(), n);
    EXPECT_TRUE(same_bits(p.x, e.x) && same_bits(p.y, e.y) && same_bits(p.z, e.z)) << k;
    EXPECT_TRUE(same_bits(p.vx, e.vx) && same_bits(p.vy, e.vy) && same_bits(p.vz, e.vz)) << k;
    EXPECT_TRUE(same_bits(p.wx, e.wx) && same_bits(p.wy, e.wy) && same_bits(p.wz, e.wz)) << k;
    EXPECT_TRUE(same_bits(p.radius, e.radius)) << k;
    EXPECT_TRUE(same_bits(p.species, e.species)) << k;
    EXPECT_TRUE(same_bits(p.id, e.id)) << k;
    // Masses: a sphere of density 1 (documented).
    EXPECT_NEAR(p.mass[5], 4.0 / 3.0 * M_PI * std::pow(p.radius[5], 3), 1e-24);
  }
  EXPECT_THROW(r.read_frame(frames, p), std::runtime_error);
}

TEST(H5mdReader, TwoDimensionalRunAndNoFrames) {
  TempDir dir;
  const std::string path = dir.file("p.h5");
  { H5mdWriter w(path, 5, 2, "test", test_box()); }
  const H5mdReader r(path);
  EXPECT_EQ(r.dimension(), 2);
  EXPECT_EQ(r.frames(), 0u);
  EXPECT_EQ(r.n_particles(), 5u);
  ParticleStore p;
  try {
    r.read_frame(0, p);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("0 frames"), std::string::npos) << e.what();
  }
}

// A frame appended to velocity only (as a live run that has written part of a frame leaves it)
// is not counted.
TEST(H5mdReader, CountsOnlyCompleteFrames) {
  TempDir dir;
  const std::string path = dir.file("p.h5");
  {
    H5mdWriter w(path, 3, 3, "test", test_box());
    for (int k = 0; k < 3; ++k) w.write_frame(k, 0.1 * k, make_frame(3, k));
  }
  {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    const hid_t d = H5Dopen2(f, "/particles/all/velocity/value", H5P_DEFAULT);
    const hsize_t dims[3] = {4, 3, 3};
    ASSERT_GE(H5Dset_extent(d, dims), 0);
    H5Dclose(d);
    H5Fclose(f);
  }
  EXPECT_EQ(H5mdReader(path).frames(), 3u);
}

TEST(H5mdReader, ErrorsNameTheFile) {
  TempDir dir;
  const auto message = [](const std::string& path) {
    try {
      H5mdReader r(path);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  const std::string missing = dir.file("missing.h5");
  EXPECT_NE(message(missing).find(missing + "': no such file"), std::string::npos)
      << message(missing);
  const std::string text = dir.file("text.h5");
  std::ofstream(text) << "not hdf5\n";
  EXPECT_NE(message(text).find(text + "' is not a readable HDF5 file"), std::string::npos)
      << message(text);
  // An HDF5 file without the particle layout.
  const std::string other = dir.file("other.h5");
  H5Fclose(H5Fcreate(other.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
  EXPECT_NE(message(other).find(other + "' is not a readable fluidem particle file: no "
                                        "/parameters"),
            std::string::npos)
      << message(other);
}
