// A packed bed of fixed particles in a coupled run against the Ergun equation [Ergun 1952, Chem.
// Eng. Prog. 48:89; Hoomans96 eq. 45; Deen07 eq. 3]:
//   -dp/dz - rho |g| = 150 mu (1-eps)^2 U / (eps^3 d^2) + 1.75 rho (1-eps) U^2 / (eps^3 d).
// The bed is made as a user makes one: `[[insert]] fixed = true`, a simple cubic lattice of
// 2560 spheres of d = 1 mm (8 x 8 across, 40 layers, touching the side walls and the floor), in a
// column of 8 x 8 x 50 mm with gravity (the particles would fall and the drag would lift them:
// they must stay put, bit for bit). Air (incompressible, rho = 1.2 kg/m3, mu = 1.8e-5 Pa s) enters
// at the bottom at U = 0.2, 0.5 and 1.0 m/s (particle Reynolds numbers 13, 33, 67: both Ergun
// terms matter), pressure at the top, free-slip sides; drag = "ergun", cell porosity, Model A;
// 300 flow steps of 1e-4 s (the flow is steady: the gradient changes by less than 1e-6 over the
// last 50 steps).
// Reference porosity, from the geometry alone: eps = 1 - (pi/6) d^3 / d^3 = 1 - pi/6 = 0.4764.
// Tolerance 1%, from the porosity mapping: the cells are 4 d x 4 d x 2 d, so every cell of the
// bed holds whole lattice periods and the cell porosity [Deen07 eq. 33] is 1 - pi/6 exactly (to
// round-off; checked to 1e-12); the superficial velocity is U in every layer (continuity), so
// the drag per bed volume is Ergun's at the geometric porosity, and at steady state in Model A it
// balances -dp/dz - rho |g| [Zhu07 eq. 5]. What is left is the solver's convergence
// (gas.solver tolerances 1e-10 / 1e-9 m/s: measured deviations ~1e-6). (A random bed would have
// a cell-porosity scatter of several percent at these cell sizes, and the pressure drop varies
// as -10 x the porosity's relative change at eps = 0.48: it could not be held to 1% without
// averaging over many realisations.) Measured in the middle of the bed, between the centres of
// cells 4 .. 16 of 20 (away from the inflow and the bed surface).
// Also: the gas force on the particles of those cells (what they feel, though they cannot move)
// per bed volume equals the pressure drop less the weight of the gas in the pores,
// -dp/dz - eps rho |g| (the Model A balance, tests/unit/coupling/packed_bed_test.cpp), 1%.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

#include "../../common/bed_gradient.hpp"

