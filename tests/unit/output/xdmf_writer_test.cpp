// write_particles_xdmf: the XDMF index is well-formed XML, has one Polyvertex grid per frame, and
// its HyperSlabs point at datasets of the H5MD file with the right shapes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "output/h5md_writer.hpp"
#include "output/xdmf_writer.hpp"

namespace fs = std::filesystem;

namespace {

class TempDir {
public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("fluidem_xdmf_" + std::to_string(::getpid()) + "_" + info->name());
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

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t pos = text.find(what); pos != std::string::npos;
       pos = text.find(what, pos + what.size()))
    ++n;
  return n;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1 || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

bool python_runs(const char* imports) {
  return run(std::string(FLUIDEM_PYTHON) + " -c 'import " + imports + "' >/dev/null 2>&1") == 0;
}

const std::vector<double> kTimes = {0.0, 0.001, 0.25};
const char* const kFields[] = {
    "/particles/all/position/value",         "/particles/all/velocity/value",
    "/particles/all/angular_velocity/value", "/particles/all/radius/value",
    "/particles/all/species/value",          "/particles/all/id/value"};

// Python: parse the XDMF file (either flavour), check its structure; with check_h5, also open the
// HDF5 datasets it references (h5py) and compare shapes, types, frame selections and times.
const char* const kCheckScript = R"PY(
import sys, os, xml.dom.minidom
xmf, n, frames, check_h5 = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4] == "1"
doc = xml.dom.minidom.parse(xmf)
root = doc.documentElement
assert root.tagName == "Xdmf" and root.getAttribute("Version") == "3.0", root.tagName
domains = root.getElementsByTagName("Domain")
assert len(domains) == 1
elements = lambda node: [c for c in node.childNodes if c.nodeType == c.ELEMENT_NODE]
coll = elements(domains[0])
assert len(coll) == 1 and coll[0].getAttribute("CollectionType") == "Temporal"
grids = [g for g in elements(coll[0]) if g.tagName == "Grid"]
assert len(grids) == frames, (len(grids), frames)
if check_h5:
    import h5py, numpy as np

def selection(item):
    """(file, dataset, data item, start, stride, count, dataset dims) of a frame selection."""
    if item.getAttribute("ItemType") == "HyperSlab":
        sel, data = elements(item)
        rows = [int(v) for v in sel.firstChild.data.split()]
        r = len(rows) // 3
        start, stride, cnt = rows[:r], rows[r:2 * r], rows[2 * r:]
        assert [int(v) for v in item.getAttribute("Dimensions").split()] == cnt
        dims = [int(v) for v in data.getAttribute("Dimensions").split()]
        fname, path = data.firstChild.data.strip().split(":")
        return fname, path, data, start, stride, cnt, dims
    text = item.firstChild.data.strip()
    fname, rest = text.split(":", 1)
    path, space = rest.split("|")
    start, stride, cnt, dims = [[int(v) for v in p.split()] for p in space.split(":")]
    size = 1
    for v in item.getAttribute("Dimensions").split():
        size *= int(v)
    count_size = 1
    for v in cnt:
        count_size *= v
    assert size == count_size, (size, cnt)
    return fname, path, item, start, stride, cnt, dims

for k, g in enumerate(grids):
    topo = g.getElementsByTagName("Topology")[0]
    assert topo.getAttribute("TopologyType") == "Polyvertex"
    assert int(topo.getAttribute("NumberOfElements")) == n
    geometry = g.getElementsByTagName("Geometry")[0]
    assert geometry.getAttribute("GeometryType") == "XYZ"
    attributes = g.getElementsByTagName("Attribute")
    names = sorted(a.getAttribute("Name") for a in attributes)
    assert names == sorted(["velocity", "angular_velocity", "radius", "species", "id"]), names
    time = float(g.getElementsByTagName("Time")[0].getAttribute("Value"))
    for holder in [geometry] + list(attributes):
        fname, path, data, start, stride, cnt, dims = selection(elements(holder)[0])
        assert start[0] == k and all(s == 0 for s in start[1:]), start
        assert all(s == 1 for s in stride) and cnt[0] == 1 and cnt[1] == n, cnt
        assert dims[0] == frames and dims[1] == n, dims
        assert len(dims) == (3 if holder.getAttribute("AttributeType") in ("Vector", "") else 2)
        if check_h5:
            with h5py.File(os.path.join(os.path.dirname(xmf), fname), "r") as f:
                ds = f[path]
                assert list(ds.shape) == dims, (path, ds.shape, dims)
                assert ds.dtype.itemsize == int(data.getAttribute("Precision")), (path, ds.dtype)
                kind = "f" if data.getAttribute("NumberType") == "Float" else "i"
                assert ds.dtype.kind == kind, (path, ds.dtype)
                assert f["particles/all/position/time"][k] == time
    if check_h5:
        conn = elements(topo)[0]
        fname, path = conn.firstChild.data.strip().split(":")
        with h5py.File(os.path.join(os.path.dirname(xmf), fname), "r") as f:
            assert list(f[path][:]) == list(range(n)), path
