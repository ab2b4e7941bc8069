#include "io/case_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "contact/contact_models.hpp"

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

std::string numbers(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) s += ", ";
    s += format_double(v[i]);
  }
  s += "]";
  return s;
}

/// An [[insert]] size_distribution as an inline table, the truncation resolved.
std::string size_distribution(const SizeDistributionSpec& d) {
  using Kind = SizeDistributionSpec::Kind;
  const char* kind = d.kind == Kind::Normal      ? "normal"
                     : d.kind == Kind::LogNormal ? "log_normal"
                     : d.kind == Kind::Table     ? "table"
                                                 : "discrete";
  std::string s = std::string("{ kind = \"") + kind + "\", basis = \"" +
                  (d.basis == SizeDistributionSpec::Basis::Mass ? "mass" : "number") + "\"";
  if (d.kind == Kind::Normal)
    s += ", mean = " + format_double(d.mean) + ", std = " + format_double(d.std);
  if (d.kind == Kind::LogNormal)
    s += ", median = " + format_double(d.median) +
         ", geometric_std = " + format_double(d.geometric_std);
  if (d.kind == Kind::Normal || d.kind == Kind::LogNormal)
    s += ", min = " + format_double(d.min) + ", max = " + format_double(d.max);
  if (d.kind == Kind::Table || d.kind == Kind::Discrete)
    s += ", diameters = " + numbers(d.diameters) +
         (d.kind == Kind::Table ? ", cumulative = " + numbers(d.cumulative)
                                : ", fractions = " + numbers(d.fractions));
  return s + " }";
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
         a.shear_modulus == b.shear_modulus && a.restitution == b.restitution &&
         a.friction == b.friction && a.tangential_restitution == b.tangential_restitution &&
         a.rolling_friction == b.rolling_friction;
}

void write_material(std::ostream& os, const MaterialSpec& m) {
  // A rigid wall as the reader takes it; the shear modulus when it was given (poisson_ratio
  // follows from it), else the Poisson ratio; friction = inf reads back as TOML's inf.
  if (std::isinf(m.youngs_modulus))
    os << "youngs_modulus = \"rigid\"\n";
  else
    os << "youngs_modulus = " << format_double(m.youngs_modulus) << "  # Pa\n";
  if (m.shear_modulus)
    os << "shear_modulus = " << format_double(*m.shear_modulus) << "  # Pa\n";
  else
    os << "poisson_ratio = " << format_double(m.poisson_ratio) << "\n";
  os << "restitution = " << format_double(m.restitution) << "\n"
     << "friction = " << format_double(m.friction) << "\n"
     << "tangential_restitution = " << format_double(m.tangential_restitution) << "\n"
     << "rolling_friction = " << format_double(m.rolling_friction) << "\n";
}

std::string vec2(const std::array<double, 2>& v) {
  std::string s = "[";
  s += format_double(v[0]);
  s += ", ";
  s += format_double(v[1]);
  s += "]";
  return s;
}

std::string vec3(const Vec3& v) {
  return vec3(std::array<double, 3>{v.x, v.y, v.z});
}

/// The type and the keys that apply to it (and to the inflow mode): the reader rejects the rest,
/// which therefore hold their defaults.
void write_boundary_keys(std::ostream& os, gas::BoundaryType type, const gas::InflowProfile& in,
                         double porosity, double pressure) {
  const unsigned keys = gas::boundary_kind(type).keys;
  if ((keys & gas::inflow_keys) != 0) {
    os << "mode = " << toml_string(gas::to_string(in.mode)) << "\n";
    if (in.mode != gas::InflowMode::table)
      os << "velocity = " << format_double(in.velocity) << "  # m/s, superficial\n";
    if (in.mode == gas::InflowMode::pulse)
      os << "background = " << format_double(in.background) << "  # m/s\n"
         << "start = " << format_double(in.start) << "  # s\n"
         << "duration = " << format_double(in.duration) << "  # s\n";
    if (in.mode == gas::InflowMode::table) {
      auto list = [&](const std::vector<double>& v) {
        std::string out = "[";
        for (std::size_t k = 0; k < v.size(); ++k) out += (k ? ", " : "") + format_double(v[k]);
        return out + "]";
      };
      os << "times = " << list(in.times) << "  # s\n"
         << "velocities = " << list(in.velocities) << "  # m/s, superficial\n";
    }
    if (in.mode == gas::InflowMode::pulsation)
      os << "amplitude = " << format_double(in.amplitude) << "  # m/s\n"
         << "frequency = " << format_double(in.frequency) << "  # Hz\n";
  }
  if ((keys & gas::porosity_key) != 0) os << "porosity = " << format_double(porosity) << "\n";
  if ((keys & gas::pressure_key) != 0) os << "pressure = " << format_double(pressure) << "  # Pa\n";
}

