// The particle -> gas sums of a distributed run (coupling/rank_sum.hpp, docs/parallel.md): each
// rank deposits its own particles in fixed point and the integers are summed over the ranks.
// Run by ctest under mpirun with 1, 2, 3 and 4 ranks. A gas grid periodic along x and y holds
// 200 random spheres and two placed ones: one centred where the four quadrants of the x-y plane
// meet (the corner of four ranks' parts when each rank takes the particles of one quadrant, as
// a 2 x 2 decomposition does) and one across the periodic corner of the domain. For every
// porosity method (cell, porous cube), exchange scheme (3: per particle; 2: cell averages) and
// gas model (A; B, whose buoyancy term the gas gets too):
//  - the porosity, the drag coefficient K, its velocity term and Model B's source on every face
//    equal, bit for bit, those of one process depositing all particles, and are the same on all
//    ranks; each rank's particles get the forces, bit for bit, one process gives them;
//  - solid volume is conserved: the porosity field holds sum_i pi d_i^3 / 6 to 1e-13 relative
//    (the cell method's volumes are exact, porosity.hpp; the fixed point's rounding is below
//    N max|part| 2^-62 per part, ~1e-17 of the total here);
//  - momentum exchange obeys Newton's third law across ranks: the gas's source summed over the
//    faces times V_cell plus the sum of all particles' drag (and Model B's buoyancy term) is 0
//    to 1e-10 of the sum of |drag| [Zhu07 §3.2] (as the one-process test periodic_coupling_test
//    asserts for one process).
// A control moves the corner sphere by 1e-9 m: the porosity must differ.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "coupling/exchange.hpp"
#include "integrate/rank_sum_of.hpp"

namespace fluidem {
namespace {
using namespace coupling;
constexpr double pi = 3.14159265358979323846;
constexpr double kLx = 0.03, kLy = 0.02, kLz = 0.04;

gas::GasSettings periodic_xy(gas::PressureModel model) {
  gas::GasSettings s;
  s.cells = {6, 4, 8};
  s.hi = {kLx, kLy, kLz};
  s.eos = gas::EquationOfState::incompressible;
  s.model = model;
  s.gravity = {0.5, -1.0, -9.81};
  for (int side = 0; side < 4; ++side) s.boundary[side].type = gas::BoundaryType::periodic;
  return s;
}

/// A smooth periodic gas velocity on every face, ghosts included.
void set_velocity(gas::GasSolver& gs) {
  const gas::GasGrid& g = gs.grid();
  for (int k = 0; k < g.padded[2]; ++k)
    for (int j = 0; j < g.padded[1]; ++j)
      for (int i = 0; i < g.padded[0]; ++i)
        for (int d = 0; d < 3; ++d) {
          const Vec3 x = g.face_centre(d, i, j, k);
          gs.velocity(d)[static_cast<std::size_t>(g.idx(i, j, k))] =
              std::sin(2.0 * pi * x[0] / kLx + d) * std::cos(70.0 * x[2]) +
              0.5 * std::sin(2.0 * pi * x[1] / kLy);
        }
}

ParticleStore all_particles(double nudge) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(0.0, kLx), uy(0.0, kLy), uz(0.006, 0.034),
      rad(0.0005, 0.001), vel(-1.0, 1.0);
  ParticleStore p;
  p.add({0.5 * kLx, 0.5 * kLy, 0.02}, {0.3, -0.2, 0.5}, 0.003, 2500.0, 0, 0);  // four ranks' corner
  p.add({0.0009, kLy - 0.0006, 0.015}, {-0.4, 0.1, 0.2}, 0.002, 2500.0, 0, 1); // periodic corner
  for (int n = 2; n < 202; ++n)
    p.add({ux(rng), uy(rng), uz(rng)}, {vel(rng), vel(rng), vel(rng)}, rad(rng), 2500.0, 0, n);
  p.x[0] += nudge; // (the corner sphere: it straddles cells, so its parts change)
  return p;
}

/// The particles of this rank: those whose centre is in quadrant q of the x-y plane, q mod P.
ParticleStore own(const ParticleStore& all, const Communicator& comm) {
  ParticleStore p;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const int q = int(all.x[i] >= 0.5 * kLx) + 2 * int(all.y[i] >= 0.5 * kLy);
    if (q % comm.size() == comm.rank())
      p.add(all.position(i), all.velocity(i), all.radius[i], 2500.0, 0, all.id[i]);
  }
  return p;
}

struct Deposited {
  std::vector<double> eps;
  std::array<std::vector<double>, 3> K, Kus, src, applied;
  ParticleGasForces f;
};

Deposited deposit(const ParticleStore& p, const CouplingSettings& c, gas::PressureModel model,
                  const RankSum& ranks) {
  gas::GasSolver gs(periodic_xy(model));
  set_velocity(gs);
  Deposited out;
  PorosityScratch scratch;
  update_porosity(gs, p, c, scratch, &ranks);
  compute_particle_forces(gs, p, c, out.f, &ranks);
  deposit_momentum_source(gs, p, out.f, &ranks);
  out.eps = gs.porosity();
  for (int d = 0; d < 3; ++d) {
    const auto ud = static_cast<std::size_t>(d);
    out.K[ud] = gs.drag_coefficient(d);
    out.Kus[ud] = gs.drag_velocity_term(d);
    out.src[ud] = gs.explicit_source(d);
    out.applied[ud] = gs.applied_source(d);
  }
  return out;
}

