// Case file of a coupled run: [gas], [gas.solver], [gas.boundary.*] with regions, [coupling],
// [[output.probe]]. A full case parses to the expected values, write -> read reproduces every
// field bit for bit, and every class of bad input is one InputError naming file:line and the key
// (docs/case-file.md is the spec).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>
#include <vector>

#include "io/case_reader.hpp"
#include "io/case_writer.hpp"

#include "../../common/case_error.hpp"

namespace fluidem {
namespace {

using gas::BoundaryType;
using gas::InflowMode;

// The particle side of a 2-D bed, 0.15 m wide, 15 mm deep, 0.5 m tall.
const std::string kParticles2D = R"([simulation]
dimension = 2
end_time = 1.0

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.15, 0.015, 0.5]

[[species]]
name = "glass"
diameter = 0.0025
density = 2500.0

[[insert]]
species = "glass"
count = 2000
)";

/// The smallest coupled 2-D case: kParticles2D plus `gas` (which must include a cells line).
std::string coupled2d(const std::string& gas_lines = "[gas]\ncells = [30, 1, 100]\n") {
  return kParticles2D + gas_lines;
}

// The docs/case-file.md example: a 2-D bed on a distributor, a pulsed orifice, a pressure top.
const std::string kBed2D = R"([simulation]
dimension = 2
end_time = 1.0

[output]
frame_interval = 0.01

[[output.probe]]
name = "p_plenum"
position = [0.075, 0.0075, 0.005]

[[output.probe]]
name = "p_freeboard"
position = [0.075, 0.0, 0.45]

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.15, 0.015, 0.5]

[[species]]
name = "glass"
diameter = 0.0025
density = 2500.0

[[insert]]
species = "glass"
count = 2000
region = { lo = [0.0, 0.0, 0.0], hi = [0.15, 0.015, 0.15] }

[gas]
cells = [30, 1, 100]
time_step = 1e-4
viscosity = 1.8e-5
model = "A"
eos = "ideal_gas"
molar_mass = 28.8e-3
temperature = 293.0
initial_pressure = 101325.0

[gas.solver]
tolerance = 1e-8
max_iterations = 50

[gas.boundary.left]
type = "wall_no_slip"

[gas.boundary.right]
type = "wall_no_slip"

[gas.boundary.bottom]
type = "inflow"
velocity = 1.8
porosity = 0.4

[[gas.boundary.bottom.region]]
type = "inflow"
lo = [0.07, 0.0]
hi = [0.08, 0.015]
mode = "pulse"
velocity = 20.0
background = 1.8
start = 0.1
duration = 0.2
porosity = 0.4

[gas.boundary.top]
type = "pressure"
pressure = 101325.0

[coupling]
drag = "ergun_wen_yu"
porosity = "cell"
scheme = 3
)";

// A 3-D case using every other option: periodic x, incompressible Model B gas, a pulsating
// bottom, outflow top with a pressure vent, free-slip front with an outflow region, porous-cube
// porosity, non-default solver settings.
const std::string kBox3D = R"([simulation]
end_time = 0.25
gravity = [0.0, 0.0, -9.80665]

[output]
series_interval = 0.0005

[[output.probe]]
name = "centre"
position = [0.05, 0.05, 0.1]

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.1, 0.1, 0.3]
periodic = [true, false, false]

[[species]]
name = "steel"
diameter = 0.002
density = 7800.0

[[insert]]
species = "steel"
count = 10

[gas]
cells = [10, 10, 30]
time_step = "auto"
viscosity = 1e-3
model = "B"
eos = "incompressible"
density = 998.2
initial_pressure = 2e5
initial_velocity = [0.0, 0.01, 0.02]

[gas.solver]
tolerance = 1e-9
velocity_tolerance = 1e-7
max_iterations = 250
velocity_relaxation = 0.7
pressure_relaxation = 0.30000000000000004
linear_tolerance = 1e-12
linear_max_iterations = 400

[gas.boundary.left]
type = "periodic"

[gas.boundary.front]
type = "wall_free_slip"

[[gas.boundary.front.region]]
type = "outflow"
lo = [0.02, 0.1]
hi = [0.08, 0.2]

[gas.boundary.back]
type = "wall_no_slip"

[gas.boundary.bottom]
type = "inflow"
mode = "pulsation"
velocity = 0.05
amplitude = 0.01
frequency = 2.5
porosity = 0.35

[gas.boundary.top]
type = "outflow"

[[gas.boundary.top.region]]
type = "pressure"
lo = [0.04, 0.04]
hi = [0.06, 0.06]
pressure = 1.5e5

[[gas.boundary.top.region]]
lo = [0.0, 0.0]
hi = [0.01, 0.01]
velocity = -0.1

[coupling]
drag = "beetstra_poly"
porosity = "porous_cube"
cube_factor = 2.5
scheme = 1
d_mean = 0.0021
)";

/// 1-based line of the first occurrence of `marker` in `text` (0 if absent).
long line_of(const std::string& text, const std::string& marker) {
  const auto pos = text.find(marker);
  if (pos == std::string::npos) return 0;
  return 1 +
         static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

using fluidem::test::error_of;

/// Expects an InputError at the line of `marker` in `text`, naming `key`, containing `what`.
void expect_error_at(const std::string& text, const std::string& marker, const std::string& key,
                     const std::string& what) {
  const long line = line_of(text, marker);
  ASSERT_GT(line, 0) << "marker not in text: " << marker;
  const std::string msg = error_of(text);
  const std::string where = "case.toml:" + std::to_string(line) + ":";
  EXPECT_EQ(msg.rfind(where, 0), 0u) << "expected location " << where << " in: " << msg;
  EXPECT_NE(msg.find(": " + key + ": "), std::string::npos)
      << "expected key " << key << " in: " << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << "expected '" << what << "' in: " << msg;
}

/// Bitwise equality of doubles (so -0.0 != 0.0 and the last ulp counts).
::testing::AssertionResult same_bits(double a, double b) {
  if (std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b))
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << format_double(a) << " != " << format_double(b);
}

void expect_same(const Vec3& a, const Vec3& b, const std::string& what) {
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(same_bits(a[i], b[i])) << what << "[" << i << "]";
}

