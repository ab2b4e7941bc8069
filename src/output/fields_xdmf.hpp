// XDMF 3 index over the fields file written by FieldsWriter (fields_writer.hpp), so that ParaView
// can open it: a temporal collection of Uniform grids, one per frame, each
//   Topology  3DCoRectMesh, Dimensions "nz+1 ny+1 nx+1" (node counts, slowest axis first)
//   Geometry  ORIGIN_DXDYDZ: origin "lo_z lo_y lo_x", spacing "dz dy dx" (XDMF's z y x order)
//   Attribute per field, Center="Cell": Scalar <- /fields/<name>[k] (nz ny nx),
//                                       Vector <- /fields/<name>[k] (nz ny nx 3)
// Frame k is selected as in xdmf_writer.hpp: by default (XdmfFlavour::kXdmf3) with the Xdmf3
// selection suffix "fields.h5:/fields/p|k 0 0 0:1 1 1 1:1 nz ny nx:F nz ny nx", which ParaView's
// Xdmf3 readers understand; XdmfFlavour::kHyperSlab gives standard HyperSlab items (whose
// Dimensions leave out the frame axis, as ParaView's legacy XDMF Reader requires for cell data).
// Both checked with ParaView 5.11 (Xdmf3ReaderS and XDMFReader): every cell value sits at its
// cell centre (tests/unit/output/fields_writer_test.cpp).
#pragma once
#include <string>
#include <vector>

#include "output/fields_writer.hpp"
#include "output/xdmf_writer.hpp"

namespace fluidem {

/// Write (atomically: a temporary file then a rename) the XDMF file `xmf_path` describing the
/// frames 0..frame_times.size()-1 of the fields file `h5_filename_relative` (a path relative to
/// the directory of `xmf_path`, normally just "fields.h5"; it must not contain ':' or '|').
/// `scalars` and `vectors` are the names given to FieldsWriter. Bad grid, names or file name:
/// std::invalid_argument; I/O error: std::runtime_error naming the file. Call after every
/// FieldsWriter::write_frame so that the file on disk is always valid.
void write_fields_xdmf(const std::string& xmf_path, const std::string& h5_filename_relative,
                       const FieldGrid& grid, const std::vector<std::string>& scalars,
                       const std::vector<std::string>& vectors,
                       const std::vector<double>& frame_times,
                       XdmfFlavour flavour = XdmfFlavour::kXdmf3);

/// The XDMF text itself (what write_fields_xdmf writes).
std::string fields_xdmf(const std::string& h5_filename_relative, const FieldGrid& grid,
                        const std::vector<std::string>& scalars,
                        const std::vector<std::string>& vectors,
                        const std::vector<double>& frame_times,
                        XdmfFlavour flavour = XdmfFlavour::kXdmf3);

} // namespace fluidem
