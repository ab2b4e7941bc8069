// XDMF 3 index over the H5MD particle file, so that ParaView (Xdmf3 reader) can open it:
// a temporal collection of Polyvertex grids, one per frame, whose Geometry and Attributes are
// HyperSlabs of the H5MD datasets written by H5mdWriter (see h5md_writer.hpp):
//   Geometry XYZ              <- /particles/all/position/value[k]
//   velocity, angular_velocity (Vector) <- .../velocity/value[k], .../angular_velocity/value[k]
//   radius, species, id (Scalar)        <- .../radius/value[k], .../species/value[k],
//   .../id/value[k] Topology                  <- /particles/all/vertex_index (0..N-1)
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace fluidem {

/// Write (atomically: a temporary file then a rename) the XDMF file `xmf_path` describing the
/// frames 0..frame_times.size()-1 of the H5MD file `h5_filename_relative` (a path relative to the
/// directory of `xmf_path`, normally just "particles.h5"). Call after every H5mdWriter::write_frame
/// so that the file on disk is always valid. Throws std::runtime_error naming the file on I/O
/// error.
void write_particles_xdmf(const std::string& xmf_path, const std::string& h5_filename_relative,
                          std::size_t n_particles, const std::vector<double>& frame_times);

/// The XDMF text itself (what write_particles_xdmf writes).
std::string particles_xdmf(const std::string& h5_filename_relative, std::size_t n_particles,
                           const std::vector<double>& frame_times);

} // namespace fluidem
