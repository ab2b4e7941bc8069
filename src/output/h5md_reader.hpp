// Reading the particle frames of an H5MD file written by H5mdWriter (particles.h5; layout in
// h5md_writer.hpp): the frame count, the frame times and steps, the box and dimension, and for
// frame k the positions, velocities, angular velocities, radii, species, ids and, when the run
// kept them (output.layers > 0), the initial layers.
// The file is opened read-only without file locking (a live run may hold it open for writing;
// it flushes after every frame). Every failure throws std::runtime_error naming the file: it
// does not exist, is not HDF5, lacks part of the layout, has datasets of inconsistent shapes,
// or the frame asked for is out of range.
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "output/h5md_writer.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

class H5mdReader {
public:
  /// Open `path` and read its static part (dimension, box, particle count, times, steps).
  explicit H5mdReader(const std::string& path);
  ~H5mdReader();
  H5mdReader(H5mdReader&&) noexcept;
  H5mdReader& operator=(H5mdReader&&) noexcept;
  H5mdReader(const H5mdReader&) = delete;
  H5mdReader& operator=(const H5mdReader&) = delete;

  /// Frames complete in every time-dependent dataset (a live run may have extended some).
  std::size_t frames() const;
  std::size_t n_particles() const;
  int dimension() const; ///< 2 or 3 (/parameters dimension)
  const H5mdBox& box() const;
  const std::vector<double>& times() const; ///< s, one per frame
  const std::vector<long>& steps() const;
  const std::string& path() const;
  /// True when the file holds /particles/all/layer (the run had output.layers > 0).
  bool has_layer() const;

  /// Frame k into `out` (resized to n_particles()): x, y, z, vx, vy, vz, wx, wy, wz, radius,
  /// species, id, layer (all 0 when has_layer() is false) exactly as stored. Mass, inverse mass and
  /// inverse inertia are those of a solid sphere of density 1 kg/m^3 (the file holds no densities;
  /// analyses that weight by mass within one species are unaffected); forces and torques are zero.
  void read_frame(std::size_t k, ParticleStore& out) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace fluidem
