// Resume of the output writers after a restart from a checkpoint: H5mdWriter::resume,
// FieldsWriter::resume and SeriesWriter::resume keep exactly what the checkpoint recorded (the
// frames' times and the run id; the CSV bytes and their hash), drop the rest (also frames or
// lines cut short by a crash) in a copy renamed over the file, append after them, and refuse
// files that do not match the run, belong to another run or stop short of the checkpoint,
// naming the file and changing nothing. The XDMF indexes rewritten from the kept times
// reference exactly the frames in the files (and, where pvpython is installed, ParaView reads
// them).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "output/fields_writer.hpp"
#include "output/fields_xdmf.hpp"
#include "output/h5md_writer.hpp"
#include "output/series_writer.hpp"
#include "output/xdmf_writer.hpp"

namespace fs = std::filesystem;
using fluidem::FieldGrid;
using fluidem::FieldsWriter;
using fluidem::H5mdBox;
using fluidem::H5mdWriter;
using fluidem::ParticleStore;
using fluidem::SeriesWriter;

namespace {

class TempDir {
public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("fluidem_resume_" + std::to_string(::getpid()) + "_" +
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

private:
  fs::path path_;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

// The message of the exception `f` throws as E (empty, and a test failure, if none).
template <class E>
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "no exception";
  return {};
}

// Frame `k` of a synthetic run; `run` tells the old run (0) from the continued one (1), so that a
// frame of the old run that should have been dropped is recognised.
ParticleStore make_frame(std::size_t n, int k, int run_id) {
  ParticleStore p;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) + 0.1 * k + 0.37 * run_id;
    p.add({std::sin(s), std::cos(3.0 * s), s / 7.0}, {s / 3.0, -s, std::sqrt(s + 1.0)},
          1e-3 * (1.0 + s), 2500.0, static_cast<std::int32_t>(i % 3 + 3 * run_id),
          1000 * (run_id + 1) + static_cast<std::int64_t>(i));
    p.wx.back() = 1.0 / (s + 1.0);
    p.wy.back() = -s * s;
    p.wz.back() = std::exp(-s);
  }
  return p;
}

double frame_time(int k) {
  return 1e-3 * k / 3.0; // awkward doubles
}

template <class T>
std::vector<T> read_dataset(const std::string& file, const std::string& name, hid_t mem_type,
                            std::vector<hsize_t>* dims_out = nullptr) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << name;
  const hid_t space = H5Dget_space(d);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  std::size_t n = 1;
  for (const hsize_t x : dims) n *= x;
  std::vector<T> out(n);
  if (n > 0) {
    EXPECT_GE(H5Dread(d, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), 0);
  }
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
  if (dims_out != nullptr) *dims_out = dims;
  return out;
}

std::int64_t read_frames_attr(const std::string& file, const std::string& object) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t a = H5Aopen_by_name(f, object.c_str(), "frames", H5P_DEFAULT, H5P_DEFAULT);
  std::int64_t v = -1;
  H5Aread(a, H5T_NATIVE_INT64, &v);
  H5Aclose(a);
  H5Fclose(f);
  return v;
}

// Extend a 1-D dataset by one element (what a crash between extending step/time and writing the
// values of a frame leaves behind).
void extend_by_one(const std::string& file, const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  const hid_t space = H5Dget_space(d);
  hsize_t dims[1] = {0};
  H5Sget_simple_extent_dims(space, dims, nullptr);
  ++dims[0];
  EXPECT_GE(H5Dset_extent(d, dims), 0);
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
}

const H5mdBox kBox{{-0.01, 0.0, 0.0}, {0.03, 0.002, 0.1}, {true, false, false}};

// The particle file of a run: frames (run_id, k) for the given list, in order.
struct Frame {
  int run_id;
  int k;
};

