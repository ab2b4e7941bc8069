// coupling.hold_gas_at_rest (integrate/gas_coupling.cpp): one 5 mm sphere (2700 kg/m3) launched at
// 5 cm/s along x through water at rest (1000 kg/m3, 1.78e-3 Pa s) in a fully periodic 40 mm box,
// 4 x 4 x 4 cells, hard-sphere engine, no gravity, 0.5 s (about 2 drag relaxation times).
// Reference: momentum balance. Without the key nothing acts on particle + water from outside, so
// their total x momentum stays at m v0 (to 1%: the coupling's third law holds to round-off, but
// the water's momentum is measured here with face averages of eps rho, and the moving porosity
// field carries some; measured 0.9967); the water moves (63% of the momentum at 0.5 s). With it the
// water's mean momentum is removed every step (what is left after a step is that step's own
// transfer, < 1e-2 of m v0), and the particle loses more speed than without (it cannot carry the
// water along).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrate/gas_coupling.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

struct Result {
  double particle = 0.0, gas = 0.0, m_v0 = 0.0, v = 0.0;
};

Result run(bool hold) {
  const std::string text =
      std::string("[simulation]\nengine = \"hard_sphere\"\nend_time = 0.5\ntime_step = 1e-3\n"
                  "gravity = [0.0, 0.0, 0.0]\n"
                  "[domain]\nlo = [0, 0, 0]\nhi = [0.04, 0.04, 0.04]\n"
                  "periodic = [true, true, true]\n"
                  "[[species]]\nname = \"s\"\ndiameter = 0.005\ndensity = 2700\n"
                  "[[insert]]\nspecies = \"s\"\ncount = 1\n"
                  "[gas]\ncells = [4, 4, 4]\neos = \"incompressible\"\ndensity = 1000.0\n"
                  "viscosity = 0.00178\n[coupling]\ndrag = \"wen_yu\"\nhold_gas_at_rest = ") +
      (hold ? "true" : "false") + "\n";
  Simulation sim(read_case_string(text, "case.toml"));
  ParticleStore& p = sim.particles();
  p.x[0] = 0.0213, p.y[0] = 0.0187, p.z[0] = 0.0201;
  p.vx[0] = 0.05, p.vy[0] = p.vz[0] = 0.0;
  Result r;
  r.m_v0 = p.mass[0] * 0.05;
  sim.advance(500);
  const gas::GasSolver& gs = sim.gas()->solver();
  const gas::GasGrid& g = gs.grid();
  const std::vector<double>& u = gs.velocity(0);
  const std::vector<double>& eps = gs.porosity();
  const std::vector<double>& rho = gs.density();
  for (int k = 1; k <= g.n[2]; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i) { // faces 1..n along x: the solved ones
        const auto q = static_cast<std::size_t>(g.idx(i, j, k));
        const auto up = static_cast<std::size_t>(g.idx(i + 1, j, k));
        r.gas += 0.5 * (eps[q] * rho[q] + eps[up] * rho[up]) * u[q] * g.cell_volume();
      }
  r.particle = p.mass[0] * p.vx[0];
  r.v = p.vx[0];
  return r;
}

TEST(HoldGasAtRest, MomentumLeavesThroughTheWater) {
  const Result free = run(false), held = run(true);
  std::printf("free: particle %.4g, water %.4g, sum/m v0 = %.6f; held: particle %.4g, water %.4g "
              "(m v0 = %.4g kg m/s)\n",
              free.particle, free.gas, (free.particle + free.gas) / free.m_v0, held.particle,
              held.gas, held.m_v0);
  EXPECT_NEAR((free.particle + free.gas) / free.m_v0, 1.0, 1e-2);
  EXPECT_GT(free.gas, 0.05 * free.m_v0); // the water was set moving
  EXPECT_LT(std::abs(held.gas), 1e-2 * held.m_v0);
  EXPECT_LT(held.v, free.v);
  EXPECT_GT(held.v, 0.0);
}

} // namespace
} // namespace fluidem