void expect_same(const gas::InflowProfile& a, const gas::InflowProfile& b,
                 const std::string& what) {
  EXPECT_EQ(a.mode, b.mode) << what;
  EXPECT_TRUE(same_bits(a.velocity, b.velocity)) << what;
  EXPECT_TRUE(same_bits(a.background, b.background)) << what;
  EXPECT_TRUE(same_bits(a.start, b.start)) << what;
  EXPECT_TRUE(same_bits(a.duration, b.duration)) << what;
  EXPECT_TRUE(same_bits(a.amplitude, b.amplitude)) << what;
  EXPECT_TRUE(same_bits(a.frequency, b.frequency)) << what;
}

/// Every field of the gas settings, the coupling settings and the probes.
void expect_same_coupled(const CaseSpec& x, const CaseSpec& y) {
  ASSERT_EQ(x.gas.has_value(), y.gas.has_value());
  if (x.gas) {
    const gas::GasSettings& a = *x.gas;
    const gas::GasSettings& b = *y.gas;
    EXPECT_EQ(a.dimension, b.dimension);
    EXPECT_EQ(a.cells, b.cells);
    expect_same(a.lo, b.lo, "lo");
    expect_same(a.hi, b.hi, "hi");
    EXPECT_TRUE(same_bits(a.depth, b.depth));
    EXPECT_TRUE(same_bits(a.time_step, b.time_step));
    EXPECT_TRUE(same_bits(a.viscosity, b.viscosity));
    EXPECT_EQ(a.model, b.model);
    EXPECT_EQ(a.eos, b.eos);
    EXPECT_TRUE(same_bits(a.molar_mass, b.molar_mass));
    EXPECT_TRUE(same_bits(a.temperature, b.temperature));
    EXPECT_TRUE(same_bits(a.density, b.density));
    expect_same(a.gravity, b.gravity, "gravity");
    EXPECT_TRUE(same_bits(a.initial_pressure, b.initial_pressure));
    expect_same(a.initial_velocity, b.initial_velocity, "initial_velocity");
    EXPECT_TRUE(same_bits(a.tolerance, b.tolerance));
    EXPECT_TRUE(same_bits(a.velocity_tolerance, b.velocity_tolerance));
    EXPECT_EQ(a.max_iterations, b.max_iterations);
    EXPECT_TRUE(same_bits(a.velocity_relaxation, b.velocity_relaxation));
    EXPECT_TRUE(same_bits(a.pressure_relaxation, b.pressure_relaxation));
    EXPECT_TRUE(same_bits(a.linear_tolerance, b.linear_tolerance));
    EXPECT_EQ(a.linear_max_iterations, b.linear_max_iterations);
    for (std::size_t f = 0; f < 6; ++f) {
      const std::string side = gas::side_names[f];
      const gas::GasBoundary& p = a.boundary[f];
      const gas::GasBoundary& q = b.boundary[f];
      EXPECT_EQ(p.type, q.type) << side;
      expect_same(p.inflow, q.inflow, side);
      EXPECT_TRUE(same_bits(p.porosity, q.porosity)) << side;
      EXPECT_TRUE(same_bits(p.pressure, q.pressure)) << side;
      ASSERT_EQ(p.regions.size(), q.regions.size()) << side;
      for (std::size_t r = 0; r < p.regions.size(); ++r) {
        const std::string what = side + ".region[" + std::to_string(r) + "]";
        const gas::BoundaryRegion& u = p.regions[r];
        const gas::BoundaryRegion& v = q.regions[r];
        EXPECT_EQ(u.type, v.type) << what;
        EXPECT_TRUE(same_bits(u.lo[0], v.lo[0]) && same_bits(u.lo[1], v.lo[1])) << what;
        EXPECT_TRUE(same_bits(u.hi[0], v.hi[0]) && same_bits(u.hi[1], v.hi[1])) << what;
        expect_same(u.inflow, v.inflow, what);
        EXPECT_TRUE(same_bits(u.porosity, v.porosity)) << what;
        EXPECT_TRUE(same_bits(u.pressure, v.pressure)) << what;
      }
    }
  }
  EXPECT_EQ(x.coupling.drag, y.coupling.drag);
  EXPECT_EQ(x.coupling.porosity.method, y.coupling.porosity.method);
  EXPECT_TRUE(same_bits(x.coupling.porosity.cube_factor, y.coupling.porosity.cube_factor));
  EXPECT_EQ(x.coupling.scheme, y.coupling.scheme);
  EXPECT_TRUE(same_bits(x.coupling.d_mean, y.coupling.d_mean));
  ASSERT_EQ(x.output.probes.size(), y.output.probes.size());
  for (std::size_t i = 0; i < x.output.probes.size(); ++i) {
    EXPECT_EQ(x.output.probes[i].name, y.output.probes[i].name);
    for (std::size_t d = 0; d < 3; ++d)
      EXPECT_TRUE(same_bits(x.output.probes[i].position[d], y.output.probes[i].position[d]));
  }
}

// --- valid input ----------------------------------------------------------------------------

TEST(GasCase, GranularCaseHasNoGas) {
  const CaseSpec c = read_case_string(kParticles2D, "case.toml");
  EXPECT_FALSE(c.gas.has_value());
  EXPECT_TRUE(c.output.probes.empty());
  const coupling::CouplingSettings d;
  EXPECT_EQ(c.coupling.drag, d.drag);
  EXPECT_EQ(c.coupling.scheme, d.scheme);
}

