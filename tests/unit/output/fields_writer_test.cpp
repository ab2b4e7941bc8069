// FieldsWriter + write_fields_xdmf: write 3 frames of analytic fields on a 4x1x3 (2-D) and a
// 3x4x5 grid, read them back with the HDF5 C API and check every value bitwise against the field
// at the cell centre (which also checks the index order); check the XDMF text; with h5py, follow
// the XDMF references into the HDF5 file; with pvpython (where installed), open the XDMF in
// ParaView and compare every cell value against the field at the cell centre that VTK computes.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "output/fields_writer.hpp"
#include "output/fields_xdmf.hpp"

namespace fs = std::filesystem;
using fluidem::FieldGrid;
using fluidem::FieldsWriter;
using fluidem::XdmfFlavour;

namespace {

class TempDir {
public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("fluidem_fields_" + std::to_string(::getpid()) + "_" +
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

bool bitwise_equal(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// --- the analytic fields (the Python scripts below repeat them) ----------------------------------

double pressure(double x, double y, double z, double t) {
  return x + 10.0 * y + 100.0 * z + 1000.0 * t;
}
double porosity(double x, double y, double z, double t) {
  return std::sin(3.0 * x) * std::cos(y) + z * z - t;
}
std::array<double, 3> velocity(double x, double y, double z, double t) {
  return {x * t + 1.0, y - 2.0 * z, 3.0 * x + z * t};
}

const std::vector<std::string> kScalars = {"pressure", "porosity"};
const std::vector<std::string> kVectors = {"velocity"};
const std::vector<long> kSteps = {0, 10, 20};
const std::vector<double> kTimes = {0.0, 0.125, 1.0 / 3.0};

// Distinct origin and spacing per axis, so that a swapped axis shows.
FieldGrid grid_2d() { // 4 x 1 x 3 cells (a 2-D run: one cell along y)
  return {{4, 1, 3}, {-0.1, 0.0, 0.2}, {0.05, 0.01, 0.1}};
}
FieldGrid grid_3d() { // 3 x 4 x 5 cells
  return {{3, 4, 5}, {1.0, -2.0, 0.5}, {0.25, 0.5, 0.125}};
}

double centre(const FieldGrid& g, int axis, int index) {
  return g.lo[axis] + (index + 0.5) * g.spacing[axis];
}

struct Frame {
  std::vector<double> p, eps, ux, uy, uz;
};

// Field values at the cell centres of g at time t, x-fastest.
Frame make_frame(const FieldGrid& g, double t) {
  Frame f;
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) {
        const double x = centre(g, 0, i), y = centre(g, 1, j), z = centre(g, 2, k);
        f.p.push_back(pressure(x, y, z, t));
        f.eps.push_back(porosity(x, y, z, t));
        const auto u = velocity(x, y, z, t);
        f.ux.push_back(u[0]);
        f.uy.push_back(u[1]);
        f.uz.push_back(u[2]);
      }
  return f;
}

// fields.h5 with 3 frames; after each frame fields.xmf (Xdmf3) and fields_hyperslab.xmf.
void write_run(const TempDir& dir, const FieldGrid& g) {
  FieldsWriter w(dir.file("fields.h5"), g, kScalars, kVectors, "0.1.0-test");
  std::vector<double> times;
  for (std::size_t f = 0; f < kTimes.size(); ++f) {
    const Frame fr = make_frame(g, kTimes[f]);
    w.write_frame(kSteps[f], kTimes[f], {fr.p.data(), fr.eps.data()},
                  {{fr.ux.data(), fr.uy.data(), fr.uz.data()}});
    times.push_back(kTimes[f]);
    EXPECT_EQ(w.frames(), times.size());
    fluidem::write_fields_xdmf(dir.file("fields.xmf"), "fields.h5", g, kScalars, kVectors, times);
    fluidem::write_fields_xdmf(dir.file("fields_hyperslab.xmf"), "fields.h5", g, kScalars, kVectors,
                               times, XdmfFlavour::kHyperSlab);
  }
  w.close();
}

// --- reading back with the C API -----------------------------------------------------------------

std::vector<hsize_t> dims_of(hid_t file, const char* path) {
  std::vector<hsize_t> dims;
  const hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
  EXPECT_GE(ds, 0) << path;
  if (ds < 0) return dims;
  const hid_t space = H5Dget_space(ds);
  dims.resize(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Dclose(ds);
  return dims;
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

// One element of a dataset, by its coordinates in the file.
double read_one(hid_t file, const char* path, const std::vector<hsize_t>& at) {
  double v = std::nan("");
  const hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
  EXPECT_GE(ds, 0) << path;
  if (ds < 0) return v;
  const hid_t space = H5Dget_space(ds);
  const std::vector<hsize_t> ones(at.size(), 1);
  EXPECT_GE(H5Sselect_hyperslab(space, H5S_SELECT_SET, at.data(), nullptr, ones.data(), nullptr),
            0);
  const hsize_t one = 1;
  const hid_t mem = H5Screate_simple(1, &one, nullptr);
  EXPECT_GE(H5Dread(ds, H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, &v), 0);
  H5Sclose(mem);
  H5Sclose(space);
  H5Dclose(ds);
  return v;
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

std::string read_string_attr(hid_t file, const char* object, const char* name) {
  const auto v = read_string_array_attr(file, object, name);
  return v.empty() ? std::string() : v[0];
}

std::int64_t read_int64_attr(hid_t file, const char* object, const char* name) {
  std::int64_t v = -1;
  const hid_t attr = H5Aopen_by_name(file, object, name, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(attr, 0) << object << " @" << name;
  if (attr < 0) return v;
  EXPECT_GE(H5Aread(attr, H5T_NATIVE_INT64, &v), 0);
  H5Aclose(attr);
  return v;
}

// Python: parse the XDMF file (either flavour), follow each attribute's reference into the HDF5
// file with h5py, and compare every cell value against the fields at the cell centres computed
// from the XDMF geometry (origin and spacing in z y x order).
const char* const kCheckScript = R"PY(
import sys, os, math, xml.dom.minidom
import h5py, numpy as np
xmf, nx, ny, nz = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
times = [float(t) for t in sys.argv[5].split(",")]
elements = lambda node: [c for c in node.childNodes if c.nodeType == c.ELEMENT_NODE]
numbers = lambda item: [float(v) for v in item.firstChild.data.split()]
doc = xml.dom.minidom.parse(xmf)
(domain,) = doc.documentElement.getElementsByTagName("Domain")
(coll,) = elements(domain)
assert coll.getAttribute("CollectionType") == "Temporal"
grids = [g for g in elements(coll) if g.tagName == "Grid"]
assert len(grids) == len(times), (len(grids), len(times))

def frame_values(item, k):
    if item.getAttribute("ItemType") == "HyperSlab":
        sel, data = elements(item)
        rows = [int(v) for v in sel.firstChild.data.split()]
        r = len(rows) // 3
        start, stride, cnt = rows[:r], rows[r:2 * r], rows[2 * r:]
        dims = [int(v) for v in data.getAttribute("Dimensions").split()]
        fname, path = data.firstChild.data.strip().split(":")
    else:
        fname, rest = item.firstChild.data.strip().split(":", 1)
        path, space = rest.split("|")
        start, stride, cnt, dims = [[int(v) for v in p.split()] for p in space.split(":")]
    shape = [1] + [int(v) for v in item.getAttribute("Dimensions").split()]
    assert start == [k] + [0] * (len(start) - 1), start
    assert all(s == 1 for s in stride) and cnt == shape, (stride, cnt, shape)
    with h5py.File(os.path.join(os.path.dirname(xmf), fname), "r") as f:
        ds = f[path]
        assert list(ds.shape) == dims and ds.dtype == np.float64, (path, ds.shape, dims)
        assert float(f["fields/time"][k]) == times[k]
        return ds[k]

for k, g in enumerate(grids):
    t = float(g.getElementsByTagName("Time")[0].getAttribute("Value"))
    assert t == times[k], (t, times[k])
    (topo,) = g.getElementsByTagName("Topology")
    assert topo.getAttribute("TopologyType") == "3DCoRectMesh"
    assert [int(v) for v in topo.getAttribute("Dimensions").split()] == [nz + 1, ny + 1, nx + 1]
    (geo,) = g.getElementsByTagName("Geometry")
    assert geo.getAttribute("GeometryType") == "ORIGIN_DXDYDZ"
    origin, spacing = [numbers(d) for d in elements(geo)]
    lo = origin[::-1]  # XDMF: z y x
    d = spacing[::-1]
    attrs = {a.getAttribute("Name"): a for a in g.getElementsByTagName("Attribute")}
    assert sorted(attrs) == ["porosity", "pressure", "velocity"], list(attrs)
    for a in attrs.values():
        assert a.getAttribute("Center") == "Cell"
    p = frame_values(elements(attrs["pressure"])[0], k)
    eps = frame_values(elements(attrs["porosity"])[0], k)
    u = frame_values(elements(attrs["velocity"])[0], k)
    assert p.shape == (nz, ny, nx) and eps.shape == (nz, ny, nx) and u.shape == (nz, ny, nx, 3)
    close = lambda a, b: abs(a - b) <= 1e-12 * (1.0 + abs(b))
    for kk in range(nz):
        for j in range(ny):
            for i in range(nx):
                x, y, z = (lo[0] + (i + 0.5) * d[0], lo[1] + (j + 0.5) * d[1],
                           lo[2] + (kk + 0.5) * d[2])
                assert close(p[kk, j, i], x + 10 * y + 100 * z + 1000 * t), (k, i, j, kk)
                assert close(eps[kk, j, i], math.sin(3 * x) * math.cos(y) + z * z - t)
                for c, want in enumerate([x * t + 1, y - 2 * z, 3 * x + z * t]):
                    assert close(u[kk, j, i, c], want), (k, i, j, kk, c)
print("ok")
)PY";

// pvpython: open the file with the given reader; at every time step check the image geometry and
// every cell value against the fields at the cell centre as VTK computes it.
const char* const kParaViewScript = R"PY(
import sys, math
from paraview.simple import Xdmf3ReaderS, XDMFReader
from paraview import servermanager as sm
xmf, reader, nx, ny, nz = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
times = [float(t) for t in sys.argv[6].split(",")]
r = Xdmf3ReaderS(FileName=[xmf]) if reader == "xdmf3" else XDMFReader(FileNames=[xmf])
assert [float(t) for t in r.TimestepValues] == times, list(r.TimestepValues)
close = lambda a, b: abs(a - b) <= 1e-12 * (1.0 + abs(b))
for t in times:
    r.UpdatePipeline(t)
    d = sm.Fetch(r)
    if d.IsA("vtkMultiBlockDataSet"):
        d = d.GetBlock(0)
    assert d.GetNumberOfCells() == nx * ny * nz, (d.GetClassName(), d.GetNumberOfCells())
    assert d.GetNumberOfPoints() == (nx + 1) * (ny + 1) * (nz + 1)
    if d.IsA("vtkImageData"):
        assert list(d.GetDimensions()) == [nx + 1, ny + 1, nz + 1], d.GetDimensions()
    cd = d.GetCellData()
    p, eps, u = cd.GetArray("pressure"), cd.GetArray("porosity"), cd.GetArray("velocity")
    assert p is not None and eps is not None and u is not None, cd
    assert u.GetNumberOfComponents() == 3
    for c in range(d.GetNumberOfCells()):
        b = d.GetCell(c).GetBounds()
        x, y, z = 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])
        assert close(p.GetValue(c), x + 10 * y + 100 * z + 1000 * t), (t, c, x, y, z, p.GetValue(c))
        assert close(eps.GetValue(c), math.sin(3 * x) * math.cos(y) + z * z - t), (t, c)
        for k, want in enumerate([x * t + 1, y - 2 * z, 3 * x + z * t]):
            assert close(u.GetComponent(c, k), want), (t, c, k, u.GetComponent(c, k), want)
print("ok")
)PY";

std::string times_arg() {
  std::string s;
  for (const double t : kTimes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", t);
    s += (s.empty() ? "" : ",") + std::string(buf);
  }
  return s;
}

} // namespace

TEST(FieldsWriter, WritesGridAndEveryValueInCOrder) {
  for (const FieldGrid& g : {grid_2d(), grid_3d()}) {
    const int nx = g.cells[0], ny = g.cells[1], nz = g.cells[2];
    SCOPED_TRACE(std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz));
    TempDir dir;
    write_run(dir, g);

    const std::string path = dir.file("fields.h5");
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    EXPECT_EQ(read_string_attr(f, "/", "creator"), "fluidem");
    EXPECT_EQ(read_string_attr(f, "/", "version"), "0.1.0-test");
    EXPECT_EQ(read_string_array_attr(f, "/fields", "scalars"), kScalars);
    EXPECT_EQ(read_string_array_attr(f, "/fields", "vectors"), kVectors);
    EXPECT_EQ(read_int64_attr(f, "/fields", "frames"), 3);

    // The grid, read back, is what the reader will use.
    const auto cells = read_all<int>(f, "/grid/cells", H5T_NATIVE_INT);
    EXPECT_EQ(cells, (std::vector<int>{nx, ny, nz}));
    const auto lo = read_all<double>(f, "/grid/lo", H5T_NATIVE_DOUBLE);
    const auto spacing = read_all<double>(f, "/grid/spacing", H5T_NATIVE_DOUBLE);
    ASSERT_EQ(lo.size(), 3u);
    ASSERT_EQ(spacing.size(), 3u);
    FieldGrid r;
    for (int d = 0; d < 3; ++d) {
      EXPECT_TRUE(bitwise_equal(lo[d], g.lo[d])) << d;
      EXPECT_TRUE(bitwise_equal(spacing[d], g.spacing[d])) << d;
      r.lo[d] = lo[d];
      r.spacing[d] = spacing[d];
    }

    EXPECT_EQ(read_all<std::int64_t>(f, "/fields/step", H5T_NATIVE_INT64),
              (std::vector<std::int64_t>{0, 10, 20}));
    const auto times = read_all<double>(f, "/fields/time", H5T_NATIVE_DOUBLE);
    ASSERT_EQ(times.size(), kTimes.size());
    for (std::size_t k = 0; k < kTimes.size(); ++k) EXPECT_TRUE(bitwise_equal(times[k], kTimes[k]));

    const hsize_t F = 3, Z = nz, Y = ny, X = nx;
    EXPECT_EQ(dims_of(f, "/fields/pressure"), (std::vector<hsize_t>{F, Z, Y, X}));
    EXPECT_EQ(dims_of(f, "/fields/porosity"), (std::vector<hsize_t>{F, Z, Y, X}));
    EXPECT_EQ(dims_of(f, "/fields/velocity"), (std::vector<hsize_t>{F, Z, Y, X, 3}));
    const auto p = read_all<double>(f, "/fields/pressure", H5T_NATIVE_DOUBLE);
    const auto eps = read_all<double>(f, "/fields/porosity", H5T_NATIVE_DOUBLE);
    const auto u = read_all<double>(f, "/fields/velocity", H5T_NATIVE_DOUBLE);
    ASSERT_EQ(p.size(), F * Z * Y * X);
    ASSERT_EQ(eps.size(), p.size());
    ASSERT_EQ(u.size(), 3 * p.size());
    int bad = 0;
    for (std::size_t fr = 0; fr < F; ++fr) {
      const double t = kTimes[fr];
      for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
          for (int i = 0; i < nx; ++i) {
            // C order of [F][nz][ny][nx]: element (fr, k, j, i)
            const std::size_t at = ((fr * Z + k) * Y + j) * X + i;
            const double x = centre(r, 0, i), y = centre(r, 1, j), z = centre(r, 2, k);
            const auto want_u = velocity(x, y, z, t);
            const bool ok = bitwise_equal(p[at], pressure(x, y, z, t)) &&
                            bitwise_equal(eps[at], porosity(x, y, z, t)) &&
                            bitwise_equal(u[3 * at], want_u[0]) &&
                            bitwise_equal(u[3 * at + 1], want_u[1]) &&
                            bitwise_equal(u[3 * at + 2], want_u[2]);
            if (!ok && ++bad <= 5)
              ADD_FAILURE() << "frame " << fr << " cell (" << i << "," << j << "," << k
                            << "): pressure " << p[at] << " want " << pressure(x, y, z, t);
          }
    }
    EXPECT_EQ(bad, 0);

    // Index order by hand: file element [1][nz-1][ny-1][1] is cell (1, ny-1, nz-1) at t1, and the
    // y component of velocity there is [1][nz-1][ny-1][1][1].
    const double x = centre(g, 0, 1), y = centre(g, 1, ny - 1), z = centre(g, 2, nz - 1);
    EXPECT_EQ(read_one(f, "/fields/pressure", {1, Z - 1, Y - 1, 1}), pressure(x, y, z, kTimes[1]));
    EXPECT_EQ(read_one(f, "/fields/velocity", {1, Z - 1, Y - 1, 1, 1}),
              velocity(x, y, z, kTimes[1])[1]);
    H5Fclose(f);
  }
}

// Another process (h5py) sees each frame while the writer still has the file open.
TEST(FieldsWriter, VisibleToAReaderAfterEachFrame) {
  if (!python_runs("h5py, numpy")) GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy";
  TempDir dir;
  const FieldGrid g = grid_3d();
  FieldsWriter w(dir.file("fields.h5"), g, {"p"}, {}, "test");
  EXPECT_EQ(w.frames(), 0u);
  const std::string check = "HDF5_USE_FILE_LOCKING=FALSE " + std::string(FLUIDEM_PYTHON) +
                            " -c 'import sys, h5py\n"
                            "f = h5py.File(sys.argv[1], \"r\")\n"
                            "n = int(sys.argv[2])\n"
                            "assert f[\"fields/p\"].shape == (n, 5, 4, 3), f[\"fields/p\"].shape\n"
                            "assert list(f[\"fields/step\"]) == list(range(7, 7 + n))\n"
                            "assert \"vectors\" not in f[\"fields\"].attrs\n"
                            "if n: assert f[\"fields/p\"][n - 1, 4, 3, 2] == 0.5 * n' '" +
                            dir.file("fields.h5") + "' ";
  EXPECT_EQ(run(check + "0"), 0);
  for (int k = 1; k <= 2; ++k) {
    std::vector<double> p(g.size(), 0.0);
    p.back() = 0.5 * k;
    w.write_frame(6 + k, 0.5 * k, {p.data()}, {});
    EXPECT_EQ(run(check + std::to_string(k)), 0) << "after frame " << k;
  }
}

TEST(FieldsWriter, BadInputThrows) {
  TempDir dir;
  const FieldGrid g = grid_2d();
  const std::string path = dir.file("fields.h5");
  FieldsWriter w(path, g, kScalars, kVectors, "test");
  const Frame fr = make_frame(g, 0.0);
  const double* const p = fr.p.data();
  const std::array<const double*, 3> u{fr.ux.data(), fr.uy.data(), fr.uz.data()};
  EXPECT_THROW(w.write_frame(0, 0.0, {p}, {u}), std::invalid_argument);          // 1 scalar of 2
  EXPECT_THROW(w.write_frame(0, 0.0, {p, p, p}, {u}), std::invalid_argument);    // 3 of 2
  EXPECT_THROW(w.write_frame(0, 0.0, {p, p}, {}), std::invalid_argument);        // 0 vectors of 1
  EXPECT_THROW(w.write_frame(0, 0.0, {p, p}, {u, u}), std::invalid_argument);    // 2 of 1
  EXPECT_THROW(w.write_frame(0, 0.0, {p, nullptr}, {u}), std::invalid_argument); // null scalar
  EXPECT_THROW(w.write_frame(0, 0.0, {p, p}, {{u[0], nullptr, u[2]}}), std::invalid_argument);
  try {
    w.write_frame(0, 0.0, {p}, {u});
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_EQ(w.frames(), 0u); // nothing written
  w.write_frame(0, 0.0, {p, p}, {u});
  EXPECT_EQ(w.frames(), 1u);
  w.close();
  w.close(); // idempotent
  EXPECT_THROW(w.write_frame(1, 1.0, {p, p}, {u}), std::logic_error);

  // Grids and names.
  const auto make = [&](const FieldGrid& grid, std::vector<std::string> s,
                        std::vector<std::string> v) {
    FieldsWriter bad(dir.file("bad.h5"), grid, std::move(s), std::move(v), "test");
  };
  for (const FieldGrid& bad :
       {FieldGrid{{0, 1, 1}, {0, 0, 0}, {1, 1, 1}}, FieldGrid{{1, 1, -2}, {0, 0, 0}, {1, 1, 1}},
        FieldGrid{{1, 1, 1}, {0, 0, 0}, {1, 0, 1}}, FieldGrid{{1, 1, 1}, {0, 0, 0}, {1, 1, -1}},
        FieldGrid{{1, 1, 1}, {0, std::nan(""), 0}, {1, 1, 1}},
        FieldGrid{{1, 1, 1}, {0, 0, 0}, {INFINITY, 1, 1}}}) {
    EXPECT_THROW(make(bad, {"p"}, {}), std::invalid_argument);
    EXPECT_THROW(fluidem::fields_xdmf("f.h5", bad, {"p"}, {}, {0.0}), std::invalid_argument);
  }
  using V = std::vector<std::string>;
  for (const auto& [s, v] :
       {std::pair{V{""}, V{}}, std::pair{V{"a/b"}, V{}}, std::pair{V{"p"}, V{"p"}},
        std::pair{V{"p", "p"}, V{}}, std::pair{V{}, V{"time"}}, std::pair{V{"step"}, V{}},
        std::pair{V{"a:b"}, V{}}, std::pair{V{"a|b"}, V{}}, std::pair{V{"."}, V{}},
        std::pair{V{"a\nb"}, V{}}}) {
    EXPECT_THROW(make(g, s, v), std::invalid_argument) << (s.empty() ? v[0] : s[0]);
    EXPECT_THROW(fluidem::fields_xdmf("f.h5", g, s, v, {0.0}), std::invalid_argument);
  }
  EXPECT_NO_THROW(make(g, {}, {})); // a file with time and step only is fine
  EXPECT_THROW(fluidem::fields_xdmf("c:fields.h5", g, {"p"}, {}, {0.0}), std::invalid_argument);
  EXPECT_THROW(fluidem::fields_xdmf("a|b.h5", g, {"p"}, {}, {0.0}), std::invalid_argument);
}

TEST(FieldsWriter, UnwritablePathsThrowNamingTheFile) {
  const std::string h5 = "/nonexistent-fluidem-dir/fields.h5";
  try {
    FieldsWriter w(h5, grid_2d(), {"p"}, {}, "test");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(h5), std::string::npos) << e.what();
  }
  const std::string xmf = "/nonexistent-fluidem-dir/fields.xmf";
  try {
    fluidem::write_fields_xdmf(xmf, "fields.h5", grid_2d(), {"p"}, {}, {0.0});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(xmf), std::string::npos) << e.what();
  }
}

