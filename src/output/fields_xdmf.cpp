#include "output/fields_xdmf.hpp"

#include <stdexcept>

#include "output/xdmf_text.hpp"

namespace fluidem {

namespace {

using xdmf_text::shortest;
using xdmf_text::xml_escape;

// A DataItem selecting frame k of /fields/<name>, a [F][nz][ny][nx] (scalar) or
// [F][nz][ny][nx][3] (vector) dataset. `cells` is "nz ny nx".
void frame_item(std::string& out, const std::string& h5, const std::string& name, bool vector,
                std::size_t k, const std::string& cells, const std::string& frames,
                XdmfFlavour flavour) {
  const std::string ks = std::to_string(k);
  const char* const indent = "          ";
  const std::string type = "NumberType=\"Float\" Precision=\"8\" Format=\"HDF\"";
  const std::string ref = h5 + ":/fields/" + xml_escape(name);
  // start, stride, count and the dataset's dims, per dimension
  const std::string start = ks + (vector ? " 0 0 0 0" : " 0 0 0");
  const std::string stride = vector ? "1 1 1 1 1" : "1 1 1 1";
  const std::string value_dims = vector ? cells + " 3" : cells;
  const std::string count = "1 " + value_dims;
  const std::string dims = frames + " " + value_dims;
  if (flavour == XdmfFlavour::kXdmf3) {
    // Xdmf3's HDF controller syntax: file:dataset|start:stride:count:dataspace
    out += indent;
    out += "<DataItem Dimensions=\"" + value_dims + "\" " + type + ">" + ref + "|" + start + ":" +
           stride + ":" + count + ":" + dims + "</DataItem>\n";
    return;
  }
  out += indent;
  // The item's shape without the frame axis: ParaView's legacy reader wants the rank of a cell
  // attribute to be the topology's (plus one for vector components).
  out += "<DataItem ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"" + value_dims + "\">\n";
  out += indent;
  out += std::string("  <DataItem Dimensions=\"3 ") + (vector ? "5" : "4") + "\" Format=\"XML\">" +
         start + " " + stride + " " + count + "</DataItem>\n";
  out += indent;
  out += "  <DataItem Dimensions=\"" + dims + "\" " + type + ">" + ref + "</DataItem>\n";
  out += indent;
  out += "</DataItem>\n";
}

} // namespace

std::string fields_xdmf(const std::string& h5_filename_relative, const FieldGrid& grid,
                        const std::vector<std::string>& scalars,
                        const std::vector<std::string>& vectors,
                        const std::vector<double>& frame_times, XdmfFlavour flavour) {
  check_field_grid(grid, "XDMF fields");
  check_field_names(scalars, vectors, "XDMF fields");
  if (h5_filename_relative.find_first_of(":|") != std::string::npos)
    throw std::invalid_argument("XDMF fields: the HDF5 file name '" + h5_filename_relative +
                                "' must not contain ':' or '|'");
  const std::string h5 = xml_escape(h5_filename_relative);
  const auto& c = grid.cells;
  const std::string cells =
      std::to_string(c[2]) + " " + std::to_string(c[1]) + " " + std::to_string(c[0]);
  const std::string nodes =
      std::to_string(c[2] + 1) + " " + std::to_string(c[1] + 1) + " " + std::to_string(c[0] + 1);
  const std::string origin =
      shortest(grid.lo[2]) + " " + shortest(grid.lo[1]) + " " + shortest(grid.lo[0]);
  const std::string spacing =
      shortest(grid.spacing[2]) + " " + shortest(grid.spacing[1]) + " " + shortest(grid.spacing[0]);
  const std::string frames = std::to_string(frame_times.size());

  std::string out;
  out.reserve(512 + frame_times.size() *
                        (600 + (scalars.size() + vectors.size()) * (400 + h5.size() * 2)));
  out += "<?xml version=\"1.0\" ?>\n";
  out += "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  out += "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n";
  out += "  <Domain>\n";
  out += "    <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < frame_times.size(); ++k) {
    out += "      <Grid Name=\"frame_" + std::to_string(k) + "\" GridType=\"Uniform\">\n";
    out += "        <Time Value=\"" + shortest(frame_times[k]) + "\"/>\n";
    out += "        <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" + nodes + "\"/>\n";
    out += "        <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n";
    out += "          <DataItem Name=\"Origin\" Dimensions=\"3\" NumberType=\"Float\" "
           "Precision=\"8\" Format=\"XML\">" +
           origin + "</DataItem>\n";
    out += "          <DataItem Name=\"Spacing\" Dimensions=\"3\" NumberType=\"Float\" "
           "Precision=\"8\" Format=\"XML\">" +
           spacing + "</DataItem>\n";
    out += "        </Geometry>\n";
    for (const auto* names : {&scalars, &vectors}) {
      const bool vector = names == &vectors;
      for (const std::string& name : *names) {
        out += "        <Attribute Name=\"" + xml_escape(name) + "\" AttributeType=\"" +
               (vector ? "Vector" : "Scalar") + "\" Center=\"Cell\">\n";
        frame_item(out, h5, name, vector, k, cells, frames, flavour);
        out += "        </Attribute>\n";
      }
    }
    out += "      </Grid>\n";
  }
  out += "    </Grid>\n";
  out += "  </Domain>\n";
  out += "</Xdmf>\n";
  return out;
}

void write_fields_xdmf(const std::string& xmf_path, const std::string& h5_filename_relative,
                       const FieldGrid& grid, const std::vector<std::string>& scalars,
                       const std::vector<std::string>& vectors,
                       const std::vector<double>& frame_times, XdmfFlavour flavour) {
  const std::string text =
      fields_xdmf(h5_filename_relative, grid, scalars, vectors, frame_times, flavour);
  xdmf_text::write_file_atomically(xmf_path, text);
}

} // namespace fluidem
