// Particle trajectories in H5MD 1.1 (https://nongnu.org/h5md/h5md.html), HDF5 C API.
//
// Layout written (N particles, F frames so far):
//   /h5md                      +version = int32[2] {1,1}
//        /author               +name
//        /creator              +name = "fluidem", +version
//        /modules/units        +version = int32[2] {1,0}, +system = "SI"
//   /parameters                +dimension (2 or 3: the run's dimension; 2-D runs move in x-z)
//   /particles/all             +frames = int64 scalar (F, updated every frame)
//        /box                  +dimension = 3, +boundary = string[3] "none" | "periodic"
//             /edges           float64[3]  (hi - lo, m)
//             /offset          float64[3]  (lo, m)
//        /position             /step int64[F], /time float64[F], /value float64[F][N][3]
//        /velocity             same, m/s
//        /angular_velocity     same, rad/s
//        /radius               /step, /time, /value float64[F][N]
//        /species              /step, /time, /value int32[F][N]
//        /id                   /step, /time, /value int64[F][N]
//        /layer                /step, /time, /value int32[F][N]; only when the run keeps layers
//                              (output.layers > 0): the index of the horizontal band of the
//                              initial bed the particle started in (ParticleStore::layer).
//                              Written every frame like species and id, although it does not
//                              change, so that row i of every quantity of frame k is one particle
//                              (a time-independent dataset would break if the store is reordered)
//        /vertex_index         int64[N] = 0..N-1 (time-independent; the XDMF Polyvertex
//                              connectivity, see xdmf_writer.hpp)
// Vectors always have 3 components; in a 2-D run the y components are zero.
// Value datasets are chunked with an unlimited first dimension; one chunk is one frame (capped at
// about 1 MiB). Any HDF5 failure throws std::runtime_error naming the file and the operation.
//
// Resume (continuing a run from a checkpoint, H5mdWriter::resume): the existing file is reopened
// read-write, checked against the run (particle count, dimension, box), and every time-dependent
// dataset (the shared step and time, and each element's value) is shrunk (H5Dset_extent) to the
// leading frames whose time is <= t_keep; the frames after them (written after the checkpoint,
// or incomplete after a crash) are dropped, and write_frame appends from there. Everything else
// (author, creator version, vertex_index) is left as it was. The space of the dropped frames
// stays in the file (HDF5 does not shrink files; h5repack does), but is reused by the frames
// appended while the file remains open.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "particles/particle_store.hpp"

namespace fluidem {

/// The simulation box stored in particles/all/box.
struct H5mdBox {
  std::array<double, 3> lo{0.0, 0.0, 0.0};           ///< lower corner, m
  std::array<double, 3> hi{0.0, 0.0, 0.0};           ///< upper corner, m
  std::array<bool, 3> periodic{false, false, false}; ///< periodic along x, y, z
};

/// Path (inside the H5MD file) of the Polyvertex connectivity 0..N-1 used by the XDMF file.
inline constexpr const char* kH5mdVertexIndexPath = "/particles/all/vertex_index";

class H5mdWriter {
public:
  /// Create `path` and write the static part of the layout. `dimension` is 2 or 3.
  /// `author` defaults to $USER (or "unknown"). `layer`: also write ParticleStore::layer.
  /// `run_id` (when not empty) goes into /parameters as the attribute run_id, which resume()
  /// checks. A regular file at `path` is replaced; a link or anything else there is refused
  /// (std::runtime_error), never written through.
  H5mdWriter(const std::string& path, std::size_t n_particles, int dimension,
             const std::string& creator_version, const H5mdBox& box = {},
             const std::string& author = {}, bool layer = false, const std::string& run_id = {});
  /// Continue the existing H5MD file `path` (written by this class) after a restart from a
  /// checkpoint. The checkpoint's run had written the frames at `frame_times`: the file must
  /// hold them, complete and at bitwise those times, and belong to the run `run_id`; later
  /// frames (written after the checkpoint, or cut short by a crash) are dropped, in a copy of
  /// the file that is then renamed over it (the file is never left half-edited), and write_frame
  /// appends after them. With `check_only` the file is only checked (opened read-only) and an
  /// empty writer returned.
  /// Errors, all std::runtime_error naming `path`: the file does not exist, is a link or is not
  /// readable HDF5; it does not match the run (n_particles, dimension, box, whether it holds
  /// /layer as `layer` asks; the message says what differs) or lacks part of the layout; it
  /// belongs to another run; it stops short of the checkpoint's frames or holds others.
  static H5mdWriter resume(const std::string& path, const std::vector<double>& frame_times,
                           const std::string& run_id, std::size_t n_particles, int dimension,
                           const H5mdBox& box = {}, bool layer = false, bool check_only = false);

  ~H5mdWriter(); ///< closes the file; errors on this path are swallowed (call close() to see them)
  H5mdWriter(H5mdWriter&&) noexcept;
  H5mdWriter& operator=(H5mdWriter&&) noexcept;
  H5mdWriter(const H5mdWriter&) = delete;
  H5mdWriter& operator=(const H5mdWriter&) = delete;

  /// Append one frame. `particles.size()` must equal n_particles() (std::invalid_argument).
  /// No allocation by the writer after the first frame.
  /// `order`: write particle order[k] as the k-th row (nullptr: the store's order).
  void write_frame(long step, double time, const ParticleStore& particles,
                   const std::vector<std::uint32_t>* order = nullptr);
  /// Flush HDF5 buffers to disk, so that a reader opening the file now sees every frame.
  void flush();
  /// Close the file now (further writes throw std::logic_error). Idempotent.
  void close();

  std::size_t frames() const;
  std::size_t n_particles() const;
  const std::string& path() const;
  /// After resume(): the times of the frames kept (frames 0..kept_times().size()-1); else empty.
  const std::vector<double>& kept_times() const;

  struct Impl; ///< (opaque)

private:
  H5mdWriter(); // an empty writer for resume() to fill
  std::unique_ptr<Impl> impl_;
};

} // namespace fluidem