TEST(FieldsXdmf, DimensionsOriginSpacingAndTimes) {
  { // 4 x 1 x 3, lo (-0.1, 0, 0.2), spacing (0.05, 0.01, 0.1): z y x order in XDMF
    const std::string x = fluidem::fields_xdmf("fields.h5", grid_2d(), kScalars, kVectors, kTimes);
    EXPECT_EQ(count(x, "CollectionType=\"Temporal\""), 1u);
    EXPECT_EQ(count(x, "GridType=\"Uniform\""), 3u);
    EXPECT_EQ(count(x, "<Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"4 2 5\"/>"), 3u);
    EXPECT_EQ(count(x, "<Geometry GeometryType=\"ORIGIN_DXDYDZ\">"), 3u);
    EXPECT_EQ(count(x, "Format=\"XML\">0.2 0 -0.1</DataItem>"), 3u);
    EXPECT_EQ(count(x, "Format=\"XML\">0.1 0.01 0.05</DataItem>"), 3u);
    EXPECT_EQ(count(x, "<Time Value=\"0\"/>"), 1u);
    EXPECT_EQ(count(x, "<Time Value=\"0.125\"/>"), 1u);
    EXPECT_EQ(count(x, "<Time Value=\"0.3333333333333333\"/>"), 1u);
    EXPECT_EQ(count(x, "Center=\"Cell\""), 9u);
    EXPECT_EQ(count(x, "<Attribute Name=\"pressure\" AttributeType=\"Scalar\""), 3u);
    EXPECT_EQ(count(x, "<Attribute Name=\"velocity\" AttributeType=\"Vector\""), 3u);
    // Frame 2 of a scalar and of the vector field, Xdmf3 selection suffix.
    EXPECT_EQ(count(x, "<DataItem Dimensions=\"3 1 4\" NumberType=\"Float\" Precision=\"8\" "
                       "Format=\"HDF\">fields.h5:/fields/pressure|2 0 0 0:1 1 1 1:1 3 1 4:3 3 1 "
                       "4</DataItem>"),
              1u);
    EXPECT_EQ(count(x, "<DataItem Dimensions=\"3 1 4 3\" NumberType=\"Float\" Precision=\"8\" "
                       "Format=\"HDF\">fields.h5:/fields/velocity|2 0 0 0 0:1 1 1 1 1:1 3 1 4 "
                       "3:3 3 1 4 3</DataItem>"),
              1u);
    EXPECT_EQ(count(x, "HyperSlab"), 0u);
  }
  { // 3 x 4 x 5, lo (1, -2, 0.5), spacing (0.25, 0.5, 0.125)
    const std::string x = fluidem::fields_xdmf("fields.h5", grid_3d(), {"p"}, {}, {0.0, 1e-3});
    EXPECT_EQ(count(x, "TopologyType=\"3DCoRectMesh\" Dimensions=\"6 5 4\""), 2u);
    EXPECT_EQ(count(x, "Format=\"XML\">0.5 -2 1</DataItem>"), 2u);
    EXPECT_EQ(count(x, "Format=\"XML\">0.125 0.5 0.25</DataItem>"), 2u);
    EXPECT_EQ(count(x, "fields.h5:/fields/p|1 0 0 0:1 1 1 1:1 5 4 3:2 5 4 3<"), 1u);
    EXPECT_EQ(count(x, "<Time Value=\"0.001\"/>"), 1u);
    // Legacy flavour: HyperSlab items over the whole [F][nz][ny][nx] dataset.
    const std::string h = fluidem::fields_xdmf("fields.h5", grid_3d(), {"p"}, {"u"}, {0.0, 1e-3},
                                               XdmfFlavour::kHyperSlab);
    EXPECT_EQ(count(h, "ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"5 4 3\""), 2u);
    EXPECT_EQ(count(h, "ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"5 4 3 3\""), 2u);
    EXPECT_EQ(count(h, "<DataItem Dimensions=\"3 4\" Format=\"XML\">1 0 0 0 1 1 1 1 1 5 4 3<"), 1u);
    EXPECT_EQ(count(h, "<DataItem Dimensions=\"3 5\" Format=\"XML\">1 0 0 0 0 1 1 1 1 1 1 5 4 3 "
                       "3<"),
              1u);
    EXPECT_EQ(count(h, "Dimensions=\"2 5 4 3\" NumberType=\"Float\" Precision=\"8\" "
                       "Format=\"HDF\">fields.h5:/fields/p<"),
              2u);
    EXPECT_EQ(count(h, "Dimensions=\"2 5 4 3 3\" NumberType=\"Float\" Precision=\"8\" "
                       "Format=\"HDF\">fields.h5:/fields/u<"),
              2u);
  }
  { // escaping; no frame yet
    const std::string x = fluidem::fields_xdmf("a&b.h5", grid_2d(), {"p<1>"}, {}, {0.0});
    EXPECT_NE(x.find("Name=\"p&lt;1&gt;\""), std::string::npos);
    EXPECT_NE(x.find("a&amp;b.h5:/fields/p&lt;1&gt;|"), std::string::npos);
    EXPECT_EQ(count(fluidem::fields_xdmf("f.h5", grid_2d(), {"p"}, {}, {}), "<Grid"), 1u);
  }
}