TEST(GasCase, DefaultsAndDerivedSettings) {
  const CaseSpec c = read_case_string(coupled2d(), "case.toml");
  ASSERT_TRUE(c.gas.has_value());
  const gas::GasSettings& g = *c.gas;
  const gas::GasSettings d;
  // Derived from [simulation] and [domain].
  EXPECT_EQ(g.dimension, 2);
  EXPECT_EQ(g.lo[0], 0.0);
  EXPECT_EQ(g.hi[0], 0.15);
  EXPECT_EQ(g.hi[2], 0.5);
  EXPECT_EQ(g.depth, 0.015);
  EXPECT_EQ(g.gravity[2], -9.81);
  EXPECT_EQ(g.cells, (std::array<int, 3>{30, 1, 100}));
  // Everything else: the GasSettings defaults (no-slip walls).
  EXPECT_EQ(g.time_step, 0.0); // "auto"
  EXPECT_EQ(g.viscosity, d.viscosity);
  EXPECT_EQ(g.model, d.model);
  EXPECT_EQ(g.eos, d.eos);
  EXPECT_EQ(g.molar_mass, d.molar_mass);
  EXPECT_EQ(g.initial_pressure, d.initial_pressure);
  EXPECT_EQ(g.max_iterations, d.max_iterations);
  EXPECT_EQ(g.linear_tolerance, d.linear_tolerance);
  for (const int f : {gas::left, gas::right, gas::bottom, gas::top}) {
    EXPECT_EQ(g.boundary[f].type, BoundaryType::wall_no_slip);
    EXPECT_TRUE(g.boundary[f].regions.empty());
  }
  // The one-cell-thick 2-D gas: front and back are free-slip walls.
  EXPECT_EQ(g.boundary[gas::front].type, BoundaryType::wall_free_slip);
  EXPECT_EQ(g.boundary[gas::back].type, BoundaryType::wall_free_slip);
  const coupling::CouplingSettings cd;
  EXPECT_EQ(c.coupling.drag, cd.drag);
  EXPECT_EQ(c.coupling.porosity.method, cd.porosity.method);
  EXPECT_EQ(c.coupling.scheme, coupling::ExchangeScheme::scheme3);
  EXPECT_EQ(c.coupling.d_mean, 0.0);
  EXPECT_EQ(c.where("gas.cells").line, line_of(coupled2d(), "cells"));
}

TEST(GasCase, FullTwoDimensionalBedParses) {
  const CaseSpec c = read_case_string(kBed2D, "case.toml");
  ASSERT_TRUE(c.gas.has_value());
  const gas::GasSettings& g = *c.gas;
  EXPECT_EQ(g.cells, (std::array<int, 3>{30, 1, 100}));
  EXPECT_EQ(g.time_step, 1e-4);
  EXPECT_EQ(g.viscosity, 1.8e-5);
  EXPECT_EQ(g.model, gas::PressureModel::A);
  EXPECT_EQ(g.eos, gas::EquationOfState::ideal_gas);
  EXPECT_EQ(g.molar_mass, 28.8e-3);
  EXPECT_EQ(g.temperature, 293.0);
  EXPECT_EQ(g.tolerance, 1e-8);
  EXPECT_EQ(g.max_iterations, 50);
  EXPECT_EQ(g.depth, 0.015);

  const gas::GasBoundary& bottom = g.boundary[gas::bottom];
  EXPECT_EQ(bottom.type, BoundaryType::inflow);
  EXPECT_EQ(bottom.inflow.mode, InflowMode::constant);
  EXPECT_EQ(bottom.inflow.velocity, 1.8);
  EXPECT_EQ(bottom.porosity, 0.4);
  ASSERT_EQ(bottom.regions.size(), 1u);
  const gas::BoundaryRegion& orifice = bottom.regions[0];
  EXPECT_EQ(orifice.type, BoundaryType::inflow);
  EXPECT_EQ(orifice.lo, (std::array<double, 2>{0.07, 0.0}));
  EXPECT_EQ(orifice.hi, (std::array<double, 2>{0.08, 0.015}));
  EXPECT_EQ(orifice.inflow.mode, InflowMode::pulse);
  EXPECT_EQ(orifice.inflow.velocity, 20.0);
  EXPECT_EQ(orifice.inflow.background, 1.8);
  EXPECT_EQ(orifice.inflow.start, 0.1);
  EXPECT_EQ(orifice.inflow.duration, 0.2);
  // The pulse as the gas module sees it.
  EXPECT_EQ(gas::inflow_velocity(orifice.inflow, 0.05), 1.8);
  EXPECT_EQ(gas::inflow_velocity(orifice.inflow, 0.2), 20.0);
  EXPECT_EQ(gas::inflow_velocity(orifice.inflow, 0.35), 1.8);
  EXPECT_EQ(g.boundary[gas::top].type, BoundaryType::pressure);
  EXPECT_EQ(g.boundary[gas::top].pressure, 101325.0);
  EXPECT_EQ(g.boundary[gas::left].type, BoundaryType::wall_no_slip);
  EXPECT_EQ(g.boundary[gas::right].type, BoundaryType::wall_no_slip);

  EXPECT_EQ(c.coupling.drag, "ergun_wen_yu");
  EXPECT_EQ(c.coupling.porosity.method, coupling::PorosityMethod::cell);
  EXPECT_EQ(c.coupling.scheme, coupling::ExchangeScheme::scheme3);

  ASSERT_EQ(c.output.probes.size(), 2u);
  EXPECT_EQ(c.output.probes[0].name, "p_plenum");
  EXPECT_EQ(c.output.probes[0].position, (std::array<double, 3>{0.075, 0.0075, 0.005}));
  EXPECT_EQ(c.output.probes[1].name, "p_freeboard");
  EXPECT_EQ(c.output.frame_interval, 0.01); // [output] keys still read

  // Locations, in the documented path forms.
  EXPECT_EQ(c.where("gas.viscosity").line, line_of(kBed2D, "viscosity"));
  EXPECT_EQ(c.where("gas.solver.max_iterations").line, line_of(kBed2D, "max_iterations"));
  EXPECT_EQ(c.where("gas.boundary.bottom.region[0]").line,
            line_of(kBed2D, "[[gas.boundary.bottom.region]]"));
  EXPECT_EQ(c.where("gas.boundary.bottom.region[0].duration").line, line_of(kBed2D, "duration"));
  EXPECT_EQ(c.where("gas.boundary.top.pressure").line, line_of(kBed2D, "[gas.boundary.top]") + 2);
  EXPECT_EQ(c.where("coupling.drag").line, line_of(kBed2D, "drag ="));
  EXPECT_EQ(c.where("output.probe[1].name").line, line_of(kBed2D, "p_freeboard"));
}

