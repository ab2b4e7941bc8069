// XDMF 3 index over the H5MD particle file, so that ParaView can open it: a temporal collection of
// Polyvertex grids, one per frame, whose Geometry and Attributes select frame k of the H5MD
// datasets written by H5mdWriter (see h5md_writer.hpp):
//   Geometry XYZ                        <- /particles/all/position/value[k]
//   velocity, angular_velocity (Vector) <- .../velocity/value[k], .../angular_velocity/value[k]
//   radius, species, id (Scalar)        <- .../radius/value[k], .../species/value[k],
//   .../id/value[k] Topology                            <- /particles/all/vertex_index (0..N-1)
//
// How frame k is selected depends on the reader, and no one file suits both of ParaView's:
//  - kXdmf3 (default): HDF DataItems carrying the Xdmf3 library's selection suffix,
//    "particles.h5:/particles/all/position/value|k 0 0:1 1 1:1 N 3:F N 3"
//    (start:stride:count:dataset dims). Read by ParaView's Xdmf3 readers (Xdmf3ReaderS/T,
//    "XDMF3 Reader"); checked with ParaView 5.11.
//  - kHyperSlab: the XDMF standard's HyperSlab DataItems. Read by ParaView's legacy "XDMF Reader"
//    (and VisIt). ParaView's Xdmf3 readers silently give 0 points for these (VTK reads a HyperSlab
//    reference's type before reading it), hence the default above.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace fluidem {

enum class XdmfFlavour {
  kXdmf3,    ///< Xdmf3 selection suffix: ParaView's Xdmf3 readers
  kHyperSlab ///< standard HyperSlab items: ParaView's legacy XDMF Reader, VisIt
};

/// Write (atomically: a temporary file then a rename) the XDMF file `xmf_path` describing the
/// frames 0..frame_times.size()-1 of the H5MD file `h5_filename_relative` (a path relative to the
/// directory of `xmf_path`, normally just "particles.h5"; it must not contain ':' or '|':
/// std::invalid_argument). Call after every H5mdWriter::write_frame so that the file on disk is
/// always valid. Throws std::runtime_error naming the file on I/O error.
void write_particles_xdmf(const std::string& xmf_path, const std::string& h5_filename_relative,
                          std::size_t n_particles, const std::vector<double>& frame_times,
                          XdmfFlavour flavour = XdmfFlavour::kXdmf3);

/// The XDMF text itself (what write_particles_xdmf writes).
std::string particles_xdmf(const std::string& h5_filename_relative, std::size_t n_particles,
                           const std::vector<double>& frame_times,
                           XdmfFlavour flavour = XdmfFlavour::kXdmf3);

} // namespace fluidem
