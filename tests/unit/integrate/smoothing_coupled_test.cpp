// coupling.smoothing_length in the flow step (GasCoupling::step, coupling/smoothing.hpp).
//  (4) Off is today's step, bitwise: a GasCoupling without the key and one with
//      smoothing_length = 0 give, over three flow steps of 250 random particles in a 3-D bed
//      (inflow floor, pressure top, ergun_wen_yu), the same bits as the flow step written out
//      from the coupling functions (update_porosity, compute_particle_forces,
//      deposit_momentum_source, GasSolver::step, update_particle_forces: the sequence before the
//      key existed) on a solver of its own: porosity, gas velocity and pressure fields, force on
//      every particle.
//  On: the porosity differs from the unsmoothed one (the key acts), the solids volume
//      sum (1 - eps) V_cell is the unsmoothed one to 1e-13 relative, and the smallest porosity is
//      not below the unsmoothed smallest (a weighted mean).
//      Newton's third law in the coupled step (particles away from the side walls): the
//      particles' drag plus the gas's applied source, summed, 1e-10 relative.
//      coupling.mode = "frozen" with the key: the particle sees the prescribed linear field
//      exactly (1e-7 m/s, as coupling_modes_test): the velocity is smoothed only in two_way.
//  (6) Threads: the Hoomans96 bubble bed (2-D, 2400 hard spheres, 15 x 25 cells) with
//      smoothing_length = 15 mm, 20 flow steps on 1 and on 2 OpenMP threads: particle positions,
//      velocities, porosity and gas velocity bitwise the same (the smoothing is serial; the
//      particle loops are per-particle).
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>

#include "coupling/exchange.hpp"
#include "integrate/gas_coupling.hpp"
#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

std::string bed_case(const std::string& coupling_extra) {
  return "[simulation]\nend_time = 0.01\ntime_step = 1e-5\n"
         "[domain]\nlo = [0, 0, 0]\nhi = [0.04, 0.04, 0.08]\n"
         "[[species]]\nname = \"s\"\ndiameter = 0.002\ndensity = 2500\n"
         "[[insert]]\nspecies = \"s\"\ncount = 10\n"
         "[gas]\ncells = [4, 4, 8]\ntime_step = 1e-4\n"
         "[gas.boundary.bottom]\ntype = \"inflow\"\nvelocity = 0.8\n"
         "[gas.boundary.top]\ntype = \"pressure\"\npressure = 101325.0\n"
         "[coupling]\ndrag = \"ergun_wen_yu\"\n" +
         coupling_extra;
}

ParticleStore random_particles() {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> x(0.002, 0.038), z(0.002, 0.05), v(-0.5, 0.5);
  ParticleStore p;
  for (int n = 0; n < 250; ++n)
    p.add({x(rng), x(rng), z(rng)}, {v(rng), v(rng), v(rng)}, 0.001, 2500.0, 0, n);
  return p;
}

bool same(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](double x, double y) {
           return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y);
         });
}

constexpr double kDt = 1e-4;
constexpr int kSteps = 3;

TEST(SmoothingCoupled, OffIsTodaysStepBitwise) {
  const ParticleStore p = random_particles();
  const CaseSpec plain = read_case_string(bed_case(""), "case.toml");
  const CaseSpec zero = read_case_string(bed_case("smoothing_length = 0.0\n"), "case.toml");
  GasCoupling a(plain, p), b(zero, p);
  // The flow step as it was written before the key, from the coupling functions.
  gas::GasSolver gs(GasCoupling::complete_settings(plain));
  coupling::CouplingSettings c = plain.coupling;
  coupling::update_porosity(gs, p, c);
  gs.sync_old_porosity();
  coupling::ParticleGasForces f;
  f.resize(p.size());
  for (int s = 0; s < kSteps; ++s) {
    const double t = s * kDt;
    a.step(p, t, kDt);
    b.step(p, t, kDt);
    coupling::update_porosity(gs, p, c);
    coupling::compute_particle_forces(gs, p, c, f);
    coupling::deposit_momentum_source(gs, p, f);
    gs.step(t, kDt);
    coupling::update_particle_forces(gs, p, f);
  }
  for (const GasCoupling* g : {&a, &b}) {
    EXPECT_TRUE(same(g->solver().porosity(), gs.porosity()));
    EXPECT_TRUE(same(g->solver().pressure(), gs.pressure()));
    for (int d = 0; d < 3; ++d) EXPECT_TRUE(same(g->solver().velocity(d), gs.velocity(d))) << d;
    std::vector<double> fx(p.size()), fy(p.size()), fz(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      fx[i] = f.drag_x[i] + f.pres_x[i];
      fy[i] = f.drag_y[i] + f.pres_y[i];
      fz[i] = f.drag_z[i] + f.pres_z[i];
    }
    EXPECT_TRUE(same(g->force(0), fx));
    EXPECT_TRUE(same(g->force(1), fy));
    EXPECT_TRUE(same(g->force(2), fz));
  }
}

TEST(SmoothingCoupled, OnKeepsTheSolidsVolume) {
  const ParticleStore p = random_particles();
  GasCoupling off(read_case_string(bed_case(""), "case.toml"), p);
  GasCoupling on(read_case_string(bed_case("smoothing_length = 0.012\n"), "case.toml"), p);
  off.step(p, 0.0, kDt);
  on.step(p, 0.0, kDt);
  const gas::GasGrid& g = off.solver().grid();
  double s_off = 0.0, s_on = 0.0, min_off = 1.0, min_on = 1.0, diff = 0.0;
  for (int k = 1; k <= g.n[2]; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i) {
        const auto q = static_cast<std::size_t>(g.idx(i, j, k));
        const double e0 = off.solver().porosity()[q], e1 = on.solver().porosity()[q];
        s_off += 1.0 - e0;
        s_on += 1.0 - e1;
        min_off = std::min(min_off, e0);
        min_on = std::min(min_on, e1);
        diff = std::max(diff, std::abs(e1 - e0));
      }
  std::printf("solids volume fraction sum: off %.17g, on %.17g (rel. %.2e); min eps off %.6f, "
              "on %.6f; max |change| %.3e\n",
              s_off, s_on, std::abs(s_on - s_off) / s_off, min_off, min_on, diff);
  EXPECT_LT(std::abs(s_on - s_off) / s_off, 1e-13);
  EXPECT_GE(min_on, min_off);
  EXPECT_GT(diff, 1e-4);
}

