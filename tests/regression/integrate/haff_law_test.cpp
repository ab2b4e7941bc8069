// Homogeneous cooling of a granular gas: Haff's law [Haff 1983, J. Fluid Mech. 134, 401;
// Brilliantov & Poeschel 2004, "Kinetic Theory of Granular Gases", OUP, the homogeneous cooling
// state].
//
// Monodisperse smooth (mu = 0) spheres of diameter sigma and mass m, normal restitution e,
// number density n, solid fraction phi = n pi sigma^3 / 6, in a fully periodic box without
// gravity. Granular temperature (velocity-squared units):
//   T = <|v - <v>|^2> / 3.
// Kinetic theory for a Maxwellian velocity distribution, with Enskog's pair correlation at
// contact (Carnahan-Starling) g0 = (1 - phi/2) / (1 - phi)^3:
//  * the relative velocity g = v1 - v2 is Maxwellian with variance 2T per component, so
//    <|g|> = 4 sqrt(T/pi) and <|g|^3> = 32 T^{3/2} / sqrt(pi);
//  * collision frequency per particle
//      omega_c = n pi sigma^2 g0 <|g|> = 4 n sigma^2 g0 sqrt(pi T);
//  * a collision with normal relative speed g_n removes (1 - e^2) (m/2) g_n^2 / 2 (reduced mass
//    m/2). Collisions per unit volume and time with unit normal k in dk: (1/2) n^2 g0 sigma^2
//    |g.k| dk (1/2: each pair once), and int_{g.k<0} |g.k|^3 dk = pi |g|^3 / 2, so the energy
//    lost per unit volume and time is
//      (1/2) n^2 g0 sigma^2 (1 - e^2) (m/4) (pi/2) <|g|^3> = 2 sqrt(pi) (1 - e^2) m n^2 g0
//      sigma^2 T^{3/2};
//  * divided by the kinetic energy density (3/2) n m T:
//      dT/dt = -(4/3) sqrt(pi) (1 - e^2) n g0 sigma^2 T^{3/2} = -(1 - e^2)/3 omega_c(T) T,
//    Haff's law with the Enskog collision frequency (B&P's cooling coefficient zeta_0).
// Integrating from t0, T(t) = T(t0) / (1 + (t - t0)/tau)^2 with
//      tau = 6 / ((1 - e^2) omega_c(T(t0))) = 3 / (2 sqrt(pi) (1 - e^2) n g0 sigma^2 sqrt(T(t0))).
// Over the first decade (T down to T(t0)/10, t - t0 = (sqrt(10) - 1) tau) each particle collides
// 6/(1 - e^2) ln sqrt(10) = 36 times. Left out: the non-Maxwellian cooling state, Sonine
// coefficient a2 = 16 (1 - e)(1 - 2 e^2) / (81 - 17 e + 30 e^2 (1 - e)) = -0.015 at e = 0.9,
// multiplies the cooling rate by 1 + 3 a2/16 = 0.997 [van Noije & Ernst 1998, Granular Matter 1,
// 57]; velocity correlations beyond Enskog; the shear and clustering instabilities of the cooling
// state, which grow in boxes of many mean free paths (here the box is 13 mean free paths wide).
//
// The test, with nothing fitted. kRealizations independent gases (seeds) are run in parallel and
// their T(t) averaged sample by sample, so that the statistical scatter of one gas of 2000
// particles (chaotic trajectories, slow hydrodynamic modes: 1-3% between seeds) stays well inside
// the tolerances.
//  1. Hard spheres (engine = "hard_sphere", TC model off, DT = 1e-4 s): uniform random
//     velocities (velocity_spread) relax towards the cooling state for 4 mean free times (about
//     4 collisions per particle) up to t0; from t0 the measured <T>(t)/<T>(t0) must follow
//     (1 + (t - t0)/tau)^-2, tau from the formula above with the measured <T>(t0) and the box's
//     phi, within 5% at every sample until the prediction reaches <T>(t0)/10.
//  2. The same gases (same initial positions and velocities) with the soft-sphere DEM
//     (engine = "soft_sphere", linear spring-dashpot, head-on e_n = 0.9 exact [Deen07 eq. 41], no
//     tangential force, time_step = "auto" = t_c/50), stiff enough that a contact lasts 1/50 of
//     the initial mean free time 1/omega_c: the averaged soft <T>(t) must agree with the hard one
//     within 5% at every sample of the same window. Expected small, systematic: soft spheres cool
//     slightly slower (about 1% in tau), because an oblique soft contact rotates its normal and
//     returns more normal energy than e^2 (measured with this code at the initial speeds, 1 m/s
//     and t_c = 1.8e-4 s: e_eff = 0.9002, 0.9017, 0.9052 at impact parameters 0.5, 0.8, 0.95 sigma;
//     independent of the time step), and because a contact lasts t_c instead of an instant.
// Printed: tau measured (least squares of sqrt(T(t0)/T(t)) - 1 = (t - t0)/tau through the
// origin, reported only, and checked within 5%), tau of kinetic theory, the largest deviations.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kD = 0.004;      // m, diameter sigma
constexpr double kRho = 2700.0;   // kg/m^3
constexpr double kE = 0.9;        // normal restitution
constexpr long kCount = 2000;     // particles per gas
constexpr double kPhi = 0.05;     // solid fraction
constexpr double kSpread = 1.0;   // m/s: each velocity component uniform in [-1, 1] m/s
constexpr double kRelax = 4.0;    // t0 in initial mean free times 1/omega_c(T(0))
constexpr double kSample = 0.5;   // sample interval in initial mean free times
constexpr double kContact = 50.0; // soft spheres: initial mean free time / contact duration
constexpr std::array<long, 4> kSeeds{1983, 2004, 1998, 2007}; // one gas per seed
constexpr std::size_t kRealizations = kSeeds.size();
constexpr double kDtHard = 1.0e-4; // s, hard-sphere flow step

