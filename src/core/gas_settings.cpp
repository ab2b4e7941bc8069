// Validation of the gas settings and the inflow time functions [Deen07 §6.1].
#include "core/gas_settings.hpp"
#include "core/error.hpp"
#include <algorithm>
#include <cmath>
#include <numbers>

namespace fluidem::gas {

double inflow_velocity(const InflowProfile& p, double t) {
  switch (p.mode) {
  case InflowMode::constant:
    return p.velocity;
  case InflowMode::pulse:
    return (t >= p.start && t < p.start + p.duration) ? p.velocity : p.background;
  case InflowMode::pulsation:
    return p.velocity + p.amplitude * std::sin(2.0 * std::numbers::pi * p.frequency * t);
  case InflowMode::table: {
    // Piecewise linear through (times[k], velocities[k]); constant beyond the ends.
    const auto& ts = p.times;
    const auto& vs = p.velocities;
    if (ts.empty()) return 0.0;
    if (t <= ts.front()) return vs.front();
    if (t >= ts.back()) return vs.back();
    const auto k = static_cast<std::size_t>(std::upper_bound(ts.begin(), ts.end(), t) -
                                            ts.begin()); // ts[k-1] <= t < ts[k]
    const double w = (t - ts[k - 1]) / (ts[k] - ts[k - 1]);
    return vs[k - 1] + w * (vs[k] - vs[k - 1]);
  }
  }
  throw InputError("gas: inflow mode out of range");
}

namespace {

[[noreturn]] void bad(const std::string& key, const std::string& what) {
  throw InputError(key + ": " + what);
}

void check_finite(double v, const std::string& key) {
  if (!std::isfinite(v)) bad(key, "must be a finite number");
}

void check_profile(const InflowProfile& p, const std::string& key) {
  const int m = static_cast<int>(p.mode);
  if (m < 0 || m > 3) bad(key + ".mode", "unknown inflow mode (constant, pulse, pulsation, table)");
  if (p.mode == InflowMode::table) {
    if (p.times.size() < 2 || p.times.size() != p.velocities.size())
      bad(key + ".times", "mode \"table\" needs times and velocities of equal length >= 2");
    for (std::size_t k = 0; k < p.times.size(); ++k) {
      check_finite(p.times[k], key + ".times");
      check_finite(p.velocities[k], key + ".velocities");
      if (k > 0 && !(p.times[k] > p.times[k - 1]))
        bad(key + ".times", "must be strictly increasing");
    }
  }
  check_finite(p.velocity, key + ".velocity");
  check_finite(p.background, key + ".background");
  check_finite(p.start, key + ".start");
  check_finite(p.amplitude, key + ".amplitude");
  if (!(p.duration >= 0.0) || !std::isfinite(p.duration)) bad(key + ".duration", "must be >= 0 s");
  if (!(p.frequency >= 0.0) || !std::isfinite(p.frequency))
    bad(key + ".frequency", "must be >= 0 Hz");
}

/// "a, b, c": the names of every boundary type.
std::string boundary_type_names() {
  std::string s;
  for (std::size_t t = 0; t < boundary_type_count; ++t)
    s += std::string(t ? ", " : "") + boundary_kind(static_cast<BoundaryType>(t)).name;
  return s;
}

void check_type(BoundaryType t, const std::string& key) {
  if (static_cast<std::size_t>(t) >= boundary_type_count)
    bad(key, "unknown boundary type (" + boundary_type_names() + ")");
}

void check_pressure(double p, const std::string& key) {
  check_boundary_pressure(p, key);
}

/// The check a type declares for its own keys (the pressure's, ...).
void check_own(BoundaryType t, const BoundaryValues& v, const std::string& key) {
  if (const auto check = boundary_kind(t).check) check(v, key);
}

bool is_periodic(BoundaryType t) {
  return static_cast<std::size_t>(t) < boundary_type_count &&
         boundary_kind(t).normal == NormalRule::periodic;
}

void check_porosity(double e, const std::string& key) {
  if (!(e > 0.0 && e <= 1.0)) bad(key, "must be in (0, 1]");
}

} // namespace

void validate(const GasSettings& s) {
  if (s.dimension != 2 && s.dimension != 3) bad("gas.dimension", "must be 2 or 3");
  for (int d = 0; d < 3; ++d) {
    if (d == 1 && s.dimension == 2) continue;
    if (s.cells[d] < 1) bad("gas.cells", "every cell count must be >= 1");
    if (!(s.hi[d] > s.lo[d]) || !std::isfinite(s.hi[d] - s.lo[d]))
      bad("gas.hi", "must exceed gas.lo on every axis");
  }
  if (s.dimension == 2 && (!(s.depth > 0.0) || !std::isfinite(s.depth)))
    bad("gas.depth", "must be > 0 m in 2-D");
  if (!(s.time_step >= 0.0) || !std::isfinite(s.time_step))
    bad("gas.time_step", "must be > 0 s (or \"auto\")");
  if (!(s.viscosity >= 0.0) || !std::isfinite(s.viscosity))
    bad("gas.viscosity", "must be >= 0 Pa s");
  if (s.model != PressureModel::A && s.model != PressureModel::B)
    bad("gas.model", "unknown model (A, B)");
  if (s.eos == EquationOfState::ideal_gas) {
    if (!(s.molar_mass > 0.0)) bad("gas.molar_mass", "must be > 0 kg/mol");
    if (!(s.temperature > 0.0)) bad("gas.temperature", "must be > 0 K");
  } else if (s.eos == EquationOfState::incompressible) {
    if (!(s.density > 0.0) || !std::isfinite(s.density)) bad("gas.density", "must be > 0 kg/m^3");
  } else {
    bad("gas.eos", "unknown equation of state (ideal_gas, incompressible)");
  }
  for (int d = 0; d < 3; ++d) check_finite(s.gravity[d], "gas.gravity");
  for (int d = 0; d < 3; ++d) check_finite(s.initial_velocity[d], "gas.initial_velocity");
  check_pressure(s.initial_pressure, "gas.initial_pressure");

  for (int f = 0; f < 6; ++f) {
    const GasBoundary& b = s.boundary[f];
    const std::string key = std::string("gas.boundary.") + side_names[f];
    if (s.dimension == 2 && (f == front || f == back)) continue;
    check_type(b.type, key + ".type");
    const GasBoundary& other = s.boundary[f ^ 1];
    if (is_periodic(b.type) != is_periodic(other.type))
      bad(key + ".type", std::string("periodic must be set on both ") + side_names[f & ~1] +
                             " and " + side_names[f | 1]);
    check_profile(b.inflow, key);
    check_porosity(b.porosity, key + ".porosity");
    check_own(b.type, {b.inflow, b.porosity, b.pressure}, key);
    for (std::size_t r = 0; r < b.regions.size(); ++r) {
      const BoundaryRegion& g = b.regions[r];
      const std::string rk = key + ".regions[" + std::to_string(r) + "]";
      check_type(g.type, rk + ".type");
      if (!boundary_kind(g.type).on_regions)
        bad(rk + ".type", std::string("a region cannot be ") + boundary_kind(g.type).name);
      if (is_periodic(b.type)) bad(rk, "a periodic face cannot have regions");
      for (int a = 0; a < 2; ++a)
        if (!(g.hi[a] > g.lo[a]) || !std::isfinite(g.hi[a] - g.lo[a]))
          bad(rk + ".hi", "must exceed .lo in both tangential coordinates");
      check_profile(g.inflow, rk);
      check_porosity(g.porosity, rk + ".porosity");
      check_own(g.type, {g.inflow, g.porosity, g.pressure}, rk);
    }
  }
  if (!(s.tolerance > 0.0)) bad("gas.solver.tolerance", "must be > 0");
  if (!(s.velocity_tolerance > 0.0)) bad("gas.solver.velocity_tolerance", "must be > 0 m/s");
  if (s.max_iterations < 1) bad("gas.solver.max_iterations", "must be >= 1");
  if (!(s.velocity_relaxation > 0.0 && s.velocity_relaxation <= 1.0))
    bad("gas.solver.velocity_relaxation", "must be in (0, 1]");
  if (!(s.pressure_relaxation > 0.0 && s.pressure_relaxation <= 1.0))
    bad("gas.solver.pressure_relaxation", "must be in (0, 1]");
  if (!(s.linear_tolerance > 0.0 && s.linear_tolerance < 1.0))
    bad("gas.solver.linear_tolerance", "must be in (0, 1)");
  if (s.linear_max_iterations < 1) bad("gas.solver.linear_max_iterations", "must be >= 1");
  if (!(s.max_courant > 0.0) || !std::isfinite(s.max_courant))
    bad("gas.solver.max_courant", "must be > 0");
}

std::string to_string(BoundaryType t) {
  return static_cast<std::size_t>(t) < boundary_type_count ? boundary_kind(t).name : "?";
}

std::string to_string(InflowMode m) {
  switch (m) {
  case InflowMode::constant:
    return "constant";
  case InflowMode::pulse:
    return "pulse";
  case InflowMode::pulsation:
    return "pulsation";
  case InflowMode::table:
    return "table";
  }
  return "?";
}

BoundaryType boundary_type_from_string(const std::string& name, const std::string& key) {
  for (std::size_t t = 0; t < boundary_type_count; ++t)
    if (boundary_kind(static_cast<BoundaryType>(t)).name == name)
      return static_cast<BoundaryType>(t);
  bad(key, "unknown boundary type '" + name + "' (" + boundary_type_names() + ")");
}

InflowMode inflow_mode_from_string(const std::string& name, const std::string& key) {
  for (InflowMode m :
       {InflowMode::constant, InflowMode::pulse, InflowMode::pulsation, InflowMode::table})
    if (to_string(m) == name) return m;
  bad(key, "unknown inflow mode '" + name + "' (constant, pulse, pulsation, table)");
}

PressureModel pressure_model_from_string(const std::string& name, const std::string& key) {
  if (name == "A") return PressureModel::A;
  if (name == "B") return PressureModel::B;
  bad(key, "unknown model '" + name + "' (A, B)");
}

EquationOfState eos_from_string(const std::string& name, const std::string& key) {
  if (name == "ideal_gas") return EquationOfState::ideal_gas;
  if (name == "incompressible") return EquationOfState::incompressible;
  bad(key, "unknown equation of state '" + name + "' (ideal_gas, incompressible)");
}

} // namespace fluidem::gas