TEST(FieldsXdmf, WritesAtomically) {
  TempDir dir;
  const std::string xmf = dir.file("fields.xmf");
  fluidem::write_fields_xdmf(xmf, "fields.h5", grid_3d(), kScalars, kVectors, {0.0});
  fluidem::write_fields_xdmf(xmf, "fields.h5", grid_3d(), kScalars, kVectors, kTimes);
  EXPECT_EQ(slurp(xmf), fluidem::fields_xdmf("fields.h5", grid_3d(), kScalars, kVectors, kTimes));
  EXPECT_FALSE(fs::exists(xmf + ".tmp"));
}

TEST(FieldsXdmf, ReferencesMatchTheFieldsFile) {
  if (!python_runs("h5py, numpy, xml.dom.minidom"))
    GTEST_SKIP() << FLUIDEM_PYTHON << " lacks h5py/numpy";
  for (const FieldGrid& g : {grid_2d(), grid_3d()}) {
    const std::string dims = std::to_string(g.cells[0]) + " " + std::to_string(g.cells[1]) + " " +
                             std::to_string(g.cells[2]);
    SCOPED_TRACE(dims);
    TempDir dir;
    write_run(dir, g);
    { std::ofstream(dir.file("check.py")) << kCheckScript; }
    for (const char* xmf : {"fields.xmf", "fields_hyperslab.xmf"}) {
      const std::string log = dir.file("check.log");
      EXPECT_EQ(run(std::string(FLUIDEM_PYTHON) + " '" + dir.file("check.py") + "' '" +
                    dir.file(xmf) + "' " + dims + " " + times_arg() + " > '" + log + "' 2>&1"),
                0)
          << xmf << ":\n"
          << slurp(log);
    }
  }
}