/// Edge of the cubic box holding kCount spheres at solid fraction kPhi, m.
double box_edge() {
  return kD * std::cbrt(static_cast<double>(kCount) * kPi / (6.0 * kPhi));
}
double solid_fraction() {
  const double l = box_edge();
  return static_cast<double>(kCount) * kPi * kD * kD * kD / 6.0 / (l * l * l);
}
double mass() {
  return kPi / 6.0 * kD * kD * kD * kRho;
}

/// Enskog collision frequency per particle, 1/s, at granular temperature t (m^2/s^2).
double collision_frequency(double t) {
  const double phi = solid_fraction();
  const double n = 6.0 * phi / (kPi * kD * kD * kD);
  const double g0 = (1.0 - 0.5 * phi) / std::pow(1.0 - phi, 3);
  return 4.0 * n * kD * kD * g0 * std::sqrt(kPi * t);
}

/// Haff's time scale, s, from granular temperature t0.
double haff_tau(double t0) {
  return 6.0 / ((1.0 - kE * kE) * collision_frequency(t0));
}

/// T = <|v - <v>|^2> / 3, m^2/s^2 (equal masses).
double temperature(const ParticleStore& p) {
  const std::size_t n = p.size();
  const double inv_n = 1.0 / static_cast<double>(n);
  double mx = 0.0, my = 0.0, mz = 0.0;
  for (std::size_t i = 0; i < n; ++i) mx += p.vx[i], my += p.vy[i], mz += p.vz[i];
  mx *= inv_n, my *= inv_n, mz *= inv_n;
  double s = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double ux = p.vx[i] - mx, uy = p.vy[i] - my, uz = p.vz[i] - mz;
    s += ux * ux + uy * uy + uz * uz;
  }
  return s * inv_n / 3.0;
}

