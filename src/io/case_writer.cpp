#include "io/case_writer.hpp"

#include <charconv>
#include <cstdio>
#include <sstream>

namespace fluidem {
namespace {

/// A TOML basic string, with quotes, backslashes and control characters escaped.
std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\b':
      out += "\\b";
      break;
    case '\t':
      out += "\\t";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\f':
      out += "\\f";
      break;
    case '\r':
      out += "\\r";
      break;
    default:
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
        out += buf;
      } else {
        out += c;
      }
    }
  }
  return out + "\"";
}

std::string vec3(const std::array<double, 3>& v) {
  // Appending (not "[" + string) sidesteps a GCC 12 -Wrestrict false positive.
  std::string s = "[";
  for (std::size_t i = 0; i < 3; ++i) {
    if (i > 0) s += ", ";
    s += format_double(v[i]);
  }
  s += "]";
  return s;
}

std::string bool3(const std::array<bool, 3>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < 3; ++i) s += std::string(i ? ", " : "") + (v[i] ? "true" : "false");
  return s + "]";
}

std::string auto_or(const std::optional<double>& v) {
  return v ? format_double(*v) : std::string("\"auto\"");
}

bool same(const MaterialSpec& a, const MaterialSpec& b) {
  return a.youngs_modulus == b.youngs_modulus && a.poisson_ratio == b.poisson_ratio &&
         a.restitution == b.restitution && a.friction == b.friction &&
         a.tangential_restitution == b.tangential_restitution &&
         a.rolling_friction == b.rolling_friction;
}

void write_material(std::ostream& os, const MaterialSpec& m) {
  os << "youngs_modulus = " << format_double(m.youngs_modulus) << "  # Pa\n"
     << "poisson_ratio = " << format_double(m.poisson_ratio) << "\n"
     << "restitution = " << format_double(m.restitution) << "\n"
     << "friction = " << format_double(m.friction) << "\n"
     << "tangential_restitution = " << format_double(m.tangential_restitution) << "\n"
     << "rolling_friction = " << format_double(m.rolling_friction) << "\n";
}

} // namespace

std::string format_double(double x) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  std::string s(buf, res.ptr);
  // "1" would read back as a TOML integer; make every number a TOML float.
  if (s.find_first_of(".eEni") == std::string::npos) s += ".0";
  return s;
}

std::string write_case_toml(const CaseSpec& spec) {
  std::ostringstream os;
  os << "# fluidem case, resolved: every key with its value or its default (docs/case-file.md).\n";

  const SimulationSpec& s = spec.simulation;
  os << "\n[simulation]\n"
     << "engine = " << toml_string(to_string(s.engine)) << "\n"
     << "dimension = " << s.dimension << "\n"
     << "end_time = " << format_double(s.end_time) << "  # s\n"
     << "time_step = " << auto_or(s.time_step) << "  # s\n"
     << "time_step_fraction = " << format_double(s.time_step_fraction) << "\n"
     << "force_time_step = " << (s.force_time_step ? "true" : "false") << "\n"
     << "gravity = " << vec3(s.gravity) << "  # m/s^2\n"
     << "insertion_overlap_tolerance = " << format_double(s.insertion_overlap_tolerance) << "\n";

  os << "\n[output]\n"
     << "frame_interval = " << format_double(spec.output.frame_interval) << "  # s\n"
     << "series_interval = " << format_double(spec.output.series_interval) << "  # s\n";

  const DomainSpec& d = spec.domain;
  os << "\n[domain]\n"
     << "lo = " << vec3(d.lo) << "  # m\n"
     << "hi = " << vec3(d.hi) << "  # m\n"
     << "periodic = " << bool3(d.periodic) << "\n";

  // [walls] holds the material most faces share; the other faces get their own full table.
  std::size_t base = 0;
  std::size_t base_count = 0;
  for (std::size_t f = 0; f < d.wall_material.size(); ++f) {
    std::size_t n = 0;
    for (const auto& m : d.wall_material) n += same(m, d.wall_material[f]) ? 1 : 0;
    if (n > base_count) {
      base = f;
      base_count = n;
    }
  }
  os << "\n[walls]\n";
  write_material(os, d.wall_material[base]);
  for (std::size_t f = 0; f < d.wall_material.size(); ++f) {
    if (same(d.wall_material[f], d.wall_material[base])) continue;
    os << "\n[walls." << kFaceNames[f] << "]\n";
    write_material(os, d.wall_material[f]);
  }

  for (const auto& sp : spec.species) {
    os << "\n[[species]]\n"
       << "name = " << toml_string(sp.name) << "\n"
       << "diameter = " << format_double(sp.diameter) << "  # m\n"
       << "density = " << format_double(sp.density) << "  # kg/m^3\n";
    write_material(os, sp.material);
  }

  for (const auto& in : spec.inserts) {
    os << "\n[[insert]]\n"
       << "species = " << toml_string(in.species) << "\n"
       << "placement = " << toml_string(to_string(in.placement)) << "\n";
    if (in.placement == Placement::File)
      os << "file = " << toml_string(in.file) << "\n";
    else
      os << "count = " << in.count << "\n";
    os << "region = { lo = " << vec3(in.region_lo) << ", hi = " << vec3(in.region_hi) << " }  # m\n"
       << "velocity = " << vec3(in.velocity) << "  # m/s\n"
       << "velocity_spread = " << format_double(in.velocity_spread) << "  # m/s\n"
       << "seed = " << in.seed << "\n";
  }

  const ContactSpec& c = spec.contact;
  os << "\n[contact]\n"
     << "normal = " << toml_string(to_string(c.normal)) << "\n";
  if (c.normal == NormalModel::Linear)
    os << "stiffness = " << format_double(c.stiffness) << "  # N/m\n";
  os << "tangential = " << toml_string(to_string(c.tangential)) << "\n"
     << "stiffness_ratio = " << auto_or(c.stiffness_ratio) << "\n"
     << "rolling = " << toml_string(to_string(c.rolling)) << "\n"
     << "characteristic_velocity = " << auto_or(c.characteristic_velocity) << "  # m/s\n"
     << "max_overlap = " << format_double(c.max_overlap) << "\n";

  os << "\n[neighbour]\n"
     << "skin = " << auto_or(spec.neighbour.skin) << "  # m\n";

  const HardSphereSpec& h = spec.hardsphere;
  os << "\n[hardsphere]\n"
     << "tc_time = " << format_double(h.tc_time) << "  # s\n"
     << "elastic_below = " << auto_or(h.elastic_below) << "  # m/s\n"
     << "max_events_per_particle = " << format_double(h.max_events_per_particle) << "\n";
  return os.str();
}

} // namespace fluidem
