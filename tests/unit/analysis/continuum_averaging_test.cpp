// Discrete-to-continuum averaging (analysis/continuum_averaging.hpp) [Zhu07 Tables 5-6] against
// independent references:
//  (a) a periodic simple-cubic lattice of spheres (diameter d, centre spacing a = d - delta)
//      under uniform compression, every contact a linear spring F = k delta. Per particle the
//      two contacts along x give f_x l_x = 2 (-F)(a/2) and there is one particle per a^3, so
//      T_xx = T_yy = T_zz = -F / a^2 (compression negative), off-diagonals 0; phi = pi d^3 /
//      (6 a^3). A rolling torque t on every x bond adds M_zx = t / a^2. Tolerance 1e-12
//      relative (round-off), both methods: the volume cells hold whole numbers of lattice
//      cells; the weighted method (Gaussian w = 1.5 a, cutoff 9 w) sums a smooth weight over
//      a lattice, exact up to exp(-2 pi^2 w^2 / a^2) ~ 1e-19 and the truncated tail exp(-40).
//  (c) kinetic stress of particles with prescribed random velocities (two sizes, one
//      density), over two steps: equals -rho_s phi <v'v'> (volume) and -sum_i h_i m_i v'v'
//      with u = sum h m v / sum h m (weighted), both computed directly here with the mean over
//      both steps; tolerance 1e-12 relative to the largest component.
//  (d) sum over cells of phi V = the particle volume: volume method 1e-13 relative; weighted
//      (periodic box, w = cell size, cutoff 3 w) within 1e-3: the quadrature of the truncated
//      Gaussian on the cell centres (its jump at 3 w is 1.1% of its peak).
//  (e) both methods give bitwise equal fields with 1 and 2 OpenMP threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

#include "analysis/continuum_averaging.hpp"