TEST(GasCase, FullThreeDimensionalBoxParses) {
  const CaseSpec c = read_case_string(kBox3D, "case.toml");
  ASSERT_TRUE(c.gas.has_value());
  const gas::GasSettings& g = *c.gas;
  EXPECT_EQ(g.dimension, 3);
  EXPECT_EQ(g.cells, (std::array<int, 3>{10, 10, 30}));
  EXPECT_EQ(g.time_step, 0.0); // "auto"
  EXPECT_EQ(g.gravity[2], -9.80665);
  EXPECT_EQ(g.model, gas::PressureModel::B);
  EXPECT_EQ(g.eos, gas::EquationOfState::incompressible);
  EXPECT_EQ(g.density, 998.2);
  EXPECT_EQ(g.initial_pressure, 2e5);
  EXPECT_EQ(g.initial_velocity[2], 0.02);
  EXPECT_EQ(g.velocity_tolerance, 1e-7);
  EXPECT_EQ(g.velocity_relaxation, 0.7);
  EXPECT_EQ(g.pressure_relaxation, 0.30000000000000004);
  EXPECT_EQ(g.linear_max_iterations, 400);
  // Periodic x: both faces, whether or not a table says so.
  EXPECT_EQ(g.boundary[gas::left].type, BoundaryType::periodic);
  EXPECT_EQ(g.boundary[gas::right].type, BoundaryType::periodic);
  EXPECT_EQ(g.boundary[gas::front].type, BoundaryType::wall_free_slip);
  ASSERT_EQ(g.boundary[gas::front].regions.size(), 1u);
  EXPECT_EQ(g.boundary[gas::front].regions[0].type, BoundaryType::outflow);
  EXPECT_EQ(g.boundary[gas::front].regions[0].lo, (std::array<double, 2>{0.02, 0.1})); // (x, z)
  EXPECT_EQ(g.boundary[gas::back].type, BoundaryType::wall_no_slip);
  const gas::GasBoundary& bottom = g.boundary[gas::bottom];
  EXPECT_EQ(bottom.inflow.mode, InflowMode::pulsation);
  EXPECT_EQ(bottom.inflow.velocity, 0.05);
  EXPECT_EQ(bottom.inflow.amplitude, 0.01);
  EXPECT_EQ(bottom.inflow.frequency, 2.5);
  EXPECT_EQ(bottom.porosity, 0.35);
  const gas::GasBoundary& top = g.boundary[gas::top];
  EXPECT_EQ(top.type, BoundaryType::outflow);
  ASSERT_EQ(top.regions.size(), 2u);
  EXPECT_EQ(top.regions[0].type, BoundaryType::pressure);
  EXPECT_EQ(top.regions[0].pressure, 1.5e5);
  EXPECT_EQ(top.regions[1].type, BoundaryType::inflow); // a region's default type
  EXPECT_EQ(top.regions[1].inflow.velocity, -0.1);
  EXPECT_EQ(c.coupling.drag, "beetstra_poly");
  EXPECT_EQ(c.coupling.porosity.method, coupling::PorosityMethod::porous_cube);
  EXPECT_EQ(c.coupling.porosity.cube_factor, 2.5);
  EXPECT_EQ(c.coupling.scheme, coupling::ExchangeScheme::scheme1);
  EXPECT_EQ(c.coupling.d_mean, 0.0021);
  ASSERT_EQ(c.output.probes.size(), 1u);
  EXPECT_EQ(c.output.probes[0].name, "centre");
}

TEST(GasCase, DocumentedExampleParses) {
  // The coupled example of docs/case-file.md is kBed2D with comments.
  std::ifstream in(std::string(FLUIDEM_SOURCE_DIR) + "/docs/case-file.md");
  ASSERT_TRUE(in) << "cannot open docs/case-file.md";
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const auto heading = doc.find("## A coupled example");
  ASSERT_NE(heading, std::string::npos);
  const auto begin = doc.find("```toml\n", heading);
  ASSERT_NE(begin, std::string::npos);
  const auto end = doc.find("```", begin + 8);
  ASSERT_NE(end, std::string::npos);
  const CaseSpec c = read_case_string(doc.substr(begin + 8, end - begin - 8), "case-file.md");
  expect_same_coupled(c, read_case_string(kBed2D, "case.toml"));
}

// --- writer ---------------------------------------------------------------------------------

TEST(GasCaseWriter, RoundTripIsExact) {
  for (const std::string* text : {&kBed2D, &kBox3D}) {
    const CaseSpec a = read_case_string(*text, "case.toml");
    const std::string written = write_case_toml(a);
    SCOPED_TRACE(written);
    const CaseSpec b = read_case_string(written, "case.resolved.toml");
    expect_same_coupled(a, b);
    EXPECT_EQ(write_case_toml(b), written); // the format is a fixed point
  }
}

TEST(GasCaseWriter, RoundTripHardSphereEngine) {
  // Hard spheres: DT is simulation.time_step, so gas.time_step is neither read nor written.
  std::string text = kBed2D;
  text.replace(text.find("time_step = 1e-4\n"), 17, "");
  text.replace(text.find("dimension = 2\n"), 14, "dimension = 2\nengine = \"hard_sphere\"\n");
  const CaseSpec a = read_case_string(text, "case.toml");
  ASSERT_EQ(a.simulation.engine, Engine::HardSphere);
  const std::string written = write_case_toml(a);
  EXPECT_EQ(written.substr(written.find("[gas]")).find("time_step"), std::string::npos) << written;
  const CaseSpec b = read_case_string(written, "case.resolved.toml");
  expect_same_coupled(a, b);
  EXPECT_EQ(write_case_toml(b), written);
}

// A velocity sweep: mode "table" parses, is validated, and round-trips exactly.
TEST(GasCaseWriter, RoundTripInflowTable) {
  const std::string text = coupled2d() +
                           "[gas.boundary.bottom]\ntype = \"inflow\"\nmode = \"table\"\n"
                           "times = [0.0, 1.0, 5, 9.0]\nvelocities = [2.8, 2.8, 0.3, 2.8]\n";
  const CaseSpec a = read_case_string(text, "case.toml");
  const auto& in = a.gas->boundary[gas::bottom].inflow;
  ASSERT_EQ(in.mode, gas::InflowMode::table);
  EXPECT_EQ(in.times, (std::vector<double>{0.0, 1.0, 5.0, 9.0}));
  EXPECT_EQ(in.velocities, (std::vector<double>{2.8, 2.8, 0.3, 2.8}));
  const CaseSpec b = read_case_string(write_case_toml(a), "case.resolved.toml");
  EXPECT_EQ(b.gas->boundary[gas::bottom].inflow.times, in.times);
  EXPECT_EQ(b.gas->boundary[gas::bottom].inflow.velocities, in.velocities);
  // Unequal lengths: gas::validate's error at the key.
  const std::string bad = coupled2d() +
                          "[gas.boundary.bottom]\ntype = \"inflow\"\nmode = \"table\"\n"
                          "times = [0.0, 1.0]\nvelocities = [2.8]\n";
  EXPECT_THROW(read_case_string(bad, "case.toml"), InputError);
}