/// FNV-1a over the bytes of the fields.
std::uint64_t hash(const Deposited& r) {
  std::uint64_t h = 1469598103934665603ull;
  auto add = [&](const std::vector<double>& v) {
    const auto* b = reinterpret_cast<const unsigned char*>(v.data());
    for (std::size_t k = 0; k < v.size() * sizeof(double); ++k) h = (h ^ b[k]) * 1099511628211ull;
  };
  add(r.eps);
  for (int d = 0; d < 3; ++d) {
    add(r.K[static_cast<std::size_t>(d)]);
    add(r.Kus[static_cast<std::size_t>(d)]);
    add(r.src[static_cast<std::size_t>(d)]);
  }
  return h;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void check(PorosityMethod method, ExchangeScheme scheme, gas::PressureModel model) {
  const Communicator& world = Communicator::world();
  const RankSum ranks = rank_sum_of(world), alone = rank_sum_of(Communicator::self());
  const std::string what = "porosity " + std::to_string(int(method)) + ", scheme " +
                           std::to_string(int(scheme) + 1) + ", model " +
                           (model == gas::PressureModel::A ? "A" : "B");
  CouplingSettings c;
  c.porosity.method = method;
  c.porosity.cube_factor = 3.0;
  c.scheme = scheme;
  validate(c, periodic_xy(model));
  const ParticleStore all = all_particles(0.0);
  const ParticleStore mine = own(all, world);
  const Deposited one = deposit(all, c, model, alone); // one process, every particle
  const Deposited split = deposit(mine, c, model, ranks);
  EXPECT_TRUE(same_bits(split.eps, one.eps)) << what;
  for (std::size_t d = 0; d < 3; ++d) {
    EXPECT_TRUE(same_bits(split.K[d], one.K[d])) << what << ", K " << d;
    EXPECT_TRUE(same_bits(split.Kus[d], one.Kus[d])) << what << ", K u_s " << d;
    EXPECT_TRUE(same_bits(split.src[d], one.src[d])) << what << ", source " << d;
  }
  const double h = static_cast<double>(hash(split) >> 12); // (exact in a double)
  EXPECT_EQ(world.max(h), world.min(h)) << what << ": the ranks' fields differ";
  // This rank's particles get the forces one process gives them.
  for (std::size_t i = 0; i < mine.size(); ++i) {
    const auto k = static_cast<std::size_t>(mine.id[i]); // (all: id = index)
    EXPECT_EQ(split.f.drag_x[i], one.f.drag_x[k]) << what << ", particle " << k;
    EXPECT_EQ(split.f.drag_z[i], one.f.drag_z[k]) << what << ", particle " << k;
    EXPECT_EQ(split.f.pres_y[i], one.f.pres_y[k]) << what << ", particle " << k;
  }
  // Solid volume: the distributed field holds every particle's.
  gas::GasSolver gs(periodic_xy(model));
  const gas::GasGrid& g = gs.grid();
  double solid = 0.0, volume = 0.0;
  for (int k = 1; k <= g.n[2]; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i)
        solid += (1.0 - split.eps[static_cast<std::size_t>(g.idx(i, j, k))]) * g.cell_volume();
  for (std::size_t i = 0; i < all.size(); ++i)
    volume += pi * std::pow(2.0 * all.radius[i], 3) / 6.0;
  EXPECT_NEAR(solid / volume, 1.0, 1e-13) << what;
  // Newton's third law over all ranks' particles (their forces: one process's, asserted equal).
  const bool b = model == gas::PressureModel::B;
  for (std::size_t d = 0; d < 3; ++d) {
    const std::vector<double>& dr = d == 0 ? one.f.drag_x : (d == 1 ? one.f.drag_y : one.f.drag_z);
    const std::vector<double>& pr = d == 0 ? one.f.pres_x : (d == 1 ? one.f.pres_y : one.f.pres_z);
    double sum_p = 0.0, abs_p = 0.0, sum_g = 0.0;
    for (std::size_t i = 0; i < dr.size(); ++i) {
      sum_p += dr[i] + (b ? pr[i] : 0.0);
      abs_p += std::abs(dr[i] + (b ? pr[i] : 0.0));
    }
    for (double x : split.applied[d]) sum_g += x * g.cell_volume();
    EXPECT_LT(std::abs(sum_p + sum_g) / abs_p, 1e-10) << what << ", component " << d;
  }
}

TEST(FixedPointDeposition, RanksGiveTheSumsOfOneProcess) {
  for (PorosityMethod m : {PorosityMethod::cell, PorosityMethod::porous_cube})
    for (ExchangeScheme s : {ExchangeScheme::scheme3, ExchangeScheme::scheme2})
      for (gas::PressureModel model : {gas::PressureModel::A, gas::PressureModel::B})
        check(m, s, model);
}

TEST(FixedPointDeposition, AMovedParticleChangesThePorosity) {
  const Communicator& world = Communicator::world();
  CouplingSettings c;
  const Deposited a =
      deposit(own(all_particles(0.0), world), c, gas::PressureModel::A, rank_sum_of(world));
  const Deposited b =
      deposit(own(all_particles(1e-9), world), c, gas::PressureModel::A, rank_sum_of(world));
  EXPECT_FALSE(same_bits(a.eps, b.eps));
}

} // namespace
} // namespace fluidem
