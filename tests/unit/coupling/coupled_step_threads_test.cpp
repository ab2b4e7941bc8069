// One coupled flow step as GasCoupling::step does it (integrate/gas_coupling.cpp): porosity by
// cell, gas -> particle forces, deposit, gas step, forces after the gas step; five steps with
// the particles moved in between, for the Tsuji grid in 2-D (15 x 1 x 25 cells, discs) and in
// 3-D (the same box one cell deep, spheres), 5000 particles of 2 mm (above the threshold of the
// threaded particle loops, core/parallel.hpp kThreadedParticles), the ergun_wen_yu closure.
//  - Thread independence: porosity, gas velocity and pressure, and the particle forces are
//    bitwise identical with 1 and 2 OpenMP threads.
//  - The per-step stencil cache (ParticleGasForces::face_stencils, the compact stencils of
//    trilinear.hpp):
//    the gas velocity and pressure gradient at each particle after the gas step are bitwise
//    those of gas_velocity_at and pressure_gradient_at (interpolation.hpp), which build each
//    component's stencil anew with face_stencil.
//  - The shared-corner porosity (porosity.cpp): the solid fraction of every cell agrees with
//    the per-cell closed forms sphere_box_volume / disc_rect_area (each cell's 8 / 4 corners
//    evaluated on their own, the method before the corners were shared) to 1e-14 absolute;
//    in 2-D this covers the shortcuts for a disc across one face (one segment for both parts)
//    and across one face along x and one along z (one quadrant and two segments).
#include "core/parallel.hpp"
#include "coupling/exchange.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>
#include <numbers>
#include <omp.h>
#include <random>

using namespace fluidem;
using namespace fluidem::coupling;

namespace {

gas::GasSettings tsuji(int dim) {
  gas::GasSettings s;
  s.dimension = dim;
  s.cells = {15, 1, 25};
  s.lo = {0.0, 0.0, 0.0};
  s.hi = {0.15, 0.004, 0.5};
  s.depth = 0.004;
  s.gravity = {0.0, 0.0, -9.81};
  for (auto& b : s.boundary) b.type = gas::BoundaryType::wall_no_slip;
  s.boundary[gas::bottom].type = gas::BoundaryType::inflow;
  s.boundary[gas::bottom].inflow.velocity = 2.6;
  s.boundary[gas::bottom].porosity = 0.4;
  s.boundary[gas::top].type = gas::BoundaryType::pressure;
  return s;
}

ParticleStore particles(unsigned seed) {
  // Random discs / spheres of 2 mm below 0.45 m (mean area fraction 0.24, volume fraction 0.08:
  // no cell fills up), more than core/parallel.hpp's kThreadedParticles.
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(0.002, 0.148), z(0.002, 0.448), v(-0.3, 0.3);
  ParticleStore p;
  for (int n = 0; n < 5000; ++n)
    p.add({x(rng), 0.002, z(rng)}, {v(rng), 0.0, v(rng)}, 0.001, 2700.0, 0, n);
  EXPECT_GT(p.size(), kThreadedParticles);
  return p;
}

struct Result {
  std::vector<double> eps, u, w, pr, fx, fz;
  long mismatches = 0; ///< particles whose cached-stencil values differ from fresh stencils
};

bool same(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

Result run(int dim, int threads) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  gas::GasSolver gs(tsuji(dim));
  ParticleStore p = particles(3u);
  CouplingSettings c; // porosity by cell, ergun_wen_yu, scheme 3
  ParticleGasForces f;
  PorosityScratch scratch;
  long mismatches = 0;
  update_porosity(gs, p, c, scratch);
  gs.sync_old_porosity();
  const double dt = 1e-4;
  for (int step = 0; step < 5; ++step) {
    update_porosity(gs, p, c, scratch);
    compute_particle_forces(gs, p, c, f);
    deposit_momentum_source(gs, p, f);
    gs.step(step * dt, dt);
    update_particle_forces(gs, p, f);
    // The cached stencils give what fresh ones give.
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec3 u = gas_velocity_at(gs, p.position(i)),
                 gp = pressure_gradient_at(gs, p.position(i));
      const double vol = std::numbers::pi * 0.002 * 0.002 * 0.002 / 6.0; // d = 2 mm
      if (u[0] != f.ux[i] || u[2] != f.uz[i] || -gp[2] * vol != f.pres_z[i]) ++mismatches;
    }
    for (std::size_t i = 0; i < p.size(); ++i) { // move (stay inside the box)
      p.x[i] = std::clamp(p.x[i] + 20.0 * dt * p.vx[i], 0.002, 0.148);
      p.z[i] = std::clamp(p.z[i] + 20.0 * dt * p.vz[i], 0.002, 0.448);
    }
  }
  omp_set_num_threads(before);
  return {gs.porosity(), gs.velocity(0), gs.velocity(2), gs.pressure(),
          f.drag_x,      f.drag_z,       mismatches};
}

} // namespace

