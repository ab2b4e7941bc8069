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
//        /vertex_index         int64[N] = 0..N-1 (time-independent; the XDMF Polyvertex
//                              connectivity, see xdmf_writer.hpp)
// Vectors always have 3 components; in a 2-D run the y components are zero.
// Value datasets are chunked with an unlimited first dimension; one chunk is one frame (capped at
// about 1 MiB). Any HDF5 failure throws std::runtime_error naming the file and the operation.
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <string>

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
  /// Create (truncate) `path` and write the static part of the layout. `dimension` is 2 or 3.
  /// `author` defaults to $USER (or "unknown").
  H5mdWriter(const std::string& path, std::size_t n_particles, int dimension,
             const std::string& creator_version, const H5mdBox& box = {},
             const std::string& author = {});
  ~H5mdWriter(); ///< closes the file; errors on this path are swallowed (call close() to see them)
  H5mdWriter(H5mdWriter&&) noexcept;
  H5mdWriter& operator=(H5mdWriter&&) noexcept;
  H5mdWriter(const H5mdWriter&) = delete;
  H5mdWriter& operator=(const H5mdWriter&) = delete;

  /// Append one frame. `particles.size()` must equal n_particles() (std::invalid_argument).
  /// No allocation by the writer after the first frame.
  void write_frame(long step, double time, const ParticleStore& particles);
  /// Flush HDF5 buffers to disk, so that a reader opening the file now sees every frame.
  void flush();
  /// Close the file now (further writes throw std::logic_error). Idempotent.
  void close();

  std::size_t frames() const;
  std::size_t n_particles() const;
  const std::string& path() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace fluidem
