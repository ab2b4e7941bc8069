#include "output/xdmf_writer.hpp"

#include <stdexcept>

#include "output/h5md_writer.hpp"
#include "output/xdmf_text.hpp"

namespace fluidem {

namespace {

using xdmf_text::shortest;
using xdmf_text::xml_escape;

struct Field {
  const char* name;      // XDMF attribute name ("" for the geometry)
  const char* dataset;   // H5MD path of the value dataset
  const char* type;      // NumberType
  const char* precision; // bytes
  bool vector;
};

constexpr Field kGeometry{"", "/particles/all/position/value", "Float", "8", true};
constexpr Field kAttributes[] = {
    {"velocity", "/particles/all/velocity/value", "Float", "8", true},
    {"angular_velocity", "/particles/all/angular_velocity/value", "Float", "8", true},
    {"radius", "/particles/all/radius/value", "Float", "8", false},
    {"species", "/particles/all/species/value", "Int", "4", false},
    {"id", "/particles/all/id/value", "Int", "8", false},
};

// A DataItem selecting frame k of the [F][N] or [F][N][3] dataset of field f.
void frame_item(std::string& out, const Field& f, const std::string& h5, std::size_t k,
                const std::string& n, const std::string& frames, XdmfFlavour flavour,
                const char* indent) {
  const std::string ks = std::to_string(k);
  const std::string type =
      std::string("NumberType=\"") + f.type + "\" Precision=\"" + f.precision + "\" Format=\"HDF\"";
  // start, stride, count and the dataset's dims, per dimension
  const std::string start = f.vector ? ks + " 0 0" : ks + " 0";
  const std::string stride = f.vector ? "1 1 1" : "1 1";
  const std::string count = f.vector ? "1 " + n + " 3" : "1 " + n;
  const std::string dims = f.vector ? frames + " " + n + " 3" : frames + " " + n;
  if (flavour == XdmfFlavour::kXdmf3) {
    // Xdmf3's HDF controller syntax: file:dataset|start:stride:count:dataspace
    out += indent;
    out += "<DataItem Dimensions=\"" + std::string(f.vector ? n + " 3" : n) + "\" " + type + ">" +
           h5 + ":" + f.dataset + "|" + start + ":" + stride + ":" + count + ":" + dims +
           "</DataItem>\n";
    return;
  }
  out += indent;
  out += "<DataItem ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"" + count + "\">\n";
  out += indent;
  out += std::string("  <DataItem Dimensions=\"3 ") + (f.vector ? "3" : "2") +
         "\" Format=\"XML\">" + start + " " + stride + " " + count + "</DataItem>\n";
  out += indent;
  out += "  <DataItem Dimensions=\"" + dims + "\" " + type + ">" + h5 + ":" + f.dataset +
         "</DataItem>\n";
  out += indent;
  out += "</DataItem>\n";
}

} // namespace

std::string particles_xdmf(const std::string& h5_filename_relative, std::size_t n_particles,
                           const std::vector<double>& frame_times, XdmfFlavour flavour) {
  if (h5_filename_relative.find_first_of(":|") != std::string::npos)
    throw std::invalid_argument("XDMF: the HDF5 file name '" + h5_filename_relative +
                                "' must not contain ':' or '|'");
  const std::string h5 = xml_escape(h5_filename_relative);
  const std::string n = std::to_string(n_particles);
  const std::string frames = std::to_string(frame_times.size());
  std::string out;
  out.reserve(512 + frame_times.size() * (2200 + h5.size() * 7));
  out += "<?xml version=\"1.0\" ?>\n";
  out += "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  out += "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n";
  out += "  <Domain>\n";
  out += "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < frame_times.size(); ++k) {
    out += "      <Grid Name=\"frame_" + std::to_string(k) + "\" GridType=\"Uniform\">\n";
    out += "        <Time Value=\"" + shortest(frame_times[k]) + "\"/>\n";
    out += "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + n +
           "\" NodesPerElement=\"1\">\n";
    out += "          <DataItem Dimensions=\"" + n +
           "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" + h5 + ":" +
           kH5mdVertexIndexPath + "</DataItem>\n";
    out += "        </Topology>\n";
    out += "        <Geometry GeometryType=\"XYZ\">\n";
    frame_item(out, kGeometry, h5, k, n, frames, flavour, "          ");
    out += "        </Geometry>\n";
    for (const Field& f : kAttributes) {
      out += std::string("        <Attribute Name=\"") + f.name + "\" AttributeType=\"" +
             (f.vector ? "Vector" : "Scalar") + "\" Center=\"Node\">\n";
      frame_item(out, f, h5, k, n, frames, flavour, "          ");
      out += "        </Attribute>\n";
    }
    out += "      </Grid>\n";
  }
  out += "    </Grid>\n";
  out += "  </Domain>\n";
  out += "</Xdmf>\n";
  return out;
}

void write_particles_xdmf(const std::string& xmf_path, const std::string& h5_filename_relative,
                          std::size_t n_particles, const std::vector<double>& frame_times,
                          XdmfFlavour flavour) {
  const std::string text = particles_xdmf(h5_filename_relative, n_particles, frame_times, flavour);
  xdmf_text::write_file_atomically(xmf_path, text);
}

} // namespace fluidem