/// The gas: `engine` lines go into [simulation], `tail` after the insert (the contact model or
/// the [hardsphere] section). end_time is the sample interval: the automatic soft-sphere step is
/// end_time / a whole number, so it divides the sample interval exactly.
std::string gas_case(const std::string& engine, const std::string& tail, double end_time,
                     long seed) {
  return fmt::format(
      "[simulation]\ndimension = 3\nend_time = {end}\ngravity = [0.0, 0.0, 0.0]\n{engine}\n"
      "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [{L}, {L}, {L}]\nperiodic = [true, true, true]\n\n"
      "[[species]]\nname = \"glass\"\ndiameter = {d}\ndensity = {rho}\nrestitution = {e}\n"
      "friction = 0.0\n\n"
      "[[insert]]\nspecies = \"glass\"\ncount = {n}\nplacement = \"random\"\n"
      "velocity_spread = {v}\nseed = {seed}\n\n{tail}",
      fmt::arg("end", end_time), fmt::arg("engine", engine), fmt::arg("L", box_edge()),
      fmt::arg("d", kD), fmt::arg("rho", kRho), fmt::arg("e", kE), fmt::arg("n", kCount),
      fmt::arg("v", kSpread), fmt::arg("seed", seed), fmt::arg("tail", tail));
}

/// T after every sample interval from t = 0 (element 0: the initial state).
struct Series {
  std::vector<double> t, temp;
  void add(const Simulation& sim) {
    t.push_back(sim.time());
    temp.push_back(temperature(sim.particles()));
  }
  /// Advance in samples of `steps` steps until the series holds samples 0..k.
  void extend(Simulation& sim, long steps, std::size_t k) {
    while (t.size() <= k) {
      sim.advance(steps);
      add(sim);
    }
  }
};

/// Least-squares tau of sqrt(T(t0)/T(t)) - 1 = (t - t0)/tau through the origin, samples k0..k1.
double measured_tau(const std::vector<double>& t, const std::vector<double>& temp, std::size_t k0,
                    std::size_t k1) {
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t k = k0 + 1; k <= k1; ++k) {
    const double x = t[k] - t[k0], y = std::sqrt(temp[k0] / temp[k]) - 1.0;
    sxx += x * x, sxy += x * y;
  }
  return sxx / sxy;
}

/// One gas, run with both engines.
struct Gas {
  std::unique_ptr<Simulation> hard, soft;
  long hard_steps = 0, soft_steps = 0; // steps per sample
  Series h, s;
  long collisions_t0 = 0;
  std::string error; // an exception inside the parallel region
};