namespace fluidem {
namespace {

constexpr double kD = 1e-3, kRho = 1.2, kMu = 1.8e-5, kG = 9.81;

/// `extra`: appended to the case ([coarse_graining]); `count`: the lattice's particles.
std::string bed_case(double u, int cells_z = 25, long count = 2560, const std::string& extra = "") {
  const double eps = 1.0 - std::numbers::pi / 6.0;
  return fmt::format(R"(
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
cells = [2, 2, {nz}]
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
                     fmt::arg("u", u), fmt::arg("eps", eps), fmt::arg("nz", cells_z),
                     fmt::arg("count", count)) +
         extra;
}

/// -dp/dz and the porosity over the middle of the bed, cell layers k = 4..15.
std::array<double, 2> bed_gradient(const gas::GasSolver& gs) {
  return test::band_pressure_gradient(gs, 4, 16);
}

TEST(FixedBed, PressureDropIsErguns) {
  const double eps = 1.0 - std::numbers::pi / 6.0;
  for (const double u : {0.2, 0.5, 1.0}) {
    Simulation sim(read_case_string(bed_case(u), "ergun.toml"));
    const ParticleStore& p = sim.particles();
    ASSERT_EQ(p.size(), 2560u);
    const ParticleStore before = p;
    ASSERT_NEAR(sim.time_step(), 1e-4, 1e-12); // every particle fixed: the flow step
    const gas::GasSolver& gs = sim.gas()->solver();
    const gas::GasGrid& g = gs.grid();
    const auto gradient = [&] { return bed_gradient(gs); };
    sim.advance(250);
    const double early = gradient()[0];
    sim.advance(50);
    const auto [drop, cell_eps] = gradient();
    const double ergun = 150.0 * kMu * (1 - eps) * (1 - eps) * u / (eps * eps * eps * kD * kD) +
                         1.75 * kRho * (1 - eps) * u * u / (eps * eps * eps * kD);
    const double frictional = drop - kRho * kG;
    // The gas force on the particles of cells 4..15 (centres in z = 6..30 mm) per bed volume.
    double fz = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.z[i] > 3 * g.h[2] && p.z[i] < 15 * g.h[2]) fz += sim.gas()->force(2)[i];
    const double per_volume = fz / (12 * g.h[2] * 0.008 * 0.008);
    const double balance = drop - eps * kRho * kG;
    std::printf("U = %.1f m/s: cell porosity %.12f (1 - pi/6 = %.12f); -dp/dz - rho g = %.6g "
                "Pa/m, Ergun %.6g Pa/m, ratio %.6f (change over the last 50 steps %.1e); gas force "
                "on the particles %.6g N/m^3, -dp/dz - eps rho g %.6g (ratio %.6f)\n",
                u, cell_eps, eps, frictional, ergun, frictional / ergun, drop / early - 1.0,
                per_volume, balance, per_volume / balance);
    EXPECT_NEAR(cell_eps, eps, 1e-12);
    EXPECT_NEAR(frictional / ergun, 1.0, 0.01);
    EXPECT_NEAR(drop / early, 1.0, 1e-6); // steady
    EXPECT_NEAR(per_volume / balance, 1.0, 0.01);
    // The particles felt the drag (and gravity), and did not move.
    EXPECT_TRUE(p.x == before.x && p.y == before.y && p.z == before.z);
    EXPECT_TRUE(p.vx == before.vx && p.vy == before.vy && p.vz == before.vz);
  }
}

// The pressure drop the run reports (`pressure_drop` in series.csv: inflow face to outflow face)
// is the momentum balance of all the gas of the column [Zhu07 eq. 5, summed over the cells]: at
// steady state, with free-slip side walls, Delta p A = sum over the particles of the gas force
// on them (drag and pressure force; Newton's third law) + the weight of the gas in the pores.
// Before issue 32 item 22 the inflow ghost cell copied the first cell's pressure, so the half
// cell above the distributor carried no gradient and the drop was read from the first cell
// centre: 0.866, 0.934, 0.973, 0.986 of the balance at cells of 10, 5, 2, 1 mm (printed below as
// "first cell centre"; it read 0.968 of a fluidised bed's weight with 1 cm cells). Measured now:
// 0.9993, 0.9986, 0.9986, 0.9986 (a residual of 0.33 Pa, the size of the gas weight in the
// column, 0.34 Pa, not explained yet). Tolerance 0.5%, at cell sizes of one to ten particle
// layers; the issue asks for 1%.
TEST(FixedBed, PressureDropBalancesTheGasForceOnTheParticlesAtAnyCellSize) {
  for (const int nz : {5, 10, 25, 50}) {
    Simulation sim(read_case_string(bed_case(0.5, nz), "ergun.toml"));
    sim.advance(300);
    const ParticleStore& p = sim.particles();
    const gas::GasSolver& gs = sim.gas()->solver();
    const gas::GasGrid& g = gs.grid();
    double fz = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) fz += sim.gas()->force(2)[i];
    double gas_weight = 0.0;
    for (int k = 1; k <= g.n[2]; ++k)
      for (int j = 1; j <= g.n[1]; ++j)
        for (int i = 1; i <= g.n[0]; ++i)
          gas_weight += gs.porosity()[static_cast<std::size_t>(g.idx(i, j, k))] * kRho * kG *
                        g.h[0] * g.h[1] * g.h[2];
    const double area = 0.008 * 0.008;
    const double expected = (fz + gas_weight) / area;
    const double drop = sim.gas()->pressure_drop();
    // What the run reported before: the first cell centre's pressure for the inflow face's.
    double p1 = 0.0, p0 = 0.0;
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i) {
        p1 += gs.pressure()[static_cast<std::size_t>(g.idx(i, j, 1))] / (g.n[0] * g.n[1]);
        p0 += gs.pressure()[static_cast<std::size_t>(g.idx(i, j, 0))] / (g.n[0] * g.n[1]);
      }
    const double old_drop = drop - (0.5 * (p0 + p1) - p1);
    std::printf("  first cell centre to the top: %.6g Pa, ratio %.6f\n", old_drop,
                old_drop / expected);
    std::printf("cells of %.0f mm: pressure drop %.6g Pa, gas force on the particles + gas weight "
                "%.6g Pa, ratio %.6f\n",
                g.h[2] * 1e3, drop, expected, drop / expected);
    EXPECT_NEAR(drop / expected, 1.0, 5e-3) << "cells of " << g.h[2] << " m";
  }
}