TEST(GasCaseWriter, RoundTripAwkwardDoubles) {
  CaseSpec a = read_case_string(kBox3D, "case.toml");
  gas::GasSettings& g = *a.gas;
  const double third = 1.0 / 3.0;
  g.viscosity = 0.1 + 0.2;
  g.density = std::nextafter(1000.0, 2000.0);
  g.initial_velocity = Vec3{-0.0, third, -1e-300};
  g.boundary[gas::bottom].inflow.velocity = third;
  g.boundary[gas::bottom].inflow.amplitude = std::nextafter(0.01, 1.0);
  g.boundary[gas::top].regions[0].lo = {0.1 * third, 0.01 + 0.02};
  g.boundary[gas::top].regions[0].pressure = 101325.0 + third;
  g.tolerance = 2.5e-7;
  g.time_step = 1e-4 / 3.0;
  a.coupling.porosity.cube_factor = 1.0 + third;
  a.coupling.d_mean = 1e-3 / 3.0;
  a.output.probes[0].position = {0.1 * third, 0.2 * third, 0.3 * third};
  const CaseSpec b = read_case_string(write_case_toml(a), "case.resolved.toml");
  expect_same_coupled(a, b);
}

TEST(GasCaseWriter, OnlyApplicableKeysWritten) {
  const std::string text = write_case_toml(read_case_string(kBed2D, "case.toml"));
  for (const char* key : {"[gas]",
                          "cells = [30, 1, 100]",
                          "time_step = 1e-04",
                          "viscosity = 1.8e-05",
                          "model = \"A\"",
                          "eos = \"ideal_gas\"",
                          "[gas.solver]",
                          "max_iterations = 50",
                          "[gas.boundary.bottom]",
                          "type = \"inflow\"",
                          "mode = \"pulse\"",
                          "[[gas.boundary.bottom.region]]",
                          "lo = [0.07, 0.0]",
                          "[gas.boundary.top]",
                          "type = \"pressure\"",
                          "[coupling]",
                          "drag = \"ergun_wen_yu\"",
                          "porosity = \"cell\"",
                          "scheme = 3",
                          "[[output.probe]]",
                          "name = \"p_plenum\""})
    EXPECT_NE(text.find(key), std::string::npos) << "missing '" << key << "' in:\n" << text;
  // Derived settings, the 2-D front/back, and keys of other types/modes are left out.
  const std::string gas_part = text.substr(text.find("[gas]"));
  for (const char* key :
       {"dimension =", "lo = [0.0, 0.0, 0.0]", "gravity =", "depth =", "[gas.boundary.front]",
        "[gas.boundary.back]", "density =", "cube_factor", "amplitude", "background = 0.0"})
    EXPECT_EQ(gas_part.find(key), std::string::npos) << "unexpected '" << key << "' in:\n" << text;
}

TEST(GasCaseWriter, GranularCaseUnchanged) {
  const std::string text = write_case_toml(read_case_string(kParticles2D, "case.toml"));
  for (const char* key : {"[gas", "[coupling]", "probe"})
    EXPECT_EQ(text.find(key), std::string::npos) << "unexpected '" << key << "' in:\n" << text;
  EXPECT_FALSE(read_case_string(text, "case.resolved.toml").gas.has_value());
}

// --- bad input ------------------------------------------------------------------------------

TEST(GasCaseErrors, UnknownKeyInBoundaryWithSuggestion) {
  const std::string t = coupled2d() + "[gas.boundary.bottom]\ntype = \"inflow\"\nvelocty = 1.8\n";
  const long line = line_of(t, "velocty");
  EXPECT_EQ(error_of(t), "case.toml:" + std::to_string(line) +
                             ":1: gas.boundary.bottom.velocty: unknown key (did you mean "
                             "\"velocity\"?)");
  std::string u = coupled2d() + "[gas.boundary.bottm]\ntype = \"inflow\"\n";
  expect_error_at(u, "[gas.boundary.bottm]", "gas.boundary.bottm", "did you mean \"bottom\"?");
  u = coupled2d("[gas]\ncells = [30, 1, 100]\nviscosty = 1e-5\n");
  expect_error_at(u, "viscosty", "gas.viscosty", "did you mean \"viscosity\"?");
  u = coupled2d() + "[gas.solver]\nmax_iteration = 5\n";
  expect_error_at(u, "max_iteration", "gas.solver.max_iteration",
                  "did you mean \"max_iterations\"?");
  u = coupled2d() + "[[gas.boundary.bottom.region]]\nlo = [0.0, 0.0]\nhi = [0.1, 0.01]\n" +
      "presure = 1e5\n";
  expect_error_at(u, "presure", "gas.boundary.bottom.region[0].presure",
                  "did you mean \"pressure\"?");
  u = coupled2d() + "[coupling]\ndarg = \"ergun\"\n";
  expect_error_at(u, "darg", "coupling.darg", "did you mean \"drag\"?");
  u = coupled2d() + "[[output.probe]]\nname = \"a\"\npostion = [0.1, 0.0, 0.1]\n";
  expect_error_at(u, "postion", "output.probe[0].postion", "did you mean \"position\"?");
}

