// The drag of coarse-grained parcels in a polydisperse cell, the worked example of [Chang08
// §2.2.3, Fig. 2.11, eq. 2.31]: a control volume holds 8 large real particles (d = 2 mm) and 16
// small ones (1 mm); with W = 8 they are 1 large parcel (4 mm) and 2 small ones (2 mm). With
// coupling scheme 2 (the cell's drag shared by surface area [Chang08 eq. 2.11]) and the closure
// seeing the real particles' diameter (coupling.drag_diameter_factor = W^(-1/3), what
// [coarse_graining] drag_diameter = "real" sets):
//  - the cell's total drag is the real system's (same solids volume, same Sauter mean diameter
//    of the real particles, same slip), to 1e-12 relative (round-off of the sums);
//  - if it is 48 force units, each large real particle gets 4 and each small one 1, and the
//    large parcel gets 32 and each small parcel 8 [Chang08 Fig. 2.11]: exactly the represented
//    surface area over the cell's (eq. 2.31), to 1e-12.
#include "coupling/exchange.hpp"
#include <gtest/gtest.h>
#include <numeric>

using namespace fluidem;
using namespace fluidem::coupling;

namespace {

struct CellDrag {
  std::vector<double> drag_z; // per particle, N
  double total = 0.0;
};

CellDrag cell_drag(const std::vector<std::pair<double, int>>& diameters_counts, double factor) {
  gas::GasSettings s;
  s.cells = {3, 3, 3};
  s.hi = {0.03, 0.03, 0.03};
  s.eos = gas::EquationOfState::incompressible;
  gas::GasSolver gs(s);
  for (double& u : gs.velocity(2)) u = 0.8; // upward gas; the particles at rest
  ParticleStore p;
  long id = 0;
  for (const auto& [d, n] : diameters_counts)
    for (int k = 0; k < n; ++k, ++id) // all inside the central cell, [0.01, 0.02]^3
      p.add({0.0125 + 0.0002 * static_cast<double>(id), 0.015,
             0.0125 + 0.0003 * static_cast<double>(id % 7)},
            {0.0, 0.0, 0.0}, 0.5 * d, 2500.0, 0, id);
  CouplingSettings c;
  c.scheme = ExchangeScheme::scheme2;
  c.drag = "ergun_wen_yu";
  c.drag_diameter_factor = factor;
  validate(c, s);
  update_porosity(gs, p, c);
  ParticleGasForces f;
  compute_particle_forces(gs, p, c, f);
  CellDrag r;
  r.drag_z = f.drag_z;
  r.total = std::accumulate(f.drag_z.begin(), f.drag_z.end(), 0.0);
  return r;
}

} // namespace

TEST(CoarseGrainedDrag, Chang08WorkedExampleSharesByRepresentedSurfaceArea) {
  const CellDrag real = cell_drag({{0.002, 8}, {0.001, 16}}, 1.0);
  const CellDrag parcels = cell_drag({{0.004, 1}, {0.002, 2}}, 0.5);
  ASSERT_GT(real.total, 0.0);
  std::printf("cell drag: real particles %.12e N, parcels %.12e N\n", real.total, parcels.total);
  EXPECT_NEAR(parcels.total / real.total, 1.0, 1e-12);
  const double unit = real.total / 48.0; // one force unit of Fig. 2.11
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(real.drag_z[i] / unit, 4.0, 1e-12);
  for (int i = 8; i < 24; ++i) EXPECT_NEAR(real.drag_z[i] / unit, 1.0, 1e-12);
  EXPECT_NEAR(parcels.drag_z[0] / unit, 32.0, 1e-11);
  EXPECT_NEAR(parcels.drag_z[1] / unit, 8.0, 1e-11);
  EXPECT_NEAR(parcels.drag_z[2] / unit, 8.0, 1e-11);
  // With the parcels' own diameter the closure sees a coarser bed: the drag changes.
  const CellDrag coarse = cell_drag({{0.004, 1}, {0.002, 2}}, 1.0);
  std::printf("parcels' own diameter: %.12e N (x %.4f)\n", coarse.total, coarse.total / real.total);
  EXPECT_LT(coarse.total, 0.9 * real.total);
}
