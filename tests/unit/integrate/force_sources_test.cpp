// Forces from the list of force sources (integrate/force_sources.hpp) move the particles as
// Newton's law says, whatever the source, and keep the energy books: one sphere, no gravity,
// far from the walls (no contact), against closed-form solutions of the equation of motion.
//  - A harmonic tether (conservative, evaluated every step): x(t) = x0 + A cos(w t),
//    w^2 = k/m. Velocity Verlet's phase error after time T is w T (w dt)^2 / 24 [Hairer,
//    Lubich & Wanner, Geometric Numerical Integration, 2006, §I.1]: 5e-6 rad here (w dt =
//    0.002, w T = 30); tolerance 1e-4 A. e_total = e_kin + e_pot (the tether's 1/2 k x^2) +
//    e_dsp stays within (w dt)^2 / 8 = 5e-7 of its start (Verlet's energy error); tolerance 1e-5.
//  - A linear dashpot F = -c v (dissipative, evaluated every step at the half-step velocity):
//    v(t) = v0 exp(-c t / m); its booked work keeps e_kin + e_dsp at e_kin(0) (O(c dt / m) =
//    1e-3 relative; tolerance 2e-3 of e_kin(0) after 3/4 of it is lost).
//  - Both at once (the list sums them): the damped oscillator,
//    x(t) = A exp(-g t / 2) (cos(wd t) + g / (2 wd) sin(wd t)), g = c/m, wd^2 = w^2 - g^2/4,
//    and e_kin + e_pot + e_dsp = e(0); tolerances as above.
//  - A constant force held over the steps (as the gas's forces are): a parabola, exact for
//    velocity Verlet (soft spheres) and, with one kick v += dt F/m per flow step before the
//    flight (hard spheres, [Hoomans96 Fig. 7]), x_n = x0 + a dt^2 n (n + 1) / 2. 1e-9 relative
//    (the round-off of 500 steps).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "integrate/simulation.hpp"
#include "io/case_reader.hpp"