namespace fluidem {
namespace {

struct Lattice {
  ParticleStore p;
  std::vector<ContactSample> contacts;
  double a = 0.0, force = 0.0;
  ContinuumGrid grid;
};

// n^3 spheres of diameter d at spacing a = d - delta in a periodic box [0, n a)^3; every
// nearest-neighbour pair (across the periodic faces too) a contact with force F; x bonds carry
// the rolling torque (0, 0, t) on i.
Lattice compressed_lattice(int n, double d, double delta, double k, double t, int cells) {
  Lattice L;
  L.a = d - delta;
  L.force = k * delta;
  const double r = 0.5 * d;
  const auto index = [n](int i, int j, int l) {
    return ((i + n) % n) + n * (((j + n) % n) + n * ((l + n) % n));
  };
  for (int l = 0; l < n; ++l)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        L.p.add({(i + 0.5) * L.a, (j + 0.5) * L.a, (l + 0.5) * L.a}, {0, 0, 0}, r, 2500.0, 0,
                index(i, j, l));
  for (int l = 0; l < n; ++l)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int axis = 0; axis < 3; ++axis) {
          const int o[3] = {axis == 0, axis == 1, axis == 2};
          ContactSample c;
          c.i = index(i, j, l);
          c.j = index(i + o[0], j + o[1], l + o[2]);
          c.id_i = c.i;
          c.id_j = c.j;
          c.overlap = delta;
          c.normal = {double(o[0]), double(o[1]), double(o[2])};
          c.force = -L.force * c.normal;
          c.torque_roll = axis == 0 ? Vec3{0, 0, t} : Vec3{0, 0, 0};
          c.contact_point =
              L.p.position(static_cast<std::size_t>(c.i)) + (r - 0.5 * delta) * c.normal;
          L.contacts.push_back(c);
        }
  L.grid.cells = {cells, cells, cells};
  L.grid.spacing = {n * L.a / cells, n * L.a / cells, n * L.a / cells};
  L.grid.periodic = {true, true, true};
  return L;
}

TEST(ContinuumAveraging, CompressedSimpleCubicLatticeGivesTheAnalyticStress) {
  const double d = 0.004, delta = 4e-5, k = 1e4, t = 3e-6;
  const Lattice L = compressed_lattice(28, d, delta, k, t, 4); // cells of 7 x 7 x 7 particles
  const double sxx = -L.force / (L.a * L.a);
  const double mzx = t / (L.a * L.a);
  const double phi = std::numbers::pi * d * d * d / (6.0 * L.a * L.a * L.a);
  for (auto method : {AveragingMethod::Volume, AveragingMethod::Weighted}) {
    ContinuumSettings s;
    s.method = method;
    s.width = 1.5 * L.a;
    s.cutoff = 9.0;
    ContinuumAverager avg(L.grid, s);
    avg.accumulate(L.p, L.contacts);
    const ContinuumFields f = avg.result();
    double worst = 0.0;
    for (std::size_t c = 0; c < L.grid.size(); ++c) {
      EXPECT_NEAR(f.solid_fraction[c], phi, 1e-12 * phi);
      for (int ab = 0; ab < 9; ++ab) {
        const double expect = (ab % 4 == 0) ? sxx : 0.0;
        const double got = f.contact_stress[static_cast<std::size_t>(ab)][c];
        EXPECT_NEAR(got, expect, 1e-12 * std::abs(sxx)) << "component " << ab << " cell " << c;
        worst = std::max(worst, std::abs(got - expect) / std::abs(sxx));
        EXPECT_EQ(f.kinetic_stress[static_cast<std::size_t>(ab)][c], 0.0);
        const double m_expect = ab == 6 ? mzx : 0.0; // M_zx
        EXPECT_NEAR(f.couple_stress[static_cast<std::size_t>(ab)][c], m_expect, 1e-12 * mzx)
            << "couple component " << ab;
      }
    }
    std::printf("[ measured ] %s: sigma_xx = %.15g Pa (analytic %.15g), worst relative "
                "error %.2e\n",
                method == AveragingMethod::Volume ? "volume" : "weighted", f.contact_stress[0][0],
                sxx, worst);
  }
}

// Random particles (radii r and 1.5 r, one density) in a box, random velocities; two steps.
ParticleStore random_particles(std::size_t n, double box, unsigned seed, bool velocities) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ParticleStore p;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = (i % 3 == 0 ? 1.5 : 1.0) * 0.001;
    const Vec3 x{box * u(rng), box * u(rng), box * u(rng)};
    Vec3 v{0, 0, 0};
    if (velocities) v = {0.3 + 0.5 * (u(rng) - 0.5), 0.2 * (u(rng) - 0.5), -0.1 + u(rng) - 0.5};
    p.add(x, v, r, 2500.0, 0, static_cast<std::int64_t>(i));
    p.wx[i] = u(rng) - 0.5;
    p.wy[i] = u(rng) - 0.5;
    p.wz[i] = u(rng) - 0.5;
  }
  return p;
}