// Only where ParaView's pvpython is installed (Debian package python3-paraview); skipped elsewhere.
TEST(FieldsXdmf, ParaViewReadsEveryCellAtItsCentre) {
  if (run("command -v pvpython >/dev/null 2>&1") != 0) GTEST_SKIP() << "no pvpython";
  for (const FieldGrid& g : {grid_2d(), grid_3d()}) {
    const std::string dims = std::to_string(g.cells[0]) + " " + std::to_string(g.cells[1]) + " " +
                             std::to_string(g.cells[2]);
    SCOPED_TRACE(dims);
    TempDir dir;
    write_run(dir, g);
    { std::ofstream(dir.file("pv.py")) << kParaViewScript; }
    const struct {
      const char* file;
      const char* reader;
    } cases[] = {{"fields.xmf", "xdmf3"}, {"fields_hyperslab.xmf", "legacy"}};
    for (const auto& c : cases) {
      const std::string log = dir.file(std::string(c.reader) + ".log");
      EXPECT_EQ(run("pvpython --force-offscreen-rendering '" + dir.file("pv.py") + "' '" +
                    dir.file(c.file) + "' " + c.reader + " " + dims + " " + times_arg() + " > '" +
                    log + "' 2>&1"),
                0)
          << c.file << " with the " << c.reader << " reader:\n"
          << slurp(log);
    }
  }
}