void expect_h5md_holds(const std::string& file, std::size_t n, const std::vector<Frame>& frames) {
  const std::string all = "/particles/all/";
  std::vector<hsize_t> dims;
  const auto steps = read_dataset<std::int64_t>(file, all + "position/step", H5T_NATIVE_INT64);
  const auto times = read_dataset<double>(file, all + "position/time", H5T_NATIVE_DOUBLE);
  ASSERT_EQ(steps.size(), frames.size());
  ASSERT_EQ(times.size(), frames.size());
  EXPECT_EQ(read_frames_attr(file, "/particles/all"), static_cast<std::int64_t>(frames.size()));
  const auto pos = read_dataset<double>(file, all + "position/value", H5T_NATIVE_DOUBLE, &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{frames.size(), n, 3}));
  const auto vel = read_dataset<double>(file, all + "velocity/value", H5T_NATIVE_DOUBLE);
  const auto ang = read_dataset<double>(file, all + "angular_velocity/value", H5T_NATIVE_DOUBLE);
  const auto rad = read_dataset<double>(file, all + "radius/value", H5T_NATIVE_DOUBLE, &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{frames.size(), n}));
  const auto spe = read_dataset<std::int32_t>(file, all + "species/value", H5T_NATIVE_INT32);
  const auto ids = read_dataset<std::int64_t>(file, all + "id/value", H5T_NATIVE_INT64);
  ASSERT_EQ(pos.size(), frames.size() * n * 3);
  ASSERT_EQ(vel.size(), pos.size());
  ASSERT_EQ(ang.size(), pos.size());
  ASSERT_EQ(rad.size(), frames.size() * n);
  ASSERT_EQ(spe.size(), rad.size());
  ASSERT_EQ(ids.size(), rad.size());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    const int k = frames[f].k;
    EXPECT_EQ(steps[f], 100 * k);
    EXPECT_EQ(times[f], frame_time(k));
    const ParticleStore p = make_frame(n, k, frames[f].run_id);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t v = 3 * (f * n + i), s = f * n + i;
      EXPECT_EQ(pos[v], p.x[i]);
      EXPECT_EQ(pos[v + 1], p.y[i]);
      EXPECT_EQ(pos[v + 2], p.z[i]);
      EXPECT_EQ(vel[v], p.vx[i]);
      EXPECT_EQ(vel[v + 2], p.vz[i]);
      EXPECT_EQ(ang[v + 1], p.wy[i]);
      EXPECT_EQ(rad[s], p.radius[i]);
      EXPECT_EQ(spe[s], p.species[i]);
      EXPECT_EQ(ids[s], p.id[i]);
    }
  }
}

const std::string kRun = "0123456789abcdef0123456789abcdef";

// The times of frames 0..count-1: what a checkpoint taken at frame count-1 records.
std::vector<double> kept(int count) {
  std::vector<double> t;
  for (int k = 0; k < count; ++k) t.push_back(frame_time(k));
  return t;
}

void write_old_run(const std::string& file, std::size_t n, int frames,
                   const std::string& run = kRun) {
  H5mdWriter w(file, n, 2, "test", kBox, "tester", false, run);
  for (int k = 0; k < frames; ++k) w.write_frame(100 * k, frame_time(k), make_frame(n, k, 0));
  w.close();
}

// ---- fields ----

FieldGrid small_grid() {
  FieldGrid g;
  g.cells = {3, 1, 2};
  g.lo = {-0.01, 0.0, 0.0};
  g.spacing = {0.005, 0.002, 0.0125};
  return g;
}

const std::vector<std::string> kScalars{"porosity", "pressure"};
const std::vector<std::string> kVectors{"gas_velocity"};

// Field f (0, 1: scalars; 2, 3, 4: vector components) of frame k of run `run_id`, cell c.
double field_value(int f, int k, int run_id, std::size_t c) {
  return 1000.0 * f + 10.0 * k + static_cast<double>(c) / 3.0 + 0.5 * run_id;
}