/// [gas], [gas.solver], [gas.boundary.*] with their regions. The dimension, box, depth, gravity
/// and periodic faces are not keys: they follow from [simulation] and [domain].
void write_gas(std::ostream& os, const gas::GasSettings& g, Engine engine) {
  os << "\n[gas]  # dimension, box, depth and gravity: from [simulation] and [domain]\n"
     << "cells = [" << g.cells[0] << ", " << g.cells[1] << ", " << g.cells[2] << "]\n";
  // Hard spheres: the flow time step is simulation.time_step.
  if (engine == Engine::SoftSphere)
    os << "time_step = "
       << (g.time_step > 0.0 ? format_double(g.time_step) : std::string("\"auto\"")) << "  # s\n";
  os << "viscosity = " << format_double(g.viscosity) << "  # Pa s\n"
     << "model = " << toml_string(g.model == gas::PressureModel::A ? "A" : "B") << "\n";
  if (g.eos == gas::EquationOfState::ideal_gas)
    os << "eos = \"ideal_gas\"\n"
       << "molar_mass = " << format_double(g.molar_mass) << "  # kg/mol\n"
       << "temperature = " << format_double(g.temperature) << "  # K\n";
  else
    os << "eos = \"incompressible\"\n"
       << "density = " << format_double(g.density) << "  # kg/m^3\n";
  os << "initial_pressure = " << format_double(g.initial_pressure) << "  # Pa\n"
     << "initial_velocity = " << vec3(g.initial_velocity) << "  # m/s\n";

  os << "\n[gas.solver]\n"
     << "tolerance = " << format_double(g.tolerance) << "\n"
     << "velocity_tolerance = " << format_double(g.velocity_tolerance) << "  # m/s\n"
     << "max_iterations = " << g.max_iterations << "\n"
     << "velocity_relaxation = " << format_double(g.velocity_relaxation) << "\n"
     << "pressure_relaxation = " << format_double(g.pressure_relaxation) << "\n"
     << "linear_tolerance = " << format_double(g.linear_tolerance) << "\n"
     << "linear_max_iterations = " << g.linear_max_iterations << "\n"
     << "max_courant = " << format_double(g.max_courant) << "\n";

  for (std::size_t f = 0; f < gas::side_names.size(); ++f) {
    // The 2-D gas is one cell thick: front and back are free-slip walls, not keys.
    if (g.dimension == 2 && (f == gas::front || f == gas::back)) continue;
    const gas::GasBoundary& b = g.boundary[f];
    const std::string name = std::string("gas.boundary.") + gas::side_names[f];
    os << "\n[" << name << "]\n"
       << "type = " << toml_string(gas::to_string(b.type))
       << (gas::boundary_kind(b.type).chosen_in_case ? "" : "  # from domain.periodic") << "\n";
    write_boundary_keys(os, b.type, b.inflow, b.porosity, b.pressure);
    for (const gas::BoundaryRegion& r : b.regions) {
      os << "\n[[" << name << ".region]]\n"
         << "type = " << toml_string(gas::to_string(r.type)) << "\n"
         << "lo = " << vec2(r.lo) << "  # m\n"
         << "hi = " << vec2(r.hi) << "  # m\n";
      write_boundary_keys(os, r.type, r.inflow, r.porosity, r.pressure);
    }
  }
}