TEST(ContinuumAveraging, KineticStressEqualsTheDirectFluctuationSum) {
  const double box = 0.02, rho = 2500.0;
  std::vector<ParticleStore> steps{random_particles(3000, box, 7, true),
                                   random_particles(3000, box, 8, true)};
  ContinuumGrid grid;
  grid.cells = {4, 3, 2};
  grid.spacing = {box / 4, box / 3, box / 2};
  const double vol = grid.cell_volume();
  // Volume method: -rho_s phi <v'v'>, the mean over both steps' particles in the cell.
  {
    ContinuumAverager avg(grid, {});
    for (const auto& p : steps) avg.accumulate(p, {});
    const ContinuumFields f = avg.result();
    for (std::size_t c = 0; c < grid.size(); ++c) {
      const int cx = static_cast<int>(c % 4), cy = static_cast<int>((c / 4) % 3),
                cz = static_cast<int>(c / 12);
      double m = 0, solid = 0, mv[3] = {0, 0, 0};
      std::vector<std::pair<double, Vec3>> in; // (mass, velocity)
      for (const auto& p : steps)
        for (std::size_t i = 0; i < p.size(); ++i)
          if (int(p.x[i] / (box / 4)) == cx && int(p.y[i] / (box / 3)) == cy &&
              int(p.z[i] / (box / 2)) == cz) {
            in.push_back({p.mass[i], p.velocity(i)});
            m += p.mass[i];
            solid += p.mass[i] / rho;
            for (int a = 0; a < 3; ++a) mv[a] += p.mass[i] * p.velocity(i)[a];
          }
      const double phi = solid / (2.0 * vol); // mean over two steps
      double mean_vv[9] = {};
      for (const auto& [mi, v] : in)
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            mean_vv[3 * a + b] += mi * (v[a] - mv[a] / m) * (v[b] - mv[b] / m) / m;
      EXPECT_NEAR(f.solid_fraction[c], phi, 1e-12 * phi);
      double scale = 0.0;
      for (double x : mean_vv) scale = std::max(scale, rho * phi * std::abs(x));
      for (int ab = 0; ab < 9; ++ab)
        EXPECT_NEAR(f.kinetic_stress[static_cast<std::size_t>(ab)][c], -rho * phi * mean_vv[ab],
                    1e-12 * scale)
            << "cell " << c << " component " << ab;
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(f.velocity[a][c], mv[a] / m, 1e-12);
      // Granular temperature: the mass-weighted mean of |v - u|^2 / 3, from the sums here.
      const double theta = (mean_vv[0] + mean_vv[4] + mean_vv[8]) / 3.0;
      EXPECT_NEAR(f.granular_temperature[c], theta, 1e-12 * theta) << "cell " << c;
    }
  }
  // Weighted: -sum_i h_i m_i v'v' with the Gaussian written out here.
  {
    ContinuumSettings s;
    s.method = AveragingMethod::Weighted;
    s.width = 0.003;
    s.cutoff = 3.0;
    ContinuumAverager avg(grid, s);
    for (const auto& p : steps) avg.accumulate(p, {});
    const ContinuumFields f = avg.result();
    const double w = s.width, c3 = s.cutoff;
    const double mass3 = std::erf(c3 / std::sqrt(2.0)) -
                         std::sqrt(2.0 / std::numbers::pi) * c3 * std::exp(-0.5 * c3 * c3);
    const double norm = 1.0 / (std::pow(2.0 * std::numbers::pi * w * w, 1.5) * mass3);
    for (std::size_t c = 0; c < grid.size(); ++c) {
      const Vec3 centre{(double(c % 4) + 0.5) * box / 4, (double((c / 4) % 3) + 0.5) * box / 3,
                        (double(c / 12) + 0.5) * box / 2};
      double hm = 0, hmv[3] = {0, 0, 0};
      for (const auto& p : steps)
        for (std::size_t i = 0; i < p.size(); ++i) {
          const double r2 = norm2(p.position(i) - centre);
          const double h = r2 > 9 * w * w ? 0.0 : norm * std::exp(-r2 / (2 * w * w));
          hm += h * p.mass[i];
          for (int a = 0; a < 3; ++a) hmv[a] += h * p.mass[i] * p.velocity(i)[a];
        }
      double t[9] = {}, scale = 0.0;
      for (const auto& p : steps)
        for (std::size_t i = 0; i < p.size(); ++i) {
          const double r2 = norm2(p.position(i) - centre);
          const double h = r2 > 9 * w * w ? 0.0 : norm * std::exp(-r2 / (2 * w * w));
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
              t[3 * a + b] -= 0.5 * h * p.mass[i] * (p.velocity(i)[a] - hmv[a] / hm) *
                              (p.velocity(i)[b] - hmv[b] / hm);
        }
      for (double x : t) scale = std::max(scale, std::abs(x));
      for (int ab = 0; ab < 9; ++ab)
        EXPECT_NEAR(f.kinetic_stress[static_cast<std::size_t>(ab)][c], t[ab], 1e-12 * scale)
            << "cell " << c << " component " << ab;
    }
  }
}

double total_solid(const ContinuumFields& f, const ContinuumGrid& g) {
  double s = 0.0;
  for (double phi : f.solid_fraction) s += phi * g.cell_volume();
  return s;
}