TEST(CoupledStep, BitwiseIndependentOfThreadCount) {
  for (int dim : {2, 3}) {
    const Result one = run(dim, 1), two = run(dim, 2);
    EXPECT_TRUE(same(one.eps, two.eps)) << dim;
    EXPECT_TRUE(same(one.u, two.u)) << dim;
    EXPECT_TRUE(same(one.w, two.w)) << dim;
    EXPECT_TRUE(same(one.pr, two.pr)) << dim;
    EXPECT_TRUE(same(one.fx, two.fx)) << dim;
    EXPECT_TRUE(same(one.fz, two.fz)) << dim;
    EXPECT_EQ(one.mismatches, 0) << dim;
    EXPECT_EQ(two.mismatches, 0) << dim;
    double fz = 0.0;
    for (double v : one.fz) fz += v;
    EXPECT_GT(fz, 0.0) << "the gas lifts the particles";
  }
}

TEST(CoupledStep, SharedCornerPorosityMatchesPerCellClosedForms) {
  for (int dim : {2, 3}) {
    const gas::GasSolver gs(tsuji(dim));
    const gas::GasGrid& g = gs.grid();
    ParticleStore p = particles(5u);
    if (dim == 3) // spheres off the mid-plane too, cut by the y walls
      for (std::size_t i = 0; i < p.size(); ++i)
        p.y[i] = 0.0015 + 0.0005 * static_cast<double>(i % 3);
    std::vector<double> frac;
    solid_fraction(g, p, {}, frac);
    std::vector<double> ref(g.size(), 0.0);
    const double measure = dim == 2 ? g.h[0] * g.h[2] : g.cell_volume();
    for (std::size_t n = 0; n < p.size(); ++n) {
      const Vec3 x = p.position(n);
      const double R = p.radius[n];
      for (int k = 1; k <= g.n[2]; ++k)
        for (int j = 1; j <= g.n[1]; ++j)
          for (int i = 1; i <= g.n[0]; ++i) {
            const std::array<double, 3> lo{g.lo[0] + (i - 1) * g.h[0], g.lo[1] + (j - 1) * g.h[1],
                                           g.lo[2] + (k - 1) * g.h[2]};
            const std::array<double, 3> hi{lo[0] + g.h[0], lo[1] + g.h[1], lo[2] + g.h[2]};
            const double v = dim == 2 ? disc_rect_area(x[0], x[2], R, lo[0], hi[0], lo[2], hi[2])
                                      : sphere_box_volume(x, R, lo, hi);
            ref[static_cast<std::size_t>(g.idx(i, j, k))] += v / measure;
          }
    }
    double worst = 0.0, total = 0.0;
    for (std::size_t q = 0; q < ref.size(); ++q) {
      worst = std::max(worst, std::abs(frac[q] - ref[q]));
      total += frac[q];
    }
    std::printf("dim %d: max |solid fraction - per-cell closed form| = %.2e\n", dim, worst);
    EXPECT_LT(worst, 1e-14) << dim;
    EXPECT_GT(total, 1.0) << dim;
  }
}
