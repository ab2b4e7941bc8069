// Gas/grid fields on a uniform cell-centred grid, one frame per call, HDF5 C API. Plain arrays in,
// so this module needs neither gas/ nor coupling/. fields_xdmf.hpp writes the matching XDMF index.
//
// Grid: nx*ny*nz cells (ny = 1 for 2-D runs, which live in x-z), lower corner lo, cell size
// spacing; cell (i,j,k) has its centre at (lo[0] + (i + 1/2) spacing[0], ..., lo[2] + (k + 1/2)
// spacing[2]). Values are passed x-fastest: cell (i,j,k) is element i + nx*(j + ny*k), which is
// the C order of an array [nz][ny][nx].
//
// Layout written (F frames so far; names given to the constructor):
//   /                        +creator = "fluidem", +version = program_version
//   /grid/cells              int32[3]   {nx, ny, nz}
//        /lo                 float64[3] lower corner (x, y, z), m
//        /spacing            float64[3] cell size (dx, dy, dz), m
//   /fields                  +frames = int64 scalar (F, updated every frame)
//                            +scalars, +vectors = string[] (the field names, in order; absent
//                            when there are none)
//          /step             int64[F]
//          /time             float64[F], s
//          /<scalar name>    float64[F][nz][ny][nx]
//          /<vector name>    float64[F][nz][ny][nx][3]  (components x, y, z)
// Field datasets are chunked with an unlimited first dimension and no compression (write speed
// first); a chunk is one frame, or a slab of whole x-y planes of it when a frame exceeds 16 MiB.
// Any HDF5 failure throws std::runtime_error naming the file and the operation.
//
// Resume (continuing a run from a checkpoint, FieldsWriter::resume): the existing file is reopened
// read-write, checked against the run (grid cells, lo, spacing; scalar and vector names in
// order), and /fields/step, /fields/time and every field dataset are shrunk (H5Dset_extent) to the
// leading frames whose time is <= t_keep; later frames (written after the checkpoint, or cut short
// by a crash) are dropped and write_frame appends from there. The creator/version attributes are
// left as they were. The space of dropped frames stays in the file (HDF5 does not shrink files).
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace fluidem {

/// A uniform cell-centred grid (see the top of this file).
struct FieldGrid {
  std::array<int, 3> cells{1, 1, 1};            ///< nx, ny, nz (ny = 1 in 2-D)
  std::array<double, 3> lo{0.0, 0.0, 0.0};      ///< lower corner, m
  std::array<double, 3> spacing{1.0, 1.0, 1.0}; ///< cell size, m
  std::size_t size() const {
    return static_cast<std::size_t>(cells[0]) * static_cast<std::size_t>(cells[1]) *
           static_cast<std::size_t>(cells[2]);
  }
};

/// std::invalid_argument (message starting with `who`) unless every cell count is >= 1 and every
/// lo / spacing is finite with spacing > 0.
void check_field_grid(const FieldGrid& g, const std::string& who);

/// std::invalid_argument (message starting with `who`) unless every name is non-empty, unique
/// across both lists, not "step" or "time", not "." or "..", and free of '/', ':', '|' and
/// control characters (names are HDF5 link names and appear in XDMF dataset references).
void check_field_names(const std::vector<std::string>& scalar_names,
                       const std::vector<std::string>& vector_names, const std::string& who);

class FieldsWriter {
public:
  /// Create `path` and write the grid. `run_id` (when not empty) goes into the root attribute
  /// run_id, which resume() checks. A regular file at `path` is replaced; a link or anything else
  /// there is refused, never written through. Bad grid or names: std::invalid_argument (see
  /// check_field_grid, check_field_names); I/O: std::runtime_error naming `path`.
  FieldsWriter(const std::string& path, const FieldGrid& grid,
               std::vector<std::string> scalar_names, std::vector<std::string> vector_names,
               const std::string& program_version, const std::string& run_id = {});
  /// Continue the existing fields file `path` (written by this class) after a restart from a
  /// checkpoint, as H5mdWriter::resume does: the file must belong to `run_id` and hold the
  /// frames at `frame_times` (the checkpoint's record), complete and at bitwise those times;
  /// later frames are dropped in a copy renamed over the file; write_frame appends after them.
  /// `check_only`: only check (read-only) and return an empty writer. Bad grid or names:
  /// std::invalid_argument. std::runtime_error naming `path`: the file does not exist, is a link
  /// or is not readable HDF5; it does not match the run (grid, field names; the message says what
  /// differs) or lacks part of the layout; another run's, or short of the checkpoint's frames.
  static FieldsWriter resume(const std::string& path, const std::vector<double>& frame_times,
                             const std::string& run_id, const FieldGrid& grid,
                             std::vector<std::string> scalar_names,
                             std::vector<std::string> vector_names, bool check_only = false);

  ~FieldsWriter(); ///< closes the file; errors on this path are swallowed (call close() to see)
  FieldsWriter(FieldsWriter&&) noexcept;
  FieldsWriter& operator=(FieldsWriter&&) noexcept;
  FieldsWriter(const FieldsWriter&) = delete;
  FieldsWriter& operator=(const FieldsWriter&) = delete;

  /// Append one frame and flush it, so that a reader opening the file now sees it. `scalars[s]`
  /// points at grid().size() values of scalar_names()[s]; `vectors[v]` at the x, y and z
  /// components of vector_names()[v], grid().size() values each. Wrong counts or null pointers:
  /// std::invalid_argument (nothing written). No allocation after the first frame.
  void write_frame(long step, double time, const std::vector<const double*>& scalars,
                   const std::vector<std::array<const double*, 3>>& vectors);
  /// Flush HDF5 buffers to disk (write_frame already does).
  void flush();
  /// Close the file now (further writes throw std::logic_error). Idempotent.
  void close();

  std::size_t frames() const;
  const FieldGrid& grid() const;
  const std::vector<std::string>& scalar_names() const;
  const std::vector<std::string>& vector_names() const;
  const std::string& path() const;
  /// After resume(): the times of the frames kept (frames 0..kept_times().size()-1); else empty.
  const std::vector<double>& kept_times() const;

  struct Impl; ///< (opaque)

private:
  FieldsWriter(); // an empty writer for resume() to fill
  std::unique_ptr<Impl> impl_;
};

} // namespace fluidem
