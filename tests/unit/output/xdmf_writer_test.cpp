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

// Python: parse the XDMF file, check its structure; with check_h5, also open the HDF5 datasets it
// references (h5py) and compare shapes, frame selections and times.
const char* const kCheckScript = R"PY(
import sys, os, xml.dom.minidom
xmf, n, frames, check_h5 = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4] == "1"
doc = xml.dom.minidom.parse(xmf)
root = doc.documentElement
assert root.tagName == "Xdmf" and root.getAttribute("Version") == "3.0", root.tagName
domains = root.getElementsByTagName("Domain")
assert len(domains) == 1
coll = [g for g in domains[0].childNodes if g.nodeType == g.ELEMENT_NODE]
assert len(coll) == 1 and coll[0].getAttribute("CollectionType") == "Temporal"
grids = [g for g in coll[0].childNodes if g.nodeType == g.ELEMENT_NODE and g.tagName == "Grid"]
assert len(grids) == frames, (len(grids), frames)
if check_h5:
    import h5py, numpy as np
for k, g in enumerate(grids):
    topo = g.getElementsByTagName("Topology")[0]
    assert topo.getAttribute("TopologyType") == "Polyvertex"
    assert int(topo.getAttribute("NumberOfElements")) == n
    assert g.getElementsByTagName("Geometry")[0].getAttribute("GeometryType") == "XYZ"
    names = sorted(a.getAttribute("Name") for a in g.getElementsByTagName("Attribute"))
    assert names == sorted(["velocity", "angular_velocity", "radius", "species", "id"]), names
    time = float(g.getElementsByTagName("Time")[0].getAttribute("Value"))
    for item in g.getElementsByTagName("DataItem"):
        if item.getAttribute("ItemType") != "HyperSlab":
            continue
        sel, data = [c for c in item.childNodes if c.nodeType == c.ELEMENT_NODE]
        rows = [int(v) for v in sel.firstChild.data.split()]
        rank = len(rows) // 3
        start, stride, cnt = rows[:rank], rows[rank:2 * rank], rows[2 * rank:]
        assert start[0] == k and all(s == 0 for s in start[1:]), start
        assert all(s == 1 for s in stride) and cnt[0] == 1 and cnt[1] == n, cnt
        dims = [int(v) for v in data.getAttribute("Dimensions").split()]
        assert [int(v) for v in item.getAttribute("Dimensions").split()] == cnt
        assert dims[0] == frames and dims[1] == n, dims
        fname, path = data.firstChild.data.strip().split(":")
        if check_h5:
            with h5py.File(os.path.join(os.path.dirname(xmf), fname), "r") as f:
                ds = f[path]
                assert list(ds.shape) == dims, (path, ds.shape, dims)
                nbytes = int(data.getAttribute("Precision"))
                assert ds.dtype.itemsize == nbytes, (path, ds.dtype)
                kind = "f" if data.getAttribute("NumberType") == "Float" else "i"
                assert ds.dtype.kind == kind, (path, ds.dtype)
                assert f["particles/all/position/time"][k] == time
    if check_h5:
        conn = topo.getElementsByTagName("DataItem")[0]
        fname, path = conn.firstChild.data.strip().split(":")
        with h5py.File(os.path.join(os.path.dirname(xmf), fname), "r") as f:
            assert list(f[path][:]) == list(range(n)), path
print("ok")
)PY";

} // namespace

TEST(XdmfWriter, OneGridPerFrameReferencingEveryField) {
  const std::string x = fluidem::particles_xdmf("particles.h5", 7, kTimes);
  EXPECT_EQ(count(x, "GridType=\"Uniform\""), 3u);
  EXPECT_EQ(count(x, "CollectionType=\"Temporal\""), 1u);
  EXPECT_EQ(count(x, "TopologyType=\"Polyvertex\" NumberOfElements=\"7\""), 3u);
  for (const char* field : kFields)
    EXPECT_EQ(count(x, std::string("particles.h5:") + field + "<"), 3u) << field;
  EXPECT_EQ(count(x, std::string("particles.h5:") + fluidem::kH5mdVertexIndexPath), 3u);
  EXPECT_EQ(count(x, "<Time Value=\"0\"/>"), 1u);
  EXPECT_EQ(count(x, "<Time Value=\"0.001\"/>"), 1u);
  EXPECT_EQ(count(x, "<Time Value=\"0.25\"/>"), 1u);
  // Frame 2 of a vector field and of a scalar field.
  EXPECT_EQ(count(x, ">2 0 0 1 1 1 1 7 3<"), 3u); // position, velocity, angular_velocity
  EXPECT_EQ(count(x, ">2 0 1 1 1 7<"), 3u);       // radius, species, id
  EXPECT_EQ(count(x, "Dimensions=\"3 7 3\""), 9u);
  EXPECT_EQ(count(x, "Dimensions=\"3 7\""), 9u);
  EXPECT_EQ(count(x, "AttributeType=\"Vector\""), 6u);
  EXPECT_EQ(count(x, "AttributeType=\"Scalar\""), 9u);
}

TEST(XdmfWriter, EscapesTheFileNameAndRoundTripsTimes) {
  const double t = 1.0 / 3.0;
  const std::string x = fluidem::particles_xdmf("a&b<c>.h5", 2, {t});
  EXPECT_NE(x.find("a&amp;b&lt;c&gt;.h5:/particles/all/position/value"), std::string::npos);
  const std::string key = "<Time Value=\"";
  const std::size_t at = x.find(key);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(std::stod(x.substr(at + key.size())), t);
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
  EXPECT_EQ(
      run(std::string(FLUIDEM_PYTHON) + " '" + dir.file("check.py") + "' '" + xmf + "' 7 3 0"), 0);
  // No frame yet is still a valid file.
  fluidem::write_particles_xdmf(xmf, "particles.h5", 7, {});
  EXPECT_EQ(
      run(std::string(FLUIDEM_PYTHON) + " '" + dir.file("check.py") + "' '" + xmf + "' 7 0 0"), 0);
}

TEST(XdmfWriter, MatchesTheH5mdFile) {
  if (!python_runs("h5py, numpy")) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy";
  TempDir dir;
  const std::size_t n = 7;
  {
    fluidem::H5mdWriter w(dir.file("particles.h5"), n, 3, "test");
    std::vector<double> times;
    for (std::size_t k = 0; k < kTimes.size(); ++k) {
      fluidem::ParticleStore p;
      for (std::size_t i = 0; i < n; ++i)
        p.add({0.001 * static_cast<double>(i), 0.0, 0.01 * static_cast<double>(k)},
              {0.0, 0.0, -1.0}, 5e-4, 2500.0, static_cast<std::int32_t>(i % 2),
              static_cast<std::int64_t>(i));
      w.write_frame(static_cast<long>(100 * k), kTimes[k], p);
      times.push_back(kTimes[k]);
      fluidem::write_particles_xdmf(dir.file("particles.xmf"), "particles.h5", n, times);
    }
  }
  { std::ofstream(dir.file("check.py")) << kCheckScript; }
  EXPECT_EQ(run(std::string(FLUIDEM_PYTHON) + " '" + dir.file("check.py") + "' '" +
                dir.file("particles.xmf") + "' 7 3 1"),
            0);
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
