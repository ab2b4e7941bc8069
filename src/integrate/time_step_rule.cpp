#include "integrate/time_step_rule.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "core/error.hpp"
#include "noncontact/liquid_bridges.hpp"
#include "noncontact/pair_forces.hpp"
#include "particles/size_distribution.hpp"

namespace fluidem {

namespace {

void check_step_count(const CaseSpec& spec, double dt) {
  const double steps = spec.simulation.end_time / dt;
  if (!(dt > 0.0) || !std::isfinite(steps) || steps > kMaxSteps)
    throw InputError(spec.where("simulation.time_step"), "simulation.time_step",
                     fmt::format("{:.4g} s gives {:.3g} steps to simulation.end_time = {:.4g} s "
                                 "(allowed: at most {:.0e} steps)",
                                 dt, steps, spec.simulation.end_time, kMaxSteps));
}

/// The hard-sphere flow step DT; "auto" = 1e-4 s [Hoomans96 Table 2]. Collisions are events, so
/// there is no contact-time limit.
TimeSteps hard_sphere_steps(CaseSpec& spec) {
  const auto& sim = spec.simulation;
  TimeSteps s;
  s.dt = sim.time_step ? *sim.time_step : 1.0e-4;
  if (!sim.time_step && sim.end_time > 0.0) s.dt = sim.end_time / std::ceil(sim.end_time / s.dt);
  spec.simulation.time_step = s.dt;
  check_step_count(spec, s.dt);
  if (spec.gas) {
    if (spec.gas->time_step != 0.0)
      throw InputError(spec.where("gas.time_step"), "gas.time_step",
                       "hard-sphere runs take the flow step DT from simulation.time_step; "
                       "remove gas.time_step");
    s.flow_dt = s.dt;
  }
  return s;
}

} // namespace

TimeSteps choose_time_steps(CaseSpec& spec, const ParticleStore& p, const ContactTable* table) {
  if (table == nullptr) return hard_sphere_steps(spec);
  // From the contact duration [Deen07 eq. 41-42] of the contacts that can happen. None (every
  // particle fixed): 1e-4 s, the flow step's default, unless given.
  TimeSteps s;
  // The non-contact forces' stiffness counts as a contact of half-period pi sqrt(m*/k)
  // (noncontact/pair_forces.hpp).
  double tc = std::min(shortest_possible_contact(with_smallest_diameters(spec), p, *table),
                       shortest_noncontact_period(spec.noncontact, p));
  if (const auto& b = spec.noncontact.liquid_bridge)
    tc = std::min(tc, shortest_bridge_time(*b, liquid_fractions(spec), p));
  s.stable_dt = tc / kMinStepsPerContact;
  const auto& sim = spec.simulation;
  s.dt = sim.time_step ? *sim.time_step : std::isfinite(tc) ? sim.time_step_fraction * tc : 1.0e-4;
  if (!sim.time_step && sim.end_time > 0.0) s.dt = sim.end_time / std::ceil(sim.end_time / s.dt);
  if (s.dt > s.stable_dt && !sim.force_time_step) {
    throw InputError(
        spec.where("simulation.time_step"), "simulation.time_step",
        fmt::format("{:.4g} s is above the stability limit {:.4g} s (the shortest "
                    "contact, or half-period of a non-contact force, lasts {:.4g} s and "
                    "needs at least {} steps); choose a "
                    "smaller step, \"auto\", or set simulation.force_time_step = "
                    "true",
                    s.dt, s.stable_dt, tc, kMinStepsPerContact));
  }
  if (spec.gas) {
    // Flow step DT ("auto" = 1e-4 s [Hoomans96 §5.3], shortened to end exactly at end_time);
    // the DEM step is shortened so that a whole number of DEM steps fills DT.
    s.flow_dt = spec.gas->time_step > 0.0 ? spec.gas->time_step : 1.0e-4;
    if (spec.gas->time_step == 0.0 && sim.end_time > 0.0)
      s.flow_dt = sim.end_time / std::ceil(sim.end_time / s.flow_dt);
    s.steps_per_flow = std::max(1L, static_cast<long>(std::ceil(s.flow_dt / s.dt - 1e-9)));
    s.dt = s.flow_dt / static_cast<double>(s.steps_per_flow);
    spec.gas->time_step = s.flow_dt;
  }
  spec.simulation.time_step = s.dt; // the resolved case reproduces this run
  check_step_count(spec, s.dt);
  s.forced = s.dt > s.stable_dt;
  return s;
}

CaseSpec with_smallest_diameters(const CaseSpec& spec) {
  CaseSpec c = spec;
  for (const InsertSpec& ins : spec.inserts)
    if (const int k = spec.species_index(ins.species); k >= 0 && ins.size_distribution) {
      double& d = c.species[static_cast<std::size_t>(k)].diameter;
      d = std::min(d, SizeDistribution(*ins.size_distribution).smallest());
    }
  return c;
}

BoxGeometry box_from(const CaseSpec& spec) {
  BoxGeometry b;
  b.lo = spec.domain.lo;
  b.hi = spec.domain.hi;
  b.periodic = spec.domain.periodic;
  for (int f = 0; f < 6; ++f) {
    const int a = f / 2;
    b.wall[f] = !b.periodic[a] && !(spec.simulation.dimension == 2 && a == 1);
  }
  return b;
}

/// The shortest contact duration of the contacts that can happen, s. Fixed particles
// (ParticleStore::fix) meet neither each other nor the walls, and a fixed partner has infinite
/// mass (m* = the moving particle's mass): the species pairs and walls that only fixed particles
/// could form do not limit the time step. Durations per species as ContactTable's; without
/// fixed particles its shortest. Infinity when no contact can happen (no particle moves).
double shortest_possible_contact(const CaseSpec& spec, const ParticleStore& p,
                                 const ContactTable& t) {
  const std::size_t ns = spec.species.size();
  std::vector<char> moving(ns, 0), fixed(ns, 0);
  for (std::size_t i = 0; i < p.size(); ++i)
    (p.fixed(i) ? fixed : moving)[static_cast<std::size_t>(p.species[i])] = 1;
  if (std::find(fixed.begin(), fixed.end(), 1) == fixed.end()) return t.shortest_contact_duration();
  double tc = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < ns; ++a) {
    const double ra = 0.5 * spec.species[a].diameter;
    const double ma = sphere_mass(ra, spec.species[a].density);
    for (std::size_t b = 0; b < ns; ++b) {
      const double rb = 0.5 * spec.species[b].diameter;
      const double mb = sphere_mass(rb, spec.species[b].density);
      const PairParams& pp = t.pair(static_cast<int>(a), static_cast<int>(b));
      const double r_eff = ra * rb / (ra + rb);
      if (moving[a] && moving[b] && a <= b)
        tc = std::min(tc, t.contact_duration(ma * mb / (ma + mb), r_eff, pp, false));
      // (A fixed partner is met as a wall is: at one particle's speed.)
      if (moving[a] && fixed[b]) tc = std::min(tc, t.contact_duration(ma, r_eff, pp, true));
    }
    for (int f = 0; f < 6 && moving[a]; ++f) {
      if (spec.domain.periodic[f / 2] || (spec.simulation.dimension == 2 && f / 2 == 1)) continue;
      tc = std::min(tc, t.contact_duration(ma, ra, t.wall(static_cast<int>(a), f), true));
    }
  }
  return tc;
}