print("ok")
)PY";

// pvpython: open the file with the given reader and check every time step.
const char* const kParaViewScript = R"PY(
import sys
from paraview.simple import Xdmf3ReaderS, XDMFReader
from paraview import servermanager as sm
from paraview.vtk.numpy_interface import dataset_adapter as dsa
xmf, reader, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
times = [float(t) for t in sys.argv[4].split(",")]
r = Xdmf3ReaderS(FileName=[xmf]) if reader == "xdmf3" else XDMFReader(FileNames=[xmf])
assert [float(t) for t in r.TimestepValues] == times, list(r.TimestepValues)
for k, t in enumerate(times):
    r.UpdatePipeline(t)
    d = sm.Fetch(r)
    if d.IsA("vtkMultiBlockDataSet"):
        d = d.GetBlock(0)
    assert d.GetNumberOfPoints() == n and d.GetNumberOfCells() == n, (t, d.GetNumberOfPoints())
    w = dsa.WrapDataObject(d)
    for name in ["velocity", "angular_velocity", "radius", "species", "id"]:
        assert name in w.PointData.keys(), (name, list(w.PointData.keys()))
    assert w.PointData["velocity"].shape == (n, 3)
    assert list(w.PointData["id"]) == [1000 + i for i in range(n)], list(w.PointData["id"])
    for i in range(n):  # positions written by the test: x = 0.001 i, z = 0.01 k
        assert abs(w.Points[i][0] - 0.001 * i) < 1e-15 and abs(w.Points[i][2] - 0.01 * k) < 1e-15
print("ok")
)PY";

} // namespace

using fluidem::XdmfFlavour;

TEST(XdmfWriter, OneGridPerFrameReferencingEveryField) {
  for (const XdmfFlavour flavour : {XdmfFlavour::kXdmf3, XdmfFlavour::kHyperSlab}) {
    SCOPED_TRACE(flavour == XdmfFlavour::kXdmf3 ? "xdmf3" : "hyperslab");
    const std::string x = fluidem::particles_xdmf("particles.h5", 7, kTimes, flavour);
    EXPECT_EQ(count(x, "GridType=\"Uniform\""), 3u);
    EXPECT_EQ(count(x, "CollectionType=\"Temporal\""), 1u);
    EXPECT_EQ(count(x, "TopologyType=\"Polyvertex\" NumberOfElements=\"7\""), 3u);
    const char* const end = flavour == XdmfFlavour::kXdmf3 ? "|" : "<";
    for (const char* field : kFields)
      EXPECT_EQ(count(x, std::string("particles.h5:") + field + end), 3u) << field;
    EXPECT_EQ(count(x, std::string("particles.h5:") + fluidem::kH5mdVertexIndexPath + "<"), 3u);
    EXPECT_EQ(count(x, "<Time Value=\"0\"/>"), 1u);
    EXPECT_EQ(count(x, "<Time Value=\"0.001\"/>"), 1u);
    EXPECT_EQ(count(x, "<Time Value=\"0.25\"/>"), 1u);
    EXPECT_EQ(count(x, "AttributeType=\"Vector\""), 6u);
    EXPECT_EQ(count(x, "AttributeType=\"Scalar\""), 9u);
    // Frame 2 of the vector fields (position, velocity, angular_velocity) and of the scalar ones.
    if (flavour == XdmfFlavour::kXdmf3) {
      EXPECT_EQ(count(x, "|2 0 0:1 1 1:1 7 3:3 7 3<"), 3u);
      EXPECT_EQ(count(x, "|2 0:1 1:1 7:3 7<"), 3u);
      EXPECT_EQ(count(x, "ItemType=\"HyperSlab\""), 0u);
    } else {
      EXPECT_EQ(count(x, ">2 0 0 1 1 1 1 7 3<"), 3u);
      EXPECT_EQ(count(x, ">2 0 1 1 1 7<"), 3u);
      EXPECT_EQ(count(x, "Dimensions=\"3 7 3\""), 9u);
      EXPECT_EQ(count(x, "Dimensions=\"3 7\""), 9u);
      EXPECT_EQ(count(x, "ItemType=\"HyperSlab\""), 18u);
    }
  }
}

TEST(XdmfWriter, EscapesTheFileNameAndRoundTripsTimes) {
  const double t = 1.0 / 3.0;
  const std::string x = fluidem::particles_xdmf("a&b<c>.h5", 2, {t});
  EXPECT_NE(x.find("a&amp;b&lt;c&gt;.h5:/particles/all/position/value"), std::string::npos);
  const std::string key = "<Time Value=\"";
  const std::size_t at = x.find(key);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(std::stod(x.substr(at + key.size())), t);
  EXPECT_THROW(fluidem::particles_xdmf("c:particles.h5", 2, {t}), std::invalid_argument);
  EXPECT_THROW(fluidem::particles_xdmf("a|b.h5", 2, {t}), std::invalid_argument);
}