TEST(GasCaseErrors, BadNamesListValid) {
  std::string t = coupled2d() + "[gas.boundary.top]\ntype = \"presure\"\n";
  expect_error_at(t, "presure", "gas.boundary.top.type",
                  "unknown value \"presure\" (allowed: \"wall_free_slip\", \"wall_no_slip\", "
                  "\"inflow\", \"pressure\", \"outflow\")");
  t = coupled2d() + "[gas.boundary.bottom]\ntype = \"inflow\"\nmode = \"pulsed\"\n";
  expect_error_at(t, "pulsed", "gas.boundary.bottom.mode",
                  "(allowed: \"constant\", \"pulse\", \"pulsation\", \"table\")");
  t = coupled2d("[gas]\ncells = [30, 1, 100]\nmodel = \"C\"\n");
  expect_error_at(t, "model", "gas.model", "(allowed: \"A\", \"B\")");
  t = coupled2d("[gas]\ncells = [30, 1, 100]\neos = \"ideal\"\n");
  expect_error_at(t, "eos", "gas.eos", "(allowed: \"ideal_gas\", \"incompressible\")");
  // coupling.drag: a closure's name, checked at set-up (tests/unit/integrate/drag_choice_test).
  t = coupled2d() + "[coupling]\ndrag = 3\n";
  expect_error_at(t, "drag", "coupling.drag", "(allowed: the name of a drag closure");
  t = coupled2d() + "[coupling]\nporosity = \"cube\"\n";
  expect_error_at(t, "cube", "coupling.porosity", "(allowed: \"cell\", \"porous_cube\")");
  t = coupled2d() + "[coupling]\nscheme = 4\n";
  expect_error_at(t, "scheme", "coupling.scheme", "(allowed: 1, 2 or 3");
  t = coupled2d() + "[[gas.boundary.left.region]]\ntype = \"periodic\"\nlo = [0.0, 0.0]\n" +
      "hi = [0.01, 0.01]\n";
  expect_error_at(t, "periodic", "gas.boundary.left.region[0].type", "cannot be periodic");
  t = coupled2d() + "[gas.boundary.left]\ntype = \"periodic\"\n";
  expect_error_at(t, "periodic", "gas.boundary.left.type", "set by domain.periodic");
}

TEST(GasCaseErrors, KeysThatDoNotApply) {
  std::string t = coupled2d() + "[gas.boundary.bottom]\ntype = \"inflow\"\nvelocity = 1.0\n" +
                  "amplitude = 0.5\n";
  expect_error_at(t, "amplitude", "gas.boundary.bottom.amplitude",
                  "not allowed with mode = \"constant\" (only with type = \"inflow\" and mode = "
                  "\"pulsation\")");
  // Default type (no-slip wall): no velocity.
  t = coupled2d() + "[gas.boundary.left]\nvelocity = 1.0\n";
  expect_error_at(t, "velocity", "gas.boundary.left.velocity",
                  "not allowed with type = \"wall_no_slip\" (only with type = \"inflow\" and "
                  "mode = \"constant\", \"pulse\" or \"pulsation\")");
  // Table mode: times/velocities only there, and no single velocity.
  t = coupled2d() + "[gas.boundary.bottom]\ntype = \"inflow\"\nmode = \"table\"\n" +
      "times = [0.0, 1.0]\nvelocities = [0.5, 2.0]\nvelocity = 1.0\n";
  expect_error_at(t, "velocity = 1.0", "gas.boundary.bottom.velocity",
                  "not allowed with mode = \"table\"");
  t = coupled2d() + "[gas.boundary.bottom]\ntype = \"inflow\"\nvelocity = 1.0\n" +
      "times = [0.0, 1.0]\n";
  expect_error_at(t, "times", "gas.boundary.bottom.times",
                  "(only with type = \"inflow\" and mode = \"table\")");
  t = coupled2d() + "[gas.boundary.top]\ntype = \"outflow\"\npressure = 1e5\n";
  expect_error_at(t, "pressure = 1e5", "gas.boundary.top.pressure",
                  "(only with type = \"pressure\")");
  t = coupled2d() + "[gas.boundary.top]\ntype = \"pressure\"\nporosity = 0.4\n";
  expect_error_at(t, "porosity", "gas.boundary.top.porosity", "(only with type = \"inflow\")");
  t = coupled2d() + "[gas.boundary.bottom]\ntype = \"inflow\"\nmode = \"pulsation\"\n" +
      "duration = 0.1\n";
  expect_error_at(t, "duration", "gas.boundary.bottom.duration",
                  "not allowed with mode = \"pulsation\" (only with type = \"inflow\" and mode = "
                  "\"pulse\")");
  // The first such key in file order is named (toml++ orders keys by name).
  t = coupled2d() + "[gas.boundary.right]\ntype = \"wall_free_slip\"\nstart = 1.0\nmode = \"x\"\n";
  expect_error_at(t, "start", "gas.boundary.right.start", "type = \"wall_free_slip\"");
  // Regions too.
  t = coupled2d() + "[[gas.boundary.bottom.region]]\ntype = \"pressure\"\nlo = [0.0, 0.0]\n" +
      "hi = [0.1, 0.01]\nvelocity = 3.0\n";
  expect_error_at(t, "velocity", "gas.boundary.bottom.region[0].velocity",
                  "not allowed with type = \"pressure\"");
  // Equation of state.
  t = coupled2d("[gas]\ncells = [30, 1, 100]\ndensity = 1.2\n");
  expect_error_at(t, "density = 1.2", "gas.density",
                  "not allowed with eos = \"ideal_gas\" (only with eos = \"incompressible\")");
  t = coupled2d("[gas]\ncells = [30, 1, 100]\neos = \"incompressible\"\ntemperature = 300\n");
  expect_error_at(t, "temperature", "gas.temperature", "only with eos = \"ideal_gas\"");
  t = coupled2d() + "[coupling]\ncube_factor = 2.0\n";
  expect_error_at(t, "cube_factor", "coupling.cube_factor",
                  "not allowed with porosity = \"cell\" (only with porosity = \"porous_cube\")");
}

TEST(GasCaseErrors, DerivedSettingsAreNotKeys) {
  std::string t = coupled2d("[gas]\ncells = [30, 1, 100]\nhi = [0.1, 0.01, 0.4] # here\n");
  expect_error_at(t, "# here", "gas.hi",
                  "not a [gas] key (the gas domain is the particle domain, domain.lo and "
                  "domain.hi)");
  t = coupled2d("[gas]\ncells = [30, 1, 100]\ngravity = [0.0, 0.0, -9.81]\n");
  expect_error_at(t, "gravity", "gas.gravity", "(the gas gravity is simulation.gravity)");
  t = coupled2d("[gas]\ndepth = 0.01\ncells = [30, 1, 100]\n");
  expect_error_at(t, "depth", "gas.depth", "domain.hi[1] - domain.lo[1]");
  t = coupled2d("[gas]\ncells = [30, 1, 100]\ndimension = 2 # here\n");
  expect_error_at(t, "# here", "gas.dimension", "simulation.dimension");
}