void write_fields_frame(FieldsWriter& w, int k, int run_id) {
  const std::size_t n = w.grid().size();
  std::vector<std::vector<double>> data(5, std::vector<double>(n));
  for (int f = 0; f < 5; ++f)
    for (std::size_t c = 0; c < n; ++c) data[f][c] = field_value(f, k, run_id, c);
  w.write_frame(100 * k, frame_time(k), {data[0].data(), data[1].data()},
                {{data[2].data(), data[3].data(), data[4].data()}});
}

void expect_fields_hold(const std::string& file, const std::vector<Frame>& frames) {
  const std::size_t n = small_grid().size();
  const auto steps = read_dataset<std::int64_t>(file, "/fields/step", H5T_NATIVE_INT64);
  const auto times = read_dataset<double>(file, "/fields/time", H5T_NATIVE_DOUBLE);
  ASSERT_EQ(steps.size(), frames.size());
  ASSERT_EQ(times.size(), frames.size());
  EXPECT_EQ(read_frames_attr(file, "/fields"), static_cast<std::int64_t>(frames.size()));
  std::vector<hsize_t> dims;
  const auto porosity = read_dataset<double>(file, "/fields/porosity", H5T_NATIVE_DOUBLE, &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{frames.size(), 2, 1, 3}));
  const auto pressure = read_dataset<double>(file, "/fields/pressure", H5T_NATIVE_DOUBLE);
  const auto gas = read_dataset<double>(file, "/fields/gas_velocity", H5T_NATIVE_DOUBLE, &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{frames.size(), 2, 1, 3, 3}));
  ASSERT_EQ(porosity.size(), frames.size() * n);
  ASSERT_EQ(pressure.size(), porosity.size());
  ASSERT_EQ(gas.size(), 3 * porosity.size());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    const int k = frames[f].k, r = frames[f].run_id;
    EXPECT_EQ(steps[f], 100 * k);
    EXPECT_EQ(times[f], frame_time(k));
    for (std::size_t c = 0; c < n; ++c) {
      EXPECT_EQ(porosity[f * n + c], field_value(0, k, r, c));
      EXPECT_EQ(pressure[f * n + c], field_value(1, k, r, c));
      for (int d = 0; d < 3; ++d) EXPECT_EQ(gas[3 * (f * n + c) + d], field_value(2 + d, k, r, c));
    }
  }
}

void write_old_fields(const std::string& file, int frames, const std::string& run = kRun) {
  FieldsWriter w(file, small_grid(), kScalars, kVectors, "test", run);
  for (int k = 0; k < frames; ++k) write_fields_frame(w, k, 0);
  w.close();
}

// Old run: frames 0..5 (run 0); checkpoint at frame 2; continued run: frames 3..6 (run 1).
std::vector<Frame> expected_after_resume() {
  return {{0, 0}, {0, 1}, {0, 2}, {1, 3}, {1, 4}, {1, 5}, {1, 6}};
}

/// No file named `path` + anything ending in ".tmp" is left in its directory.
void expect_no_temporaries(const std::string& path) {
  for (const auto& e : fs::directory_iterator(fs::path(path).parent_path()))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

} // namespace

// ---- H5MD ----