// A coarse-grained bed carries the pressure drop of the real one [Chang08 eq. 2.31-2.32]: the
// same lattice built from parcels of W = 8 real particles (d2 = 2 mm, 4 x 4 x 20 of them): every
// cell still holds whole lattice periods, so the cell porosity is 1 - pi/6 exactly (1e-12), and
// -dp/dz - rho g must be Ergun's at the REAL diameter d1 = 1 mm within the 1% above. With
// drag_diameter = "parcel" the closure sees d2 and the drop is Ergun's at d2 instead (1%): about
// 0.36 of the real one at U = 0.5 m/s (docs/coarse-graining.md).
TEST(FixedBed, CoarseGrainedBedCarriesTheRealBedsPressureDrop) {
  const double eps = 1.0 - std::numbers::pi / 6.0, u = 0.5;
  const auto ergun = [&](double d) {
    return 150.0 * kMu * (1 - eps) * (1 - eps) * u / (eps * eps * eps * d * d) +
           1.75 * kRho * (1 - eps) * u * u / (eps * eps * eps * d);
  };
  // -dp/dz - rho g between the centres of cells 4 .. 16 after 300 flow steps; their porosity.
  const auto frictional_drop = [&](const char* drag_diameter) {
    Simulation sim(read_case_string(
        bed_case(
            u, 25, 320,
            fmt::format("[coarse_graining]\nratio = 8\ndrag_diameter = \"{}\"\n", drag_diameter)),
        "cg_bed.toml"));
    EXPECT_EQ(sim.particles().size(), 320u);
    EXPECT_EQ(sim.particles().radius[0], kD); // parcels of twice the real diameter
    sim.advance(300);
    const auto [drop, cell_eps] = bed_gradient(sim.gas()->solver());
    return std::array<double, 2>{drop - kRho * kG, cell_eps};
  };
  const auto real = frictional_drop("real");
  const auto coarse = frictional_drop("parcel");
  std::printf("parcels W = 8: -dp/dz - rho g = %.6g Pa/m (Ergun at d1 %.6g); seen at their own "
              "diameter %.6g Pa/m (Ergun at d2 %.6g)\n",
              real[0], ergun(kD), coarse[0], ergun(2.0 * kD));
  EXPECT_NEAR(real[1], eps, 1e-12);
  EXPECT_NEAR(real[0] / ergun(kD), 1.0, 0.01);
  EXPECT_NEAR(coarse[0] / ergun(2.0 * kD), 1.0, 0.01);
}

} // namespace
} // namespace fluidem