TEST(GasCaseErrors, FlowTimeStep) {
  std::string t = coupled2d("[gas]\ncells = [30, 1, 100]\ntime_step = 0\n");
  expect_error_at(t, "time_step", "gas.time_step",
                  "0 is out of range (allowed: a number > 0, in s");
  t = coupled2d("[gas]\ncells = [30, 1, 100]\ntime_step = \"soon\"\n");
  expect_error_at(t, "time_step", "gas.time_step", "expected a number or \"auto\"");
  t = kParticles2D + "[gas]\ncells = [30, 1, 100]\ntime_step = 1e-4\n";
  t.replace(t.find("end_time"), 0, "engine = \"hard_sphere\"\n");
  expect_error_at(t, "time_step", "gas.time_step",
                  "not allowed with engine = \"hard_sphere\" (only with engine = \"soft_sphere\"");
}

TEST(GasCaseErrors, DimensionTwo) {
  std::string t = coupled2d("[gas]\ncells = [30, 4, 100]\n");
  expect_error_at(t, "cells", "gas.cells", "ny = 4 is not 1 in dimension 2");
  t = coupled2d() + "[gas.boundary.front]\ntype = \"wall_no_slip\"\n";
  expect_error_at(t, "[gas.boundary.front]", "gas.boundary.front", "not allowed in dimension 2");
  t = coupled2d("[gas]\ncells = [30, 1, 100]\ninitial_velocity = [0.0, 0.1, 0.0]\n");
  expect_error_at(t, "initial_velocity", "gas.initial_velocity", "not 0 in dimension 2");
}

TEST(GasCaseErrors, PeriodicFaces) {
  const std::string periodic_x =
      R"([simulation]
end_time = 1.0
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.1, 0.1, 0.1]
periodic = [true, false, false]
[[species]]
name = "s"
diameter = 0.002
density = 2500.0
[[insert]]
species = "s"
count = 1
[gas]
cells = [4, 4, 4]
)";
  std::string t = periodic_x + "[gas.boundary.right]\ntype = \"inflow\"\n";
  expect_error_at(t, "inflow", "gas.boundary.right.type",
                  "\"inflow\" on a periodic face (allowed: \"periodic\", or no type; the face is "
                  "periodic because domain.periodic[0] = true)");
  t = periodic_x + "[gas.boundary.left]\npressure = 1e5\n";
  expect_error_at(t, "pressure", "gas.boundary.left.pressure",
                  "not allowed with type = \"periodic\"");
  t = periodic_x + "[[gas.boundary.left.region]]\nlo = [0.0, 0.0]\nhi = [0.01, 0.01]\n";
  expect_error_at(t, "[[gas.boundary.left.region]]", "gas.boundary.left.region",
                  "not allowed on a periodic face");
}

TEST(GasCaseErrors, RegionsAndRequiredKeys) {
  std::string t =
      coupled2d() + "[[gas.boundary.bottom.region]]\nlo = [0.1, 0.0]\n" + "hi = [0.2, 0.015]\n";
  expect_error_at(t, "hi = [0.2", "gas.boundary.bottom.region[0].hi",
                  "hi[0] = 0.2 is outside the bottom face (allowed: 0.0 <= x <= 0.15");
  t = coupled2d() + "[[gas.boundary.bottom.region]]\nhi = [0.1, 0.015]\n";
  expect_error_at(t, "[[gas.boundary.bottom.region]]", "gas.boundary.bottom.region[0].lo",
                  "missing required key");
  t = coupled2d() + "[[gas.boundary.bottom.region]]\nlo = [0.1, 0.0, 0.0]\nhi = [0.1, 0.015]\n";
  expect_error_at(t, "lo = [0.1", "gas.boundary.bottom.region[0].lo", "an array of 2 numbers");
  // hi > lo is gas::validate()'s rule, reported at the case-file key ("region", not "regions").
  t = coupled2d() + "[[gas.boundary.bottom.region]]\nlo = [0.1, 0.0]\nhi = [0.05, 0.015]\n";
  expect_error_at(t, "hi = [0.05", "gas.boundary.bottom.region[0].hi", "must exceed .lo");
  t = kParticles2D + "[gas]\nviscosity = 1e-5\n";
  expect_error_at(t, "[gas]", "gas.cells", "missing required key in [gas]");
  t = kParticles2D + "[gas.boundary.bottom]\ntype = \"inflow\"\n"; // [gas] implied, no cells
  expect_error_at(t, "[gas.boundary.bottom]", "gas.cells", "missing required key in [gas]");
  t = coupled2d("[gas]\ncells = [30, 1.5, 100]\n");
  expect_error_at(t, "cells", "gas.cells[1]", "expected an integer");
}

TEST(GasCaseErrors, ValidateErrorsAtTheirKey) {
  std::string t = coupled2d("[gas]\ncells = [30, 1, 100]\nviscosity = -1e-5\n");
  expect_error_at(t, "viscosity", "gas.viscosity", "must be >= 0 Pa s");
  EXPECT_EQ(error_of(t), "case.toml:" + std::to_string(line_of(t, "viscosity")) +
                             ":1: gas.viscosity: must be >= 0 Pa s");
  t = coupled2d("[gas]\ncells = [30, 1, 100]\ntemperature = 0\n");
  expect_error_at(t, "temperature", "gas.temperature", "must be > 0 K");
  t = coupled2d() + "[gas.solver]\nvelocity_relaxation = 1.5\n";
  expect_error_at(t, "velocity_relaxation", "gas.solver.velocity_relaxation", "(0, 1]");
  t = coupled2d() + "[gas.boundary.bottom]\ntype = \"inflow\"\nporosity = 0.0\n";
  expect_error_at(t, "porosity", "gas.boundary.bottom.porosity", "must be in (0, 1]");
  t = coupled2d() + "[[gas.boundary.top.region]]\ntype = \"inflow\"\nlo = [0.0, 0.0]\n" +
      "hi = [0.1, 0.01]\nmode = \"pulse\"\nduration = -1\n";
  expect_error_at(t, "duration", "gas.boundary.top.region[0].duration", "must be >= 0 s");
  t = coupled2d() + "[gas.boundary.top]\ntype = \"pressure\"\npressure = -5\n";
  expect_error_at(t, "pressure = -5", "gas.boundary.top.pressure", "must be > 0 Pa");
}