// A 100^3 grid with two scalars and one vector (5 arrays, 40 MB a frame): values land and the
// write time is printed (not asserted: it depends on the disk).
TEST(FieldsWriter, LargeGrid) {
  TempDir dir;
  const FieldGrid g{{100, 100, 100}, {0, 0, 0}, {0.01, 0.01, 0.01}};
  const std::size_t n = g.size();
  std::vector<double> a(n), b(n), c(n), d(n), e(n);
  for (std::size_t i = 0; i < n; ++i) {
    a[i] = static_cast<double>(i);
    b[i] = -a[i];
    c[i] = 0.5 * a[i];
    d[i] = 1.0;
    e[i] = 2.0;
  }
  FieldsWriter w(dir.file("fields.h5"), g, {"p", "eps"}, {"u"}, "test");
  const auto t0 = std::chrono::steady_clock::now();
  for (int f = 0; f < 3; ++f)
    w.write_frame(f, 0.1 * f, {a.data(), b.data()}, {{c.data(), d.data(), e.data()}});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "[          ] 3 frames of 100^3 (2 scalars + 1 vector): " << seconds << " s, "
            << 3 * 5 * 8.0 * static_cast<double>(n) / seconds / 1e6 << " MB/s\n";
  w.close();
  const hid_t f = H5Fopen(dir.file("fields.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(dims_of(f, "/fields/u"), (std::vector<hsize_t>{3, 100, 100, 100, 3}));
  // cell (i, j, k) = (7, 42, 99): flat index 7 + 100 (42 + 100 * 99)
  EXPECT_EQ(read_one(f, "/fields/p", {2, 99, 42, 7}), 7.0 + 100.0 * (42.0 + 100.0 * 99.0));
  EXPECT_EQ(read_one(f, "/fields/u", {2, 99, 42, 7, 0}), 0.5 * (7.0 + 100.0 * (42.0 + 9900.0)));
  EXPECT_EQ(read_one(f, "/fields/u", {1, 99, 42, 7, 2}), 2.0);
  H5Fclose(f);
}