TEST(H5mdResume, KeepsTheCheckpointsFramesThenAppends) {
  TempDir dir;
  const std::string file = dir.file("particles.h5");
  const std::size_t n = 5;
  write_old_run(file, n, 6);
  // Resumed and closed at once (a crash before the next frame): only the kept frames remain.
  H5mdWriter::resume(file, kept(3), kRun, n, 2, kBox).close();
  expect_h5md_holds(file, n, {{0, 0}, {0, 1}, {0, 2}});
  expect_no_temporaries(file);
  {
    H5mdWriter w = H5mdWriter::resume(file, kept(3), kRun, n, 2, kBox);
    EXPECT_EQ(w.frames(), 3u);
    EXPECT_EQ(w.n_particles(), n);
    EXPECT_EQ(w.kept_times(), kept(3));
    for (int k = 3; k <= 6; ++k) w.write_frame(100 * k, frame_time(k), make_frame(n, k, 1));
    EXPECT_EQ(w.frames(), 7u);
    w.close();
  }
  expect_h5md_holds(file, n, expected_after_resume());
  // The rest of the layout is untouched.
  EXPECT_EQ(read_dataset<std::int64_t>(file, fluidem::kH5mdVertexIndexPath, H5T_NATIVE_INT64),
            (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(read_dataset<double>(file, "/particles/all/box/offset", H5T_NATIVE_DOUBLE),
            (std::vector<double>{-0.01, 0.0, 0.0}));
}

TEST(H5mdResume, TwiceAndAtTheEdges) {
  TempDir dir;
  const std::string file = dir.file("particles.h5");
  const std::size_t n = 3;
  write_old_run(file, n, 4);
  const std::string bytes = slurp(file);
  // A checkpoint at the last frame keeps everything, without rewriting the file.
  {
    H5mdWriter w = H5mdWriter::resume(file, kept(4), kRun, n, 2, kBox, false, true);
    EXPECT_EQ(slurp(file), bytes);
  }
  {
    H5mdWriter w = H5mdWriter::resume(file, kept(4), kRun, n, 2, kBox);
    EXPECT_EQ(w.frames(), 4u);
    w.write_frame(400, frame_time(4), make_frame(n, 4, 0));
  }
  expect_h5md_holds(file, n, {{0, 0}, {0, 1}, {0, 2}, {0, 3}, {0, 4}});
  // A checkpoint before the first frame keeps none.
  {
    H5mdWriter w = H5mdWriter::resume(file, {}, kRun, n, 2, kBox);
    EXPECT_EQ(w.frames(), 0u);
    EXPECT_TRUE(w.kept_times().empty());
    w.write_frame(0, frame_time(0), make_frame(n, 0, 1));
  }
  expect_h5md_holds(file, n, {{1, 0}});
}

TEST(H5mdResume, DropsAFrameCutShortByACrash) {
  TempDir dir;
  const std::string file = dir.file("particles.h5");
  const std::size_t n = 4;
  write_old_run(file, n, 3);
  // A crash after step and time of frame 3 were extended, before its values.
  extend_by_one(file, "/particles/all/position/step");
  extend_by_one(file, "/particles/all/position/time");
  {
    H5mdWriter w = H5mdWriter::resume(file, kept(3), kRun, n, 2, kBox);
    EXPECT_EQ(w.frames(), 3u);
    EXPECT_EQ(w.kept_times().size(), 3u);
    w.write_frame(300, frame_time(3), make_frame(n, 3, 1));
  }
  expect_h5md_holds(file, n, {{0, 0}, {0, 1}, {0, 2}, {1, 3}});
}

TEST(H5mdResume, MismatchIsAnErrorNamingTheFileAndWhatDiffers) {
  TempDir dir;
  const std::string file = dir.file("particles.h5");
  write_old_run(file, 5, 2);
  const std::string bytes = slurp(file);
  const auto resume = [&](const std::vector<double>& times, const std::string& run, std::size_t n,
                          int dim, const H5mdBox& box) {
    return error_of<std::runtime_error>([&] { H5mdWriter::resume(file, times, run, n, dim, box); });
  };
  std::string msg = resume(kept(2), kRun, 6, 2, kBox);
  EXPECT_NE(msg.find(file), std::string::npos) << msg;
  EXPECT_NE(msg.find("5 particles in the file, 6 in the run"), std::string::npos) << msg;
  msg = resume(kept(2), kRun, 5, 3, kBox);
  EXPECT_NE(msg.find(file), std::string::npos) << msg;
  EXPECT_NE(msg.find("dimension 2 in the file, 3 in the run"), std::string::npos) << msg;
  H5mdBox other = kBox;
  other.hi[2] = 0.2;
  msg = resume(kept(2), kRun, 5, 2, other);
  EXPECT_NE(msg.find("box size along z"), std::string::npos) << msg;
  other = kBox;
  other.periodic[0] = false;
  msg = resume(kept(2), kRun, 5, 2, other);
  EXPECT_NE(msg.find("box boundary along x"), std::string::npos) << msg;
  // Another run's file, a file that stops short of the checkpoint (a gap), other frames.
  msg = resume(kept(2), "ffff", 5, 2, kBox);
  EXPECT_NE(msg.find("belongs to run " + kRun + ", the checkpoint to run ffff"), std::string::npos)
      << msg;
  msg = resume(kept(3), kRun, 5, 2, kBox);
  EXPECT_NE(msg.find("holds 2 complete frames"), std::string::npos) << msg;
  EXPECT_NE(msg.find("gap"), std::string::npos) << msg;
  msg = resume({frame_time(0), frame_time(2)}, kRun, 5, 2, kBox);
  EXPECT_NE(msg.find("frame 1 is at t = "), std::string::npos) << msg;
  // The failed attempts changed nothing.
  EXPECT_EQ(slurp(file), bytes);
  expect_no_temporaries(file);
}

TEST(H5mdResume, MissingOrNonHdf5FileOrALinkIsAnErrorNamingTheFile) {
  TempDir dir;
  const std::string missing = dir.file("missing.h5");
  std::string msg =
      error_of<std::runtime_error>([&] { H5mdWriter::resume(missing, kept(1), kRun, 5, 2, kBox); });
  EXPECT_NE(msg.find(missing), std::string::npos) << msg;
  EXPECT_NE(msg.find("does not exist"), std::string::npos) << msg;
  const std::string text = dir.file("text.h5");
  { std::ofstream(text) << "not hdf5\n"; }
  msg = error_of<std::runtime_error>([&] { H5mdWriter::resume(text, kept(1), kRun, 5, 2, kBox); });
  EXPECT_NE(msg.find(text), std::string::npos) << msg;
  EXPECT_NE(msg.find("not a readable HDF5 file"), std::string::npos) << msg;
  // An HDF5 file of another kind (a fields file): the missing layout is named.
  const std::string fields = dir.file("fields.h5");
  write_old_fields(fields, 1);
  msg =
      error_of<std::runtime_error>([&] { H5mdWriter::resume(fields, kept(1), kRun, 5, 2, kBox); });
  EXPECT_NE(msg.find(fields), std::string::npos) << msg;
  EXPECT_NE(msg.find("parameters"), std::string::npos) << msg;
  // A link to a good file is not followed.
  const std::string real = dir.file("real.h5"), link = dir.file("link.h5");
  write_old_run(real, 5, 2);
  fs::create_symlink(real, link);
  msg = error_of<std::runtime_error>([&] { H5mdWriter::resume(link, kept(2), kRun, 5, 2, kBox); });
  EXPECT_NE(msg.find("symbolic link"), std::string::npos) << msg;
  // Nor does a new file write through one (dangling or not).
  const std::string dangling = dir.file("dangling.h5");
  fs::create_symlink(dir.file("target.h5"), dangling);
  msg = error_of<std::runtime_error>([&] { H5mdWriter w(dangling, 5, 2, "test", kBox); });
  EXPECT_NE(msg.find("symbolic link"), std::string::npos) << msg;
  EXPECT_FALSE(fs::exists(dir.file("target.h5")));
}

TEST(H5mdResume, XdmfFromTheKeptTimesReferencesEveryFrame) {
  TempDir dir;
  const std::string file = dir.file("particles.h5");
  const std::string xmf = dir.file("particles.xmf");
  const std::size_t n = 4;
  std::vector<double> times;
  {
    H5mdWriter w(file, n, 2, "test", kBox, "tester", false, kRun);
    for (int k = 0; k < 6; ++k) {
      w.write_frame(100 * k, frame_time(k), make_frame(n, k, 0));
      times.push_back(frame_time(k));
      fluidem::write_particles_xdmf(xmf, "particles.h5", n, times);
    }
  }
  {
    H5mdWriter w = H5mdWriter::resume(file, kept(3), kRun, n, 2, kBox);
    times = w.kept_times();
    fluidem::write_particles_xdmf(xmf, "particles.h5", n, times);
    EXPECT_EQ(count(slurp(xmf), "<Time Value="), 3u);
    for (int k = 3; k <= 6; ++k) {
      w.write_frame(100 * k, frame_time(k), make_frame(n, k, 1));
      times.push_back(frame_time(k));
      fluidem::write_particles_xdmf(xmf, "particles.h5", n, times);
    }
  }
  const std::string text = slurp(xmf);
  EXPECT_EQ(count(text, "<Time Value="), 7u);
  EXPECT_EQ(count(text, "GridType=\"Uniform\""), 7u);
  EXPECT_NE(text.find("frame_6"), std::string::npos);
  EXPECT_EQ(text.find("frame_7"), std::string::npos);
  EXPECT_EQ(text, fluidem::particles_xdmf("particles.h5", n, times));

  if (run("command -v pvpython >/dev/null 2>&1") != 0) GTEST_SKIP() << "no pvpython";
  {
    std::ofstream(dir.file("pv.py")) << R"PY(
import sys
from paraview.simple import Xdmf3ReaderS
from paraview import servermanager as sm
r = Xdmf3ReaderS(FileName=[sys.argv[1]])
times = list(r.TimestepValues)
assert len(times) == int(sys.argv[2]), times
for t in times:
    r.UpdatePipeline(t)
    d = sm.Fetch(r)
    if d.IsA("vtkMultiBlockDataSet"):
        d = d.GetBlock(0)
    assert d.GetNumberOfPoints() == int(sys.argv[3]), (t, d.GetNumberOfPoints())
print("ok")
)PY";
  }
  const std::string log = dir.file("pv.log");
  EXPECT_EQ(run("pvpython --force-offscreen-rendering '" + dir.file("pv.py") + "' '" + xmf +
                "' 7 " + std::to_string(n) + " > '" + log + "' 2>&1"),
            0)
      << slurp(log);
}

// ---- fields ----

TEST(FieldsResume, KeepsTheCheckpointsFramesThenAppends) {
  TempDir dir;
  const std::string file = dir.file("fields.h5");
  write_old_fields(file, 6);
  // Resumed and closed at once (a crash before the next frame): only the kept frames remain.
  FieldsWriter::resume(file, kept(3), kRun, small_grid(), kScalars, kVectors).close();
  expect_fields_hold(file, {{0, 0}, {0, 1}, {0, 2}});
  expect_no_temporaries(file);
  {
    FieldsWriter w = FieldsWriter::resume(file, kept(3), kRun, small_grid(), kScalars, kVectors);
    EXPECT_EQ(w.frames(), 3u);
    EXPECT_EQ(w.kept_times(), kept(3));
    EXPECT_EQ(w.scalar_names(), kScalars);
    for (int k = 3; k <= 6; ++k) write_fields_frame(w, k, 1);
    EXPECT_EQ(w.frames(), 7u);
    w.close();
  }
  expect_fields_hold(file, expected_after_resume());
}

TEST(FieldsResume, DropsAFrameCutShortByACrash) {
  TempDir dir;
  const std::string file = dir.file("fields.h5");
  write_old_fields(file, 3);
  // FieldsWriter writes values before step and time: a crash there leaves a longer field.
  {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t d = H5Dopen2(f, "/fields/porosity", H5P_DEFAULT);
    const hsize_t dims[4] = {4, 2, 1, 3};
    EXPECT_GE(H5Dset_extent(d, dims), 0);
    H5Dclose(d);
    H5Fclose(f);
  }
  extend_by_one(file, "/fields/time"); // and a time with a fill value 0
  {
    FieldsWriter w = FieldsWriter::resume(file, kept(3), kRun, small_grid(), kScalars, kVectors);
    EXPECT_EQ(w.frames(), 3u);
    write_fields_frame(w, 3, 1);
  }
  expect_fields_hold(file, {{0, 0}, {0, 1}, {0, 2}, {1, 3}});
}

TEST(FieldsResume, MismatchIsAnErrorNamingTheFileAndWhatDiffers) {
  TempDir dir;
  const std::string file = dir.file("fields.h5");
  write_old_fields(file, 2);
  const std::string bytes = slurp(file);
  const auto resume = [&](const FieldGrid& g, const std::vector<std::string>& scalars,
                          const std::vector<std::string>& vectors,
                          const std::vector<double>& times = kept(2),
                          const std::string& run = kRun) {
    return error_of<std::runtime_error>(
        [&] { FieldsWriter::resume(file, times, run, g, scalars, vectors); });
  };
  FieldGrid g = small_grid();
  g.cells[0] = 4;
  std::string msg = resume(g, kScalars, kVectors);
  EXPECT_NE(msg.find(file), std::string::npos) << msg;
  EXPECT_NE(msg.find("grid cells along x: 3 in the file, 4 in the run"), std::string::npos) << msg;
  g = small_grid();
  g.spacing[2] *= 1.001;
  msg = resume(g, kScalars, kVectors);
  EXPECT_NE(msg.find("grid spacing along z"), std::string::npos) << msg;
  msg = resume(small_grid(), {"pressure", "porosity"}, kVectors);
  EXPECT_NE(msg.find(file), std::string::npos) << msg;
  EXPECT_NE(msg.find("scalar fields [porosity, pressure] in the file, [pressure, porosity]"),
            std::string::npos)
      << msg;
  msg = resume(small_grid(), kScalars, {});
  EXPECT_NE(msg.find("vector fields [gas_velocity] in the file, [] in the run"), std::string::npos)
      << msg;
  msg = resume(small_grid(), kScalars, kVectors, kept(2), "ffff");
  EXPECT_NE(msg.find("belongs to run"), std::string::npos) << msg;
  msg = resume(small_grid(), kScalars, kVectors, kept(4));
  EXPECT_NE(msg.find("gap"), std::string::npos) << msg;
  const std::string missing = dir.file("missing.h5");
  msg = error_of<std::runtime_error>(
      [&] { FieldsWriter::resume(missing, kept(1), kRun, small_grid(), kScalars, kVectors); });
  EXPECT_NE(msg.find(missing), std::string::npos) << msg;
  EXPECT_EQ(slurp(file), bytes);
  expect_fields_hold(file, {{0, 0}, {0, 1}});
}

TEST(FieldsResume, XdmfFromTheKeptTimesReferencesEveryFrame) {
  TempDir dir;
  const std::string file = dir.file("fields.h5");
  const std::string xmf = dir.file("fields.xmf");
  write_old_fields(file, 6);
  std::vector<double> times;
  {
    FieldsWriter w = FieldsWriter::resume(file, kept(3), kRun, small_grid(), kScalars, kVectors);
    times = w.kept_times();
    for (int k = 3; k <= 6; ++k) {
      write_fields_frame(w, k, 1);
      times.push_back(frame_time(k));
    }
  }
  fluidem::write_fields_xdmf(xmf, "fields.h5", small_grid(), kScalars, kVectors, times);
  const std::string text = slurp(xmf);
  EXPECT_EQ(count(text, "<Time Value="), 7u);
  EXPECT_NE(text.find("frame_6"), std::string::npos);
  EXPECT_EQ(text.find("frame_7"), std::string::npos);
  EXPECT_EQ(read_dataset<double>(file, "/fields/time", H5T_NATIVE_DOUBLE), times);
}

// ---- series ----

// A series of 6 rows; `mark` gets what the file held after 3 (a checkpoint there).
void write_old_series(const std::string& file, const std::vector<std::string>& columns,
                      SeriesWriter::Mark& mark) {
  SeriesWriter s(file, columns);
  for (int k = 0; k < 6; ++k) {
    s.write_row({frame_time(k), 0.5 * k, static_cast<double>(k)});
    if (k == 2) mark = s.mark();
  }
}

TEST(SeriesResume, KeepsTheCheckpointsBytesThenAppends) {
  TempDir dir;
  const std::string file = dir.file("series.csv");
  const std::vector<std::string> columns{"time", "e_kin", "n"};
  SeriesWriter::Mark mark;
  write_old_series(file, columns, mark);
  const std::string kept_text = "time,e_kin,n\n0,0,0\n0.0003333333333,0.5,1\n0.0006666666667,1,2\n";
  EXPECT_EQ(mark.bytes, kept_text.size());
  {
    SeriesWriter s = SeriesWriter::resume(file, columns, mark);
    EXPECT_EQ(s.kept_rows(), 3u);
    EXPECT_EQ(s.columns(), columns);
    EXPECT_EQ(slurp(file), kept_text);
    for (int k = 3; k <= 4; ++k) s.write_row({frame_time(k), -1.0 * k, 10.0 * k});
    s.close();
    // The mark goes on from the checkpoint's: a second restart finds the same bytes.
    EXPECT_EQ(s.mark().bytes, slurp(file).size());
  }
  EXPECT_EQ(slurp(file), kept_text + "0.001,-3,30\n0.001333333333,-4,40\n");
  expect_no_temporaries(file);
}

TEST(SeriesResume, DropsATruncatedLastLine) {
  TempDir dir;
  const std::string file = dir.file("probes.csv");
  SeriesWriter::Mark mark;
  {
    SeriesWriter s(file, {"time", "p1"});
    s.write_row({0.0, 1.5});
    s.write_row({0.1, 2.5});
    mark = s.mark();
  }
  { std::ofstream(file, std::ios::app | std::ios::binary) << "0.2,3"; } // a crash mid-row
  {
    SeriesWriter s = SeriesWriter::resume(file, {"time", "p1"}, mark);
    EXPECT_EQ(s.kept_rows(), 2u);
    s.write_row({0.2, 3.5});
  }
  EXPECT_EQ(slurp(file), "time,p1\n0,1.5\n0.1,2.5\n0.2,3.5\n");
}

TEST(SeriesResume, AnotherRunsRowsAGapOrAnotherHeaderIsAnErrorNamingTheFile) {
  TempDir dir;
  const std::string file = dir.file("series.csv");
  const std::vector<std::string> columns{"time", "e_kin", "n"};
  SeriesWriter::Mark mark;
  write_old_series(file, columns, mark);
  const std::string content = slurp(file);
  std::string msg = error_of<std::runtime_error>([&] {
    SeriesWriter::resume(file, {"time", "e_kin", "e_rot"}, mark);
  });
  EXPECT_NE(msg.find(file), std::string::npos) << msg;
  EXPECT_NE(msg.find("its header 'time,e_kin,n' is not the run's, 'time,e_kin,e_rot'"),
            std::string::npos)
      << msg;
  // One digit of a kept row changed: another run's rows.
  std::string other = content;
  other[other.find("0.5,1")] = '9';
  { std::ofstream(file, std::ios::binary) << other; }
  msg = error_of<std::runtime_error>([&] { SeriesWriter::resume(file, columns, mark); });
  EXPECT_NE(msg.find("another run's rows"), std::string::npos) << msg;
  EXPECT_EQ(slurp(file), other); // untouched
  // Cut before the checkpoint's rows end: a gap.
  { std::ofstream(file, std::ios::binary) << content.substr(0, mark.bytes - 5); }
  msg = error_of<std::runtime_error>([&] { SeriesWriter::resume(file, columns, mark); });
  EXPECT_NE(msg.find("gap"), std::string::npos) << msg;
  const std::string missing = dir.file("missing.csv");
  msg = error_of<std::runtime_error>([&] { SeriesWriter::resume(missing, columns, mark); });
  EXPECT_NE(msg.find(missing), std::string::npos) << msg;
  EXPECT_FALSE(fs::exists(missing));
  expect_no_temporaries(file);
}