TEST(ContinuumAveraging, CellVolumesTimesSolidFractionSumToTheParticleVolume) {
  const double box = 0.02;
  const ParticleStore p = random_particles(2000, box, 3, false);
  double volume = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    volume += 4.0 / 3.0 * std::numbers::pi * std::pow(p.radius[i], 3);
  ContinuumGrid grid;
  grid.cells = {10, 10, 10};
  grid.spacing = {box / 10, box / 10, box / 10};
  grid.periodic = {true, true, true};
  ContinuumAverager vol(grid, {});
  vol.accumulate(p, {});
  const double v_volume = total_solid(vol.result(), grid);
  EXPECT_NEAR(v_volume, volume, 1e-13 * volume);
  ContinuumSettings s;
  s.method = AveragingMethod::Weighted;
  s.width = box / 10;
  ContinuumAverager wt(grid, s);
  wt.accumulate(p, {});
  const double v_weighted = total_solid(wt.result(), grid);
  EXPECT_NEAR(v_weighted, volume, 1e-3 * volume);
  std::printf("[ measured ] sum phi V / particle volume - 1: volume %.2e, weighted %.2e\n",
              v_volume / volume - 1.0, v_weighted / volume - 1.0);
}

TEST(ContinuumAveraging, ResultsDoNotDependOnTheThreadCount) {
  const double box = 0.02;
  ParticleStore p = random_particles(4000, box, 11, true);
  // Random contacts between near particles with random forces and torques, and wall contacts.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<ContactSample> contacts;
  for (std::int32_t i = 0; i + 1 < static_cast<std::int32_t>(p.size()); i += 2) {
    ContactSample c;
    c.i = i;
    c.j = (i % 10 == 0) ? -1 : i + 1;
    c.force = {u(rng), u(rng), u(rng)};
    c.torque_roll = {1e-4 * u(rng), 1e-4 * u(rng), 1e-4 * u(rng)};
    c.contact_point = p.position(static_cast<std::size_t>(i)) +
                      Vec3{0.001 * u(rng), 0.001 * u(rng), 0.001 * u(rng)};
    contacts.push_back(c);
  }
  ContinuumGrid grid;
  grid.cells = {7, 5, 6};
  grid.spacing = {box / 7, box / 5, box / 6};
  grid.periodic = {true, false, false};
  for (auto method : {AveragingMethod::Volume, AveragingMethod::Weighted}) {
    ContinuumSettings s;
    s.method = method;
    s.width = 0.002;
    s.parallel_threshold = 0; // threads for any size
    std::vector<ContinuumFields> out;
    const int saved = omp_get_max_threads();
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      ContinuumAverager avg(grid, s);
      avg.accumulate(p, contacts);
      avg.accumulate(p, contacts);
      out.push_back(avg.result());
    }
    omp_set_num_threads(saved);
    const auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
      return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * 8) == 0;
    };
    EXPECT_TRUE(same(out[0].solid_fraction, out[1].solid_fraction));
    for (int a = 0; a < 3; ++a) EXPECT_TRUE(same(out[0].velocity[a], out[1].velocity[a]));
    for (int ab = 0; ab < 9; ++ab) {
      EXPECT_TRUE(same(out[0].kinetic_stress[ab], out[1].kinetic_stress[ab]));
      EXPECT_TRUE(same(out[0].contact_stress[ab], out[1].contact_stress[ab]));
      EXPECT_TRUE(same(out[0].couple_stress[ab], out[1].couple_stress[ab]));
    }
  }
}

TEST(ContinuumAveraging, BadSettingsAreRejected) {
  ContinuumGrid g;
  g.cells = {0, 1, 1};
  EXPECT_THROW(ContinuumAverager(g, {}), std::invalid_argument);
  g.cells = {2, 2, 2};
  ContinuumSettings s;
  s.method = AveragingMethod::Weighted;
  s.width = -1.0;
  EXPECT_THROW(ContinuumAverager(g, s), std::invalid_argument);
  s.width = 0.4;
  g.periodic = {true, false, false}; // cutoff 1.2 m > half of the 2 m periodic length
  EXPECT_THROW(ContinuumAverager(g, s), std::invalid_argument);
}

} // namespace
} // namespace fluidem