TEST(GasCaseErrors, CouplingOnlyWithGas) {
  std::string t = kParticles2D + "[coupling]\ndrag = \"ergun\"\n";
  expect_error_at(t, "[coupling]", "coupling", "not allowed without [gas]");
  t = coupled2d() + "[coupling]\nporosity = \"porous_cube\"\ncube_factor = 0.5\n";
  expect_error_at(t, "cube_factor", "coupling.cube_factor",
                  "0.5 is out of range (allowed: a number >= (pi/6)^(1/3)");
  t = coupled2d() + "[coupling]\nd_mean = -0.001\n";
  expect_error_at(t, "d_mean", "coupling.d_mean", "(allowed: a number >= 0, in m)");
  t = coupled2d() + "[coupling]\nscheme = 3.0\n";
  expect_error_at(t, "scheme", "coupling.scheme", "expected an integer");
}

TEST(GasCaseErrors, Probes) {
  std::string t = coupled2d() + "[[output.probe]]\nname = \"p1\"\nposition = [0.2, 0.0, 0.1]\n";
  expect_error_at(t, "position", "output.probe[0].position",
                  "position[0] = 0.2 is outside the domain (allowed: a point inside the domain, "
                  "0.0 <= x <= 0.15)");
  // 2-D: y is not used, so it may lie anywhere.
  EXPECT_EQ(read_case_string(coupled2d() + "[[output.probe]]\nname = \"p1\"\n" +
                                 "position = [0.1, 7.0, 0.1]\n",
                             "case.toml")
                .output.probes.size(),
            1u);
  t = kParticles2D + "[[output.probe]]\nname = \"p1\"\nposition = [0.1, 0.0, 0.1]\n";
  expect_error_at(t, "[[output.probe]]", "output.probe", "not allowed without [gas]");
  t = coupled2d() + "[[output.probe]]\nname = \"a\"\nposition = [0.1, 0.0, 0.1]\n" +
      "[[output.probe]]\nname = \"a\" # again\nposition = [0.1, 0.0, 0.2]\n";
  expect_error_at(t, "# again", "output.probe[1].name", "duplicate probe name \"a\"");
  t = coupled2d() + "[[output.probe]]\nname = \"p,1\"\nposition = [0.1, 0.0, 0.1]\n";
  expect_error_at(t, "p,1", "output.probe[0].name", "has a comma, a quote or a line break");
  t = coupled2d() + "[[output.probe]]\nname = \"time\"\nposition = [0.1, 0.0, 0.1]\n";
  expect_error_at(t, "\"time\"", "output.probe[0].name", "the first column of probes.csv");
  t = coupled2d() + "[[output.probe]]\nname = \"\"\nposition = [0.1, 0.0, 0.1]\n";
  expect_error_at(t, "name = \"\"", "output.probe[0].name", "is empty");
  t = coupled2d() + "[[output.probe]]\nname = \"p\"\n";
  expect_error_at(t, "[[output.probe]]", "output.probe[0].position", "missing required key");
}

// --- command-line overrides -----------------------------------------------------------------

TEST(GasCaseOverrides, GasKeysCanBeSet) {
  const CaseSpec c = read_case_string(
      kBed2D, "case.toml",
      {"gas.viscosity=2e-5", "gas.solver.max_iterations=7", "gas.boundary.bottom.velocity=2.2",
       "gas.boundary.left.type=wall_free_slip", "coupling.drag=beetstra", "coupling.d_mean=0.002",
       "gas.cells=[15, 1, 50]"});
  ASSERT_TRUE(c.gas.has_value());
  EXPECT_EQ(c.gas->viscosity, 2e-5);
  EXPECT_EQ(c.gas->max_iterations, 7);
  EXPECT_EQ(c.gas->boundary[gas::bottom].inflow.velocity, 2.2);
  EXPECT_EQ(c.gas->boundary[gas::left].type, BoundaryType::wall_free_slip);
  EXPECT_EQ(c.gas->cells, (std::array<int, 3>{15, 1, 50}));
  EXPECT_EQ(c.coupling.drag, "beetstra");
  EXPECT_EQ(c.coupling.d_mean, 0.002);
  EXPECT_EQ(c.where("gas.boundary.bottom.velocity").file, "--set");
  EXPECT_EQ(c.where("gas.solver.max_iterations").file, "--set");
  EXPECT_EQ(c.where("gas.viscosity").file, "--set");
  EXPECT_EQ(c.where("gas.boundary.top.pressure").line, line_of(kBed2D, "[gas.boundary.top]") + 2);
}

TEST(GasCaseOverrides, ValidatedLikeTheFile) {
  // top = outflow now, so the file's top pressure no longer applies.
  std::string msg = error_of(kBed2D, {"gas.boundary.top.type=outflow"});
  EXPECT_EQ(msg, "case.toml:" + std::to_string(line_of(kBed2D, "[gas.boundary.top]") + 2) +
                     ":1: gas.boundary.top.pressure: not allowed with type = \"outflow\" (only "
                     "with type = \"pressure\")");
  msg = error_of(kBed2D, {"gas.viscosity=-1"});
  EXPECT_EQ(msg, "--set: gas.viscosity: must be >= 0 Pa s");
  msg = error_of(kBed2D, {"gas.boundary.botom.type=inflow"});
  EXPECT_EQ(msg, "--set: gas.boundary.botom.type: unknown key (did you mean "
                 "\"gas.boundary.bottom\"?)");
  msg = error_of(kBed2D, {"gas.solver.tolerence=1e-6"});
  EXPECT_EQ(msg, "--set: gas.solver.tolerence: unknown key (did you mean "
                 "\"gas.solver.tolerance\"?)");
  msg = error_of(kBed2D, {"gas.boundary.bottom.region[0].velocity=3"});
  EXPECT_EQ(msg, "--set: gas.boundary.bottom.region[0].velocity: gas.boundary.bottom.region is an "
                 "array of tables, which --set cannot change (edit the case file)");
  msg = error_of(kBed2D, {"output.probe=1"});
  EXPECT_EQ(msg.rfind("--set: output.probe: output.probe is an array of tables", 0), 0u) << msg;
  msg = error_of(kBed2D, {"gas.lo=[0, 0, 0]"});
  EXPECT_EQ(msg.rfind("--set: gas.lo: unknown key", 0), 0u) << msg;
  msg = error_of(kParticles2D, {"coupling.drag=ergun"});
  EXPECT_EQ(msg, "--set: coupling: not allowed without [gas] (allowed: [coupling] in a coupled "
                 "run, one with a [gas] table)");
}

} // namespace
} // namespace fluidem