namespace fluidem {
namespace {

constexpr double kD = 0.004, kRho = 2700.0, kBox = 0.2, kCentre = 0.1;
const double kMass = kRho * std::numbers::pi * kD * kD * kD / 6.0;

std::string case_text(bool hard, double dt, double vx) {
  return fmt::format(
      "[simulation]\nengine = \"{engine}\"\nend_time = 10.0\ntime_step = {dt:.17g}\n"
      "gravity = [0.0, 0.0, 0.0]\n\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [{L}, {L}, {L}]\n\n"
      "[[species]]\nname = \"s\"\ndiameter = {d}\ndensity = {rho}\n\n"
      "[[insert]]\nspecies = \"s\"\ncount = 1\nplacement = \"lattice\"\n"
      "region = {{ lo = [{lo}, {lo}, {lo}], hi = [{hi}, {hi}, {hi}] }}\n"
      "velocity = [{vx:.17g}, 0.0, 0.0]\n\n[contact]\nnormal = \"linear\"\nstiffness = 1.0e2\n",
      fmt::arg("engine", hard ? "hard_sphere" : "soft_sphere"), fmt::arg("dt", dt),
      fmt::arg("L", kBox), fmt::arg("d", kD), fmt::arg("rho", kRho),
      fmt::arg("lo", kCentre - 0.5 * kD), fmt::arg("hi", kCentre + 0.5 * kD), fmt::arg("vx", vx));
}

/// F = -k (x - anchor) along x, evaluated every step; potential 1/2 k (x - anchor)^2.
class Tether final : public StepForceSource {
public:
  Tether(double k, double anchor) : k_(k), anchor_(anchor) {}
  std::string_view name() const override { return "tether"; }
  EnergyRole energy_role() const override { return EnergyRole::Conservative; }
  void evaluate(const ParticleStore& p, double) override {
    for (auto& f : forces_) f.assign(p.size(), 0.0);
    for (std::size_t i = 0; i < p.size(); ++i) forces_[0][i] = -k_ * (p.x[i] - anchor_);
  }
  double potential_energy(const ParticleStore& p) const override {
    double e = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
      e += 0.5 * k_ * (p.x[i] - anchor_) * (p.x[i] - anchor_);
    return e;
  }

private:
  double k_, anchor_;
};

/// F = -c v, evaluated every step (at the half-step velocity, as the contacts' dashpots).
class Dashpot final : public StepForceSource {
public:
  explicit Dashpot(double c) : c_(c) {}
  std::string_view name() const override { return "dashpot"; }
  EnergyRole energy_role() const override { return EnergyRole::Dissipative; }
  void evaluate(const ParticleStore& p, double) override {
    for (auto& f : forces_) f.resize(p.size());
    for (std::size_t i = 0; i < p.size(); ++i)
      forces_[0][i] = -c_ * p.vx[i], forces_[1][i] = -c_ * p.vy[i], forces_[2][i] = -c_ * p.vz[i];
  }

private:
  double c_;
};

/// A constant force along x, held (set once, like the gas's forces over a flow step).
class Push final : public ForceSource {
public:
  Push(double f, std::size_t n)
      : f_{std::vector<double>(n, f), std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)} {}
  std::string_view name() const override { return "push"; }
  EnergyRole energy_role() const override { return EnergyRole::External; }
  const double* force(int axis) const override { return f_[static_cast<std::size_t>(axis)].data(); }
  void permute(const std::vector<std::uint32_t>&) override {}

private:
  std::array<std::vector<double>, 3> f_;
};

double total_energy(const Simulation& sim) {
  const Energies e = sim.energies();
  return e.kinetic + e.rotational + e.potential + sim.contact_stats().elastic_energy +
         sim.dissipated_energy();
}

TEST(ForceSources, ConservativeTetherOscillatesAndKeepsItsEnergy) {
  const double k = 10.0, w = std::sqrt(k / kMass), dt = 0.002 / w, amplitude = 0.01;
  Simulation sim(read_case_string(case_text(false, dt, 0.0), "tether.toml"));
  sim.add_force_source(std::make_unique<Tether>(k, kCentre - amplitude));
  const double e0 = total_energy(sim);
  EXPECT_NEAR(e0, 0.5 * k * amplitude * amplitude, 1e-12 * e0) << "the tether's potential";
  const long steps = 15000; // about 5 periods
  sim.advance(steps);
  const double t = static_cast<double>(steps) * dt;
  EXPECT_NEAR(sim.particles().x[0], kCentre - amplitude + amplitude * std::cos(w * t),
              1e-4 * amplitude);
  EXPECT_NEAR(total_energy(sim), e0, 1e-5 * e0);
}

TEST(ForceSources, DissipativeDashpotDecaysAndBooksItsWork) {
  const double c = 1e-3, gamma = c / kMass, dt = 1e-3 / gamma, v0 = 0.01;
  Simulation sim(read_case_string(case_text(false, dt, v0), "dashpot.toml"));
  sim.add_force_source(std::make_unique<Dashpot>(c));
  const double e0 = total_energy(sim);
  const long steps = 700; // e_kin falls to exp(-1.4) of its start
  sim.advance(steps);
  const double t = static_cast<double>(steps) * dt;
  EXPECT_NEAR(sim.particles().vx[0], v0 * std::exp(-gamma * t), 1e-3 * v0);
  EXPECT_GT(sim.dissipated_energy(), 0.7 * e0);
  EXPECT_NEAR(total_energy(sim), e0, 2e-3 * e0);
}

TEST(ForceSources, TwoSourcesSumToTheDampedOscillator) {
  const double k = 10.0, w = std::sqrt(k / kMass), gamma = 0.2 * w, dt = 0.01 / w, a = 0.01;
  Simulation sim(read_case_string(case_text(false, dt, 0.0), "damped.toml"));
  sim.add_force_source(std::make_unique<Tether>(k, kCentre - a));
  sim.add_force_source(std::make_unique<Dashpot>(gamma * kMass));
  const double e0 = total_energy(sim);
  const long steps = 1000;
  sim.advance(steps);
  const double t = static_cast<double>(steps) * dt;
  const double wd = std::sqrt(w * w - 0.25 * gamma * gamma);
  const double x =
      a * std::exp(-0.5 * gamma * t) * (std::cos(wd * t) + gamma / (2.0 * wd) * std::sin(wd * t));
  EXPECT_NEAR(sim.particles().x[0], kCentre - a + x, 2e-3 * a);
  EXPECT_GT(sim.dissipated_energy(), 0.5 * e0);
  EXPECT_NEAR(total_energy(sim), e0, 2e-3 * e0);
}

TEST(ForceSources, HeldForceGivesTheParabolaInBothEngines) {
  const double f = 1e-6, acc = f / kMass, dt = 1e-4;
  const long steps = 500;
  for (const bool hard : {false, true}) {
    Simulation sim(read_case_string(case_text(hard, dt, 0.0), "push.toml"));
    sim.add_force_source(std::make_unique<Push>(f, sim.particles().size()));
    sim.advance(steps);
    const double n = static_cast<double>(steps), t = n * dt;
    const double expected =
        hard ? kCentre + acc * dt * dt * n * (n + 1.0) / 2.0 : kCentre + 0.5 * acc * t * t;
    EXPECT_NEAR(sim.particles().x[0] - kCentre, expected - kCentre, 1e-9 * (expected - kCentre))
        << (hard ? "hard spheres" : "soft spheres");
  }
}

// An event-driven collision sequence has no step at which to evaluate a force every step: such a
// source is refused before it joins the list (the run goes on with the forces it had).
TEST(ForceSources, HardSpheresRefuseAStepSource) {
  Simulation sim(read_case_string(case_text(true, 1e-4, 0.01), "hard.toml"));
  EXPECT_THROW(sim.add_force_source(std::make_unique<Dashpot>(1e-3)), std::logic_error);
  sim.advance(10);
  EXPECT_NEAR(sim.particles().vx[0], 0.01, 1e-15)
      << "free flight: the refused dashpot is not there";
}

} // namespace
} // namespace fluidem