TEST(XdmfWriter, WritesAtomicallyAndIsWellFormed) {
  TempDir dir;
  const std::string xmf = dir.file("particles.xmf");
  fluidem::write_particles_xdmf(xmf, "particles.h5", 7, {0.0});
  fluidem::write_particles_xdmf(xmf, "particles.h5", 7, kTimes); // replaces the file
  EXPECT_EQ(slurp(xmf), fluidem::particles_xdmf("particles.h5", 7, kTimes));
  EXPECT_FALSE(fs::exists(xmf + ".tmp"));
  if (!python_runs("xml.dom.minidom")) GTEST_SKIP() << FLUIDEM_PYTHON << " does not run";
  { std::ofstream(dir.file("check.py")) << kCheckScript; }
  const std::string check =
      std::string(FLUIDEM_PYTHON) + " '" + dir.file("check.py") + "' '" + xmf + "' ";
  EXPECT_EQ(run(check + "7 3 0"), 0);
  fluidem::write_particles_xdmf(xmf, "particles.h5", 7, kTimes, XdmfFlavour::kHyperSlab);
  EXPECT_EQ(run(check + "7 3 0"), 0);
  // No frame yet is still a valid file.
  fluidem::write_particles_xdmf(xmf, "particles.h5", 7, {});
  EXPECT_EQ(run(check + "7 0 0"), 0);
}

namespace {

// particles.h5 with n particles and kTimes.size() frames (x = 0.001 i, z = 0.01 k, id = 1000 + i)
// and, after each frame, particles.xmf (Xdmf3 flavour) and particles_hyperslab.xmf.
void write_run(const TempDir& dir, std::size_t n) {
  fluidem::H5mdWriter w(dir.file("particles.h5"), n, 3, "test");
  std::vector<double> times;
  for (std::size_t k = 0; k < kTimes.size(); ++k) {
    fluidem::ParticleStore p;
    for (std::size_t i = 0; i < n; ++i)
      p.add({0.001 * static_cast<double>(i), 0.0, 0.01 * static_cast<double>(k)}, {0.0, 0.0, -1.0},
            5e-4, 2500.0, static_cast<std::int32_t>(i % 2), 1000 + static_cast<std::int64_t>(i));
    w.write_frame(static_cast<long>(100 * k), kTimes[k], p);
    times.push_back(kTimes[k]);
    fluidem::write_particles_xdmf(dir.file("particles.xmf"), "particles.h5", n, times);
    fluidem::write_particles_xdmf(dir.file("particles_hyperslab.xmf"), "particles.h5", n, times,
                                  XdmfFlavour::kHyperSlab);
  }
}

} // namespace

TEST(XdmfWriter, MatchesTheH5mdFile) {
  if (!python_runs("h5py, numpy")) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy";
  TempDir dir;
  write_run(dir, 7);
  { std::ofstream(dir.file("check.py")) << kCheckScript; }
  for (const char* xmf : {"particles.xmf", "particles_hyperslab.xmf"}) {
    EXPECT_EQ(run(std::string(FLUIDEM_PYTHON) + " '" + dir.file("check.py") + "' '" +
                  dir.file(xmf) + "' 7 3 1"),
              0)
        << xmf;
  }
}

// Only where ParaView's pvpython is installed (Debian package python3-paraview); skipped elsewhere.
TEST(XdmfWriter, ParaViewReadsEveryFrame) {
  if (run("command -v pvpython >/dev/null 2>&1") != 0) GTEST_SKIP() << "no pvpython";
  TempDir dir;
  write_run(dir, 5);
  { std::ofstream(dir.file("pv.py")) << kParaViewScript; }
  const std::string times = "0,0.001,0.25";
  const struct {
    const char* file;
    const char* reader;
  } cases[] = {{"particles.xmf", "xdmf3"}, {"particles_hyperslab.xmf", "legacy"}};
  for (const auto& c : cases) {
    const std::string log = dir.file(std::string(c.reader) + ".log");
    EXPECT_EQ(run("pvpython --force-offscreen-rendering '" + dir.file("pv.py") + "' '" +
                  dir.file(c.file) + "' " + c.reader + " 5 " + times + " > '" + log + "' 2>&1"),
              0)
        << c.file << " with the " << c.reader << " reader:\n"
        << slurp(log);
  }
}

TEST(XdmfWriter, UnwritableDirectoryThrowsNamingTheFile) {
  const std::string xmf = "/nonexistent-fluidem-dir/particles.xmf";
  try {
    fluidem::write_particles_xdmf(xmf, "particles.h5", 1, {0.0});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(xmf), std::string::npos) << e.what();
  }
}