/// Run job(g) for every gas in parallel (one OpenMP thread per gas while cores last).
template <class Job>
void for_each_gas(std::vector<Gas>& gases, const Job& job) {
  const auto n = static_cast<long>(gases.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (long r = 0; r < n; ++r) {
    try {
      job(gases[static_cast<std::size_t>(r)]);
    } catch (const std::exception& e) {
      gases[static_cast<std::size_t>(r)].error = e.what();
    }
  }
  for (const auto& g : gases) ASSERT_EQ(g.error, "");
}

TEST(HaffLaw, HardAndSoftSpheresCoolAsKineticTheoryPredicts) {
  const double phi = solid_fraction();
  const double temp_init = kSpread * kSpread / 3.0; // uniform in [-s, s]: variance s^2/3
  const double t_free = 1.0 / collision_frequency(temp_init);
  const double sample = kDtHard * std::round(kSample * t_free / kDtHard);          // whole DTs
  const auto k0 = static_cast<std::size_t>(std::lround(kRelax * t_free / sample)); // t0
  const double mean_free_path = 1.0 / (std::sqrt(2.0) * kPi * 6.0 * phi / (kPi * kD) *
                                       (1.0 - 0.5 * phi) / std::pow(1.0 - phi, 3));
  // Soft spheres: linear spring-dashpot, t_c = sqrt(m* (pi^2 + ln^2 e) / k_n), m* = m/2
  // [Deen07 eq. 41].
  const double t_contact = t_free / kContact;
  const double le = std::log(kE);
  const double k_n = 0.5 * mass() * (kPi * kPi + le * le) / (t_contact * t_contact);
  std::cout << fmt::format(
      "Haff's law: {} gases of N = {}, phi = {:.4f}, box edge {:.4g} m = {:.1f} d = {:.1f} mean "
      "free paths, e = {}, T(0) = {:.4g} m2/s2, 1/omega_c(T(0)) = {:.4g} s; sample every {:.4g} "
      "s, t0 = {:.4g} s\n",
      kRealizations, kCount, phi, box_edge(), box_edge() / kD, box_edge() / mean_free_path, kE,
      temp_init, t_free, sample, static_cast<double>(k0) * sample);

  std::vector<Gas> gases(kRealizations);
  for (std::size_t r = 0; r < kRealizations; ++r) {
    Gas& g = gases[r];
    g.hard = std::make_unique<Simulation>(read_case_string(
        gas_case(fmt::format("engine = \"hard_sphere\"\ntime_step = {}\n", kDtHard),
                 "[hardsphere]\ntc_time = 0.0\n", sample, kSeeds[r]),
        "haff_hard.toml"));
    g.soft = std::make_unique<Simulation>(
        read_case_string(gas_case("engine = \"soft_sphere\"\ntime_step = \"auto\"\n",
                                  fmt::format("[contact]\nnormal = \"linear\"\nstiffness = {}\n"
                                              "tangential = \"none\"\n",
                                              k_n),
                                  sample, kSeeds[r]),
                         "haff_soft.toml"));
    ASSERT_EQ(g.hard->particles().size(), static_cast<std::size_t>(kCount));
    ASSERT_NE(g.hard->hard_sphere(), nullptr);
    ASSERT_EQ(g.soft->hard_sphere(), nullptr);
    g.hard_steps = std::lround(sample / g.hard->time_step());
    g.soft_steps = std::lround(sample / g.soft->time_step());
    ASSERT_NEAR(static_cast<double>(g.hard_steps) * g.hard->time_step(), sample, 1e-9 * sample);
    ASSERT_NEAR(static_cast<double>(g.soft_steps) * g.soft->time_step(), sample, 1e-9 * sample);
    g.h.add(*g.hard);
    g.s.add(*g.soft);
    // The same initial velocities, summed in another order (the soft-sphere store starts sorted
    // in space, neighbour.sort_interval): equal to round-off.
    EXPECT_NEAR(g.s.temp[0], g.h.temp[0], 1e-12 * g.h.temp[0]);
  }

  // Relaxation (hard spheres), then the window from the averaged T(t0).
  for_each_gas(gases, [&](Gas& g) {
    g.h.extend(*g.hard, g.hard_steps, k0);
    g.collisions_t0 = g.hard->hard_sphere()->stats().collisions;
  });
  auto average = [&](auto member, std::size_t k) {
    double a = 0.0;
    for (const auto& g : gases) a += (g.*member).temp[k];
    return a / static_cast<double>(kRealizations);
  };
  const double temp0 = average(&Gas::h, k0);
  const double tau = haff_tau(temp0);
  const std::size_t k1 =
      k0 + static_cast<std::size_t>(std::ceil((std::sqrt(10.0) - 1.0) * tau / sample));
  for_each_gas(gases, [&](Gas& g) {
    g.h.extend(*g.hard, g.hard_steps, k1);
    g.s.extend(*g.soft, g.soft_steps, k1);
  });

  // Averages over the gases and the deviations in the window.
  std::vector<double> t(gases[0].h.t), hard(k1 + 1), soft(k1 + 1);
  for (std::size_t k = 0; k <= k1; ++k) {
    hard[k] = average(&Gas::h, k);
    soft[k] = average(&Gas::s, k);
    for (const auto& g : gases) ASSERT_NEAR(g.s.t[k], t[k], 1e-9 * sample);
  }
  auto haff = [&](double time) { return 1.0 / std::pow(1.0 + (time - t[k0]) / tau, 2); };
  struct Worst {
    double dev = 0.0, at = 0.0;
    void see(double d, double time) {
      if (std::abs(d) > std::abs(dev)) dev = d, at = time;
    }
  } hard_theory, soft_hard, soft_theory;
  for (std::size_t k = k0; k <= k1; ++k) {
    hard_theory.see(hard[k] / hard[k0] / haff(t[k]) - 1.0, t[k] - t[k0]);
    soft_hard.see(soft[k] / hard[k] - 1.0, t[k] - t[k0]);
    soft_theory.see(soft[k] / soft[k0] / haff(t[k]) - 1.0, t[k] - t[k0]);
  }
  const double tau_hard = measured_tau(t, hard, k0, k1);
  const double tau_soft = measured_tau(t, soft, k0, k1);

  long coll_t0 = 0, coll_end = 0;
  for (std::size_t r = 0; r < kRealizations; ++r) {
    const Gas& g = gases[r];
    coll_t0 += g.collisions_t0;
    coll_end += g.hard->hard_sphere()->stats().collisions;
    const double tau_r = haff_tau(g.h.temp[k0]);
    std::cout << fmt::format(
        "  gas {} (seed {}): T(t0)/T(0) = {:.4f}; tau: kinetic theory {:.5g} s, hard {:.5g} s "
        "({:+.2f}%), soft {:.5g} s ({:+.2f}%); T_soft/T_hard at the end {:.4f}\n",
        r, kSeeds[r], g.h.temp[k0] / g.h.temp[0], tau_r, measured_tau(g.h.t, g.h.temp, k0, k1),
        100.0 * (measured_tau(g.h.t, g.h.temp, k0, k1) / tau_r - 1.0),
        measured_tau(g.s.t, g.s.temp, k0, k1),
        100.0 * (measured_tau(g.s.t, g.s.temp, k0, k1) / tau_r - 1.0), g.s.temp[k1] / g.h.temp[k1]);
  }
  const double per_particle = 2.0 / static_cast<double>(kCount * static_cast<long>(kRealizations));
  std::cout << fmt::format(
      "window t - t0 in [0, {:.4g}] s ({} samples); hard spheres: {:.2f} collisions per particle "
      "before t0, {:.2f} in the window (kinetic theory: {:.2f})\n"
      "averaged over the gases: <T>(end)/<T>(t0) = {:.4f} hard, {:.4f} soft (Haff: {:.4f})\n"
      "tau: kinetic theory {:.5g} s; measured hard {:.5g} s ({:+.2f}%), soft {:.5g} s ({:+.2f}%)\n"
      "largest deviation from Haff's law of T/T(t0): hard {:+.2f}% (at t - t0 = {:.3g} s), soft "
      "{:+.2f}% (at {:.3g} s)\n"
      "largest deviation of T_soft/T_hard from 1: {:+.2f}% (at t - t0 = {:.3g} s); soft spheres: "
      "k_n = {:.4g} N/m, t_c = {:.4g} s, dt = {:.4g} s, {} steps\n",
      t[k1] - t[k0], k1 - k0, per_particle * static_cast<double>(coll_t0),
      per_particle * static_cast<double>(coll_end - coll_t0),
      6.0 / (1.0 - kE * kE) * std::log(1.0 + (t[k1] - t[k0]) / tau), hard[k1] / hard[k0],
      soft[k1] / soft[k0], haff(t[k1]), tau, tau_hard, 100.0 * (tau_hard / tau - 1.0), tau_soft,
      100.0 * (tau_soft / tau - 1.0), 100.0 * hard_theory.dev, hard_theory.at,
      100.0 * soft_theory.dev, soft_theory.at, 100.0 * soft_hard.dev, soft_hard.at, k_n, t_contact,
      gases[0].soft->time_step(), gases[0].soft_steps * static_cast<long>(k1));
  RecordProperty("tau_kinetic_theory", fmt::format("{:.6g}", tau));
  RecordProperty("tau_hard_sphere", fmt::format("{:.6g}", tau_hard));
  RecordProperty("tau_soft_sphere", fmt::format("{:.6g}", tau_soft));
  RecordProperty("max_deviation_hard_vs_haff", fmt::format("{:.4f}", hard_theory.dev));
  RecordProperty("max_deviation_soft_vs_hard", fmt::format("{:.4f}", soft_hard.dev));

  EXPECT_GE(per_particle * static_cast<double>(coll_t0), 3.0); // relaxed for a few collisions
  EXPECT_LT(std::abs(hard_theory.dev), 0.05);
  EXPECT_LT(std::abs(tau_hard / tau - 1.0), 0.05);
  EXPECT_LT(std::abs(soft_hard.dev), 0.05);
}

} // namespace
} // namespace fluidem
