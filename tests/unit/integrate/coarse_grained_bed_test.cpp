// A coarse-grained packed bed carries the pressure drop of the real one [Chang08 eq. 2.31-2.32;
// Ergun 1952, Chem. Eng. Prog. 48:89; Hoomans96 eq. 45]:
//   -dp/dz - rho |g| = 150 mu (1-eps)^2 U / (eps^3 d1^2) + 1.75 rho (1-eps) U^2 / (eps^3 d1),
// with d1 the REAL particles' diameter. The bed of tests/unit/integrate/fixed_bed_ergun_test.cpp
// (a simple cubic lattice of fixed spheres of d1 = 1 mm in an 8 x 8 x 50 mm column, air at
// U = 0.5 m/s, drag "ergun", cell porosity, cells of 4 x 4 x 2 mm) built from parcels of W = 8
// real particles (d2 = 2 mm, 4 x 4 x 20 of them): every cell still holds whole lattice periods,
// so the cell porosity is 1 - pi/6 exactly (checked to 1e-12) and the pressure drop per height
// must be Ergun's at d1 within 1% (the tolerance of the real-particle test, from the solver's
// convergence: measured deviations ~1e-6). With drag_diameter = "parcel" the closure sees d2
// and the drop is Ergun's at d2 instead (1%): about 0.33 of the real one at this Reynolds
// number — the change the real diameter avoids (docs/coarse-graining.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

constexpr double kD1 = 1e-3, kRho = 1.2, kMu = 1.8e-5, kG = 9.81, kU = 0.5;

std::string bed_case(double w, const char* drag_diameter) {
  const double eps = 1.0 - std::numbers::pi / 6.0;
  const long count = std::lround(2560.0 / w);
  std::string t = fmt::format(R"(
[simulation]
end_time = 1.0
gravity = [0.0, 0.0, -{g}]
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.008, 0.008, 0.05]
[[species]]
name = "glass"
diameter = 0.001
density = 2500.0
[[insert]]
species = "glass"
count = {count}
placement = "lattice"
region = {{ hi = [0.008, 0.008, 0.04] }}
fixed = true
[gas]
cells = [2, 2, 25]
eos = "incompressible"
density = {rho}
viscosity = {mu}
[gas.solver]
tolerance = 1e-10
velocity_tolerance = 1e-9
max_iterations = 200
[gas.boundary.left]
type = "wall_free_slip"
[gas.boundary.right]
type = "wall_free_slip"
[gas.boundary.front]
type = "wall_free_slip"
[gas.boundary.back]
type = "wall_free_slip"
[gas.boundary.bottom]
type = "inflow"
velocity = {u}
porosity = {eps:.17g}
[gas.boundary.top]
type = "pressure"
[coupling]
drag = "ergun"
porosity = "cell"
)",
                              fmt::arg("g", kG), fmt::arg("rho", kRho), fmt::arg("mu", kMu),
                              fmt::arg("u", kU), fmt::arg("eps", eps), fmt::arg("count", count));
  if (w != 1.0)
    t += fmt::format("[coarse_graining]\nratio = {}\ndrag_diameter = \"{}\"\n", w, drag_diameter);
  return t;
}

double ergun(double d) {
  const double eps = 1.0 - std::numbers::pi / 6.0;
  return 150.0 * kMu * (1 - eps) * (1 - eps) * kU / (eps * eps * eps * d * d) +
         1.75 * kRho * (1 - eps) * kU * kU / (eps * eps * eps * d);
}

/// -dp/dz - rho g between the centres of cells 4 .. 16 after 300 flow steps, and the mean
/// porosity of those cells.
std::array<double, 2> frictional_drop(const std::string& text, std::size_t particles) {
  Simulation sim(read_case_string(text, "cg_bed.toml"));
  EXPECT_EQ(sim.particles().size(), particles);
  sim.advance(300);
  const gas::GasSolver& gs = sim.gas()->solver();
  const gas::GasGrid& g = gs.grid();
  double grad = 0.0, cell_eps = 0.0;
  int m = 0;
  for (int k = 4; k < 16; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i, ++m) {
        const auto q = static_cast<std::size_t>(g.idx(i, j, k));
        const auto up = static_cast<std::size_t>(g.idx(i, j, k + 1));
        grad += (gs.pressure()[up] - gs.pressure()[q]) / g.h[2];
        cell_eps += gs.porosity()[q];
      }
  return {-grad / m - kRho * kG, cell_eps / m};
}

TEST(CoarseGrainedBed, PressureDropPerHeightIsTheRealBedsErgun) {
  const double eps = 1.0 - std::numbers::pi / 6.0;
  const auto real = frictional_drop(bed_case(1.0, "real"), 2560);
  const auto parcels = frictional_drop(bed_case(8.0, "real"), 320);
  const auto coarse = frictional_drop(bed_case(8.0, "parcel"), 320);
  std::printf("-dp/dz - rho g: real particles %.6g Pa/m, parcels W = 8 %.6g Pa/m (Ergun at d1 "
              "%.6g); parcels seen at their own diameter %.6g Pa/m (Ergun at d2 %.6g)\n",
              real[0], parcels[0], ergun(kD1), coarse[0], ergun(2.0 * kD1));
  EXPECT_NEAR(parcels[1], eps, 1e-12);
  EXPECT_NEAR(real[0] / ergun(kD1), 1.0, 0.01);
  EXPECT_NEAR(parcels[0] / ergun(kD1), 1.0, 0.01);
  EXPECT_NEAR(parcels[0] / real[0], 1.0, 0.01);
  EXPECT_NEAR(coarse[0] / ergun(2.0 * kD1), 1.0, 0.01);
}

} // namespace
} // namespace fluidem