TEST(SmoothingCoupled, OnKeepsNewtonsThirdLawInTheStep) {
  // Particles away from the side walls (their stencils on solved faces only, as in
  // newton_third_law_test): the drag the particles got after the gas step plus the source the
  // gas applied with its converged velocity, summed, vanish (GasCoupling::step reads the gas
  // velocity through the smoothing, smoothing.hpp).
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> x(0.011, 0.029), z(0.011, 0.06), v(-0.5, 0.5);
  ParticleStore p;
  for (int n = 0; n < 250; ++n)
    p.add({x(rng), x(rng), z(rng)}, {v(rng), v(rng), v(rng)}, 0.001, 2500.0, 0, n);
  GasCoupling on(read_case_string(bed_case("smoothing_length = 0.012\n"), "case.toml"), p);
  for (int s = 0; s < kSteps; ++s) on.step(p, s * kDt, kDt);
  const coupling::ParticleGasForces& f = on.exchange();
  const gas::GasGrid& g = on.solver().grid();
  for (int d = 0; d < 3; ++d) {
    const std::vector<double>& dr = d == 0 ? f.drag_x : (d == 1 ? f.drag_y : f.drag_z);
    double sum_p = 0.0, abs_p = 0.0, sum_g = 0.0;
    for (double q : dr) {
      sum_p += q;
      abs_p += std::abs(q);
    }
    for (double q : on.solver().applied_source(d)) sum_g += q * g.cell_volume();
    std::printf("component %d: particles %.6e N, gas %.6e N, rel. imbalance %.2e\n", d, sum_p,
                sum_g, std::abs(sum_p + sum_g) / abs_p);
    EXPECT_LT(std::abs(sum_p + sum_g) / abs_p, 1e-10);
  }
}

TEST(SmoothingCoupled, FrozenFieldIsNotSmoothed) {
  // coupling.mode = "frozen" (no source to the gas, nothing to balance): the particle sees the
  // prescribed linear field u = (1e-3 + 0.5 z, 2e-3 - 0.3 x, 0) exactly, as without the key
  // (coupling_modes_test), although the smoothing is on (10 mm on 5 mm cells; smoothing this
  // field with zero flux at the walls changes what it sees by 3.7e-4 m/s: checked by hand).
  const std::string text = "[simulation]\nend_time = 1.0\ngravity = [0.0, 0.0, -9.81]\n"
                           "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.02, 0.02, 0.02]\n"
                           "[[species]]\nname = \"s\"\ndiameter = 0.0002\ndensity = 2500\n"
                           "[[insert]]\nspecies = \"s\"\ncount = 1\n"
                           "[gas]\ncells = [4, 4, 4]\neos = \"incompressible\"\ndensity = 1000.0\n"
                           "viscosity = 1e-3\n[coupling]\nmode = \"frozen\"\ndrag = \"wen_yu\"\n"
                           "frozen_velocity = [1e-3, 2e-3, 0.0]\n"
                           "frozen_velocity_gradient = [0, 0, 0.5, -0.3, 0, 0, 0, 0, 0]\n"
                           "smoothing_length = 0.01\n";
  Simulation sim(read_case_string(text, "case.toml"));
  ParticleStore& p = sim.particles();
  p.x[0] = 0.0091, p.y[0] = 0.0113, p.z[0] = 0.0087;
  sim.advance(10);
  const coupling::ParticleGasForces& f = sim.gas()->exchange();
  EXPECT_NEAR(f.ux[0], 1e-3 + 0.5 * p.z[0], 1e-7);
  EXPECT_NEAR(f.uy[0], 2e-3 - 0.3 * p.x[0], 1e-7);
  EXPECT_NEAR(f.uz[0], 0.0, 1e-15);
}

struct Snapshot {
  std::vector<double> x, z, vx, vz, eps, ux, uz;
};

Snapshot bubble_bed(int threads) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  Simulation sim(
      read_case_file(std::string(FLUIDEM_SOURCE_DIR) + "/cases/hoomans96/bubble_orifice.toml",
                     {"coupling.smoothing_length=0.015"}));
  sim.advance(20);
  omp_set_num_threads(saved);
  const ParticleStore& p = sim.particles();
  const gas::GasSolver& gs = sim.gas()->solver();
  return {p.x, p.z, p.vx, p.vz, gs.porosity(), gs.velocity(0), gs.velocity(2)};
}

TEST(SmoothingCoupled, SameBitsOnOneAndTwoThreads) {
  const Snapshot a = bubble_bed(1), b = bubble_bed(2);
  EXPECT_TRUE(same(a.x, b.x));
  EXPECT_TRUE(same(a.z, b.z));
  EXPECT_TRUE(same(a.vx, b.vx));
  EXPECT_TRUE(same(a.vz, b.vz));
  EXPECT_TRUE(same(a.eps, b.eps));
  EXPECT_TRUE(same(a.ux, b.ux));
  EXPECT_TRUE(same(a.uz, b.uz));
}

} // namespace
} // namespace fluidem