void write_coupling(std::ostream& os, const coupling::CouplingSettings& c) {
  os << "\n[coupling]\n";
  // Empty: not given, the registry's default closure (a run's set-up writes its name in).
  if (!c.drag.empty()) os << "drag = " << toml_string(c.drag) << "\n";
  os << "porosity = " << toml_string(std::string(coupling::to_string(c.porosity.method))) << "\n";
  if (c.porosity.method == coupling::PorosityMethod::porous_cube)
    os << "cube_factor = " << format_double(c.porosity.cube_factor) << "\n";
  os << "scheme = " << static_cast<int>(c.scheme) + 1 << "\n"
     << "d_mean = " << format_double(c.d_mean) << "  # m\n"
     << "hold_gas_at_rest = " << (c.hold_gas_at_rest ? "true" : "false") << "\n"
     << "mode = " << toml_string(std::string(coupling::to_string(c.mode))) << "\n";
  if (c.particle_force)
    os << "particle_force = " << toml_string(std::string(coupling::to_string(*c.particle_force)))
       << "\n";
  if (c.mode == coupling::CouplingMode::frozen) {
    const auto& u = c.frozen_velocity;
    os << "frozen_velocity = [" << format_double(u[0]) << ", " << format_double(u[1]) << ", "
       << format_double(u[2]) << "]  # m/s\n"
       << "frozen_velocity_gradient = [";
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j)
        os << format_double(c.frozen_gradient[i][j]) << (i == 2 && j == 2 ? "" : ", ");
    os << "]  # 1/s, du_i/dx_j row-major\n";
  }
  if (c.smoothing_length > 0.0)
    os << "smoothing_length = " << format_double(c.smoothing_length) << "  # m\n";
  const coupling::FluidForceSettings& f = c.forces;
  if (f.any()) {
    os << "\n[coupling.forces]\n"
       << "virtual_mass = " << (f.virtual_mass ? "true" : "false") << "\n";
    if (f.virtual_mass)
      os << "virtual_mass_coefficient = " << format_double(f.virtual_mass_coefficient) << "\n";
    os << "basset = " << (f.basset ? "true" : "false") << "\n";
    if (f.basset) os << "basset_window = " << f.basset_window << "  # flow steps\n";
    os << "saffman = " << (f.saffman ? "true" : "false") << "\n"
       << "magnus = " << toml_string(f.magnus) << "\n"
       << "torque = " << toml_string(f.torque) << "\n";
  }
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
  if (spec.output.checkpoint_interval > 0.0)
    os << "checkpoint_interval = " << format_double(spec.output.checkpoint_interval) << "  # s\n";
  if (spec.output.layers > 0) os << "layers = " << spec.output.layers << "\n";
  if (spec.output.collisions) os << "collisions = true\n";
  if (spec.output.analyse) os << "analyse = true\n";
  if (const auto& c = spec.output.continuum) {
    os << "\n[output.continuum]\n"
       << "cells = [" << c->cells[0] << ", " << c->cells[1] << ", " << c->cells[2] << "]\n"
       << "method = " << toml_string(to_string(c->method)) << "\n";
    if (c->method == ContinuumMethod::Weighted)
      os << "width = " << format_double(c->width) << "  # m\n"
         << "cutoff = " << format_double(c->cutoff) << "  # x width\n";
    if (c->interval > 0.0) os << "interval = " << format_double(c->interval) << "  # s\n";
    os << "stride = " << c->stride << "\n";
  }
  if (spec.gas) {
    for (const ProbeSpec& p : spec.output.probes)
      os << "\n[[output.probe]]\n"
         << "name = " << toml_string(p.name) << "\n"
         << "position = " << vec3(p.position) << "  # m\n";
  }
  if (spec.output.collisions) {
    for (const CollisionRegionSpec& r : spec.output.collision_regions)
      os << "\n[[output.collision_region]]\n"
         << "name = " << toml_string(r.name) << "\n"
         << "centre = " << vec3(r.centre) << "  # m\n"
         << "radius = " << format_double(r.radius) << "  # m\n";
  }

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
    if (sp.charge != 0.0) os << "charge = " << format_double(sp.charge) << "  # C\n";
    if (sp.liquid_fraction != 0.0)
      os << "liquid_fraction = " << format_double(sp.liquid_fraction) << "  # of the volume\n";
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
       << "angular_velocity = " << vec3(in.angular_velocity) << "  # rad/s\n"
       << "fixed = " << (in.fixed ? "true" : "false") << "\n"
       << "seed = " << in.seed << "\n";
    if (in.charge) os << "charge = " << format_double(*in.charge) << "  # C\n";
    if (in.size_distribution)
      os << "size_distribution = " << size_distribution(*in.size_distribution) << "  # m\n";
  }

  // Each model's name, then its coefficients as it declares them ("auto" when left to it).
  const ContactSpec& c = spec.contact;
  os << "\n[contact]\n";
  const contact_models::Chosen chosen = contact_models::choose(spec);
  for (const contact_models::Kind kind : contact_models::kKinds) {
    const contact_models::ModelInfo& m = chosen.of(kind);
    os << contact_models::kind_key(kind) << " = " << toml_string(std::string(m.name)) << "\n";
    const auto& given = contact_models::of(c, kind).coefficients;
    for (const contact_models::Coefficient& k : m.coefficients) {
      const auto v = contact_models::coefficient(given, std::string(k.key));
      if (!v && k.given == contact_models::Given::Required) continue; // (a refused model)
      os << k.key << " = " << auto_or(v);
      if (!k.unit.empty()) os << "  # " << k.unit;
      os << "\n";
    }
  }
  os << "characteristic_velocity = " << auto_or(c.characteristic_velocity) << "  # m/s\n"
     << "max_overlap = " << format_double(c.max_overlap) << "\n";

  os << "\n[parallel]\n"
     << "rank_independent = "
     << (spec.parallel.rank_independent ? (*spec.parallel.rank_independent ? "true" : "false")
                                        : "\"auto\"")
     << "  # the same bits on any number of ranks (auto: under mpirun)\n"
     << "process_grid = ";
  if (spec.parallel.process_grid == std::array<int, 3>{0, 0, 0})
    os << "\"auto\"";
  else
    os << "[" << spec.parallel.process_grid[0] << ", " << spec.parallel.process_grid[1] << ", "
       << spec.parallel.process_grid[2] << "]";
  os << "  # ranks per axis\n"
     << "balance_interval = " << spec.parallel.balance_interval
     << "  # list builds between moves of the cut planes (0: never)\n";
  os << "\n[neighbour]\n"
     << "skin = " << auto_or(spec.neighbour.skin) << "  # m\n"
     << "sort_interval = " << spec.neighbour.sort_interval << "  # rebuilds between sorts\n";

  const HardSphereSpec& h = spec.hardsphere;
  os << "\n[hardsphere]\n"
     << "tc_time = " << format_double(h.tc_time) << "  # s\n"
     << "elastic_below = " << auto_or(h.elastic_below) << "  # m/s\n"
     << "max_events_per_particle = " << format_double(h.max_events_per_particle) << "\n";

  if (const CoarseGrainingSpec& cg = spec.coarse_graining; cg.active())
    os << "\n[coarse_graining]\n"
       << "ratio = " << format_double(cg.ratio) << "  # real particles per parcel\n"
       << "contact_scaling = " << toml_string(std::string(to_string(cg.contact_scaling))) << "\n"
       << "drag_diameter = " << toml_string(std::string(to_string(cg.drag_diameter))) << "\n";

  if (spec.body_force) {
    const BodyForceSpec& b = *spec.body_force;
    os << "\n[body_force]\n"
       << "type = " << toml_string(to_string(b.type)) << "\n"
       << "amplitude = " << format_double(b.amplitude) << "  # m/s^2\n"
       << "wavelength = " << format_double(b.wavelength) << "  # m\n"
       << "origin = " << vec3(b.origin) << "  # m\n";
  }

  if (const auto& v = spec.noncontact.van_der_waals) {
    os << "\n[van_der_waals]\n"
       << "hamaker = " << format_double(v->hamaker) << "  # J\n"
       << "min_separation = " << format_double(v->min_separation) << "  # m\n"
       << "range = " << format_double(v->range) << "  # m\n";
    if (v->wall_hamaker) os << "wall_hamaker = " << format_double(*v->wall_hamaker) << "  # J\n";
  }
  if (const auto& e = spec.noncontact.electrostatics) {
    os << "\n[electrostatics]\n"
       << "cutoff = " << format_double(e->cutoff) << "  # m\n"
       << "relative_permittivity = " << format_double(e->relative_permittivity) << "\n"
       << "conducting_walls = [";
    const char* sep = "";
    for (std::size_t f = 0; f < 6; ++f)
      if (e->conducting[f]) os << sep << toml_string(kFaceNames[f]), sep = ", ";
    os << "]\n";
  }

  if (const auto& b = spec.noncontact.liquid_bridge) {
    os << "\n[liquid_bridge]\n"
       << "surface_tension = " << format_double(b->surface_tension) << "  # N/m\n"
       << "contact_angle = " << format_double(b->contact_angle_degrees) << "  # degrees\n"
       << "viscosity = " << format_double(b->viscosity) << "  # Pa s\n";
    if (b->min_gap > 0.0) os << "min_gap = " << format_double(b->min_gap) << "  # m\n";
    os << "walls = " << (b->walls ? "true" : "false") << "\n";
  }

  // A coupled run only; a granular case has neither (the reader would reject [coupling]).
  if (spec.gas) {
    write_gas(os, *spec.gas, spec.simulation.engine);
    write_coupling(os, spec.coupling);
  }
  return os.str();
}

} // namespace fluidem