/// Overlap under the bed's own weight: a bottom particle carries the column above it,
/// F = m g h / d with h the height the particles fill at packing fraction 0.6 (3-D) or area
/// fraction 0.82 (2-D); delta from the normal model's overlap_under (its declaration), against the
/// floor.
double expected_overlap_ratio(const CaseSpec& spec, const ParticleStore& p, const ContactTable& t) {
  const auto& g = spec.simulation.gravity;
  const double gabs = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  if (gabs == 0.0 || p.size() == 0 || spec.species.empty()) return 0.0;
  int down = 2; // the axis gravity points along
  for (int a = 0; a < 3; ++a)
    if (std::abs(g[a]) > std::abs(g[down])) down = a;
  double base = 1.0, solid = 0.0;
  const bool two_d = spec.simulation.dimension == 2;
  for (int a = 0; a < 3; ++a)
    if (a != down && !(two_d && a == 1)) base *= spec.domain.hi[a] - spec.domain.lo[a];
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    solid += two_d ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
  }
  const double h = solid / ((two_d ? 0.82 : 0.6) * base);
  const auto& s = spec.species[0];
  const double r = 0.5 * s.diameter;
  const double f = sphere_mass(r, s.density) * gabs * h / s.diameter;
  const int face = 2 * down + (g[down] > 0 ? 1 : 0);
  const PairParams& pp = t.wall(0, face);
  return t.overlap_under(f, r, pp) / s.diameter;
}

} // namespace fluidem
