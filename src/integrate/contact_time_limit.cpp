#include "integrate/contact_time_limit.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "integrate/coarse_graining.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

namespace {

/// An input of the shortest contact, and its duration as a function of that input alone.
struct Input {
  std::string key, unit;
  double value = 0.0;
  double usual_lo = 0.0, usual_hi = 0.0; ///< the range met in practice (chooses the culprit)
  double usual_value = 0.0;              ///< the value compared with it (E* for a modulus)
  bool longer_when_larger = true;        ///< whether a larger value lengthens the contact
  std::function<double(double)> duration;
};

/// How far `v` lies outside [lo, hi], in decades (infinite for a value that is not > 0).
double decades_outside(double v, double lo, double hi) {
  if (!(v > 0.0) || !std::isfinite(v)) return std::numeric_limits<double>::infinity();
  return std::max({0.0, std::log10(lo / v), std::log10(v / hi)});
}

/// The value of `in` nearest its present one at which the contact lasts `target` s: decade by
/// decade away from it (at most 600), then bisection on the logarithm to 1e-6 relative; nothing
/// when the duration stops being a number first.
std::optional<double> value_for(const Input& in, double target) {
  const double step = in.longer_when_larger ? 10.0 : 0.1;
  double bad = in.value, good = bad;
  for (int decade = 0;; ++decade) {
    good = bad * step;
    const double t = in.duration(good);
    if (t >= target) break;
    if (std::isnan(t) || decade == 600 || !(good > 0.0) || !std::isfinite(good))
      return std::nullopt;
    bad = good;
  }
  for (int it = 0; it < 100 && std::abs(std::log(good / bad)) > 1e-6; ++it) {
    const double mid = std::sqrt(good) * std::sqrt(bad);
    (in.duration(mid) >= target ? good : bad) = mid;
  }
  return good;
}

std::string format_value(double v) {
  return fmt::format("{:.3g}", v);
}

} // namespace

void check_contact_durations(const CaseSpec& spec, const ContactTable& table,
                             double min_steps_per_contact, double max_steps) {
  const auto& sim = spec.simulation;
  if (sim.force_time_step) return;
  const auto& rows = table.durations();
  if (rows.empty()) return;
  // The shortest contact (one that is not a number counts as the shortest).
  const auto shortest = std::min_element(
      rows.begin(), rows.end(),
      [](const ContactTable::DurationRow& a, const ContactTable::DurationRow& b) {
        return std::isnan(a.duration) ? !std::isnan(b.duration) : a.duration < b.duration;
      });
  const double tc = shortest->duration;
  const bool automatic = !sim.time_step.has_value();
  const double fraction = automatic ? sim.time_step_fraction : 1.0 / min_steps_per_contact;
  const double steps = sim.end_time / (fraction * tc);
  if (tc > 0.0 && std::isfinite(tc) && steps <= max_steps) return;
  const double target = sim.end_time / (fraction * max_steps); // the shortest contact allowed

  // The inputs of the shortest contact.
  const bool wall = shortest->face >= 0;
  const int a = shortest->species_a, b = shortest->species_b;
  const PairParams base = wall ? table.wall(a, shortest->face) : table.pair(a, b);
  std::vector<double> diameter(spec.species.size()), density(spec.species.size());
  for (std::size_t s = 0; s < spec.species.size(); ++s) {
    diameter[s] = spec.species[s].diameter;
    density[s] = spec.species[s].density;
  }
  // The contact's duration with these diameters, densities and parameters.
  auto duration = [&table, wall, a, b](const std::vector<double>& d, const std::vector<double>& rho,
                                       const PairParams& p) {
    const double ra = 0.5 * d[a], ma = sphere_mass(ra, rho[a]);
    if (wall) return table.contact_duration(ma, ra, p, true);
    // (in the reciprocal form: masses that underflow to 0 give 0, not 0 / 0)
    const double rb = 0.5 * d[b], mb = sphere_mass(rb, rho[b]);
    return table.contact_duration(1.0 / (1.0 / ma + 1.0 / mb), 1.0 / (1.0 / ra + 1.0 / rb), p,
                                  false);
  };
  const double shown = duration(diameter, density, base); // tc, without 0 / 0 for tiny masses
  std::vector<Input> inputs;
  std::vector<int> species{a};
  if (b != a) species.push_back(b);
  for (const int s : species) {
    const std::string p = "species[" + std::to_string(s) + "]";
    inputs.push_back(
        {p + ".diameter", "m", diameter[s], 1e-6, 1.0, diameter[s], true, [=](double v) {
           auto d = diameter;
           d[s] = v;
           return duration(d, density, base);
         }});
    inputs.push_back(
        {p + ".density", "kg/m^3", density[s], 1.0, 1e5, density[s], true, [=](double v) {
           auto rho = density;
           rho[s] = v;
           return duration(diameter, rho, base);
         }});
  }
  // The normal model's own inputs: its stiffness, or the softer material's Young's modulus.
  for (ContactTable::DurationInput& in : table.duration_inputs(spec, *shortest))
    inputs.push_back({in.key, in.unit, in.value, in.usual_lo, in.usual_hi, in.usual_value,
                      in.longer_when_larger, [=, params = std::move(in.params)](double v) {
                        return duration(diameter, density, params(v));
                      }});
  // The culprit: the input farthest outside the usual range; simulation.end_time if none is.
  const Input* culprit = nullptr;
  double worst = 0.0;
  for (const Input& in : inputs) {
    const double off = decades_outside(in.usual_value, in.usual_lo, in.usual_hi);
    if (off > worst) worst = off, culprit = &in;
  }
  std::vector<std::string> fixes;
  // Values as the user wrote them: with coarse graining the inputs are the parcels'.
  auto user_value = [&spec](const Input& in, double v) {
    return v / simulated_over_user(spec, in.key);
  };
  auto fix_of = [&](const Input& in) -> std::optional<std::string> {
    const auto v = value_for(in, target);
    if (!v) return std::nullopt;
    return fmt::format("{} {} {} {}", in.key,
                       in.longer_when_larger ? ">=" : "<=", format_value(user_value(in, *v)),
                       in.unit);
  };
  if (culprit)
    if (auto f = fix_of(*culprit)) fixes.push_back(*f);
  double width = 0.0; // no diameter above the domain's largest width is offered
  for (int ax = 0; ax < 3; ++ax) width = std::max(width, spec.domain.hi[ax] - spec.domain.lo[ax]);
  for (const Input& in : inputs) // the other inputs a user would change: not the densities
    if (&in != culprit && !in.key.ends_with(".density"))
      if (auto f = fix_of(in))
        if (!in.key.ends_with(".diameter") || *value_for(in, target) <= width) fixes.push_back(*f);
  const double end_max = max_steps * fraction * shown;
  if (end_max > 0.0 && std::isfinite(end_max))
    fixes.push_back(fmt::format("simulation.end_time <= {} s", format_value(end_max)));
  std::string allowed = fmt::format("at most {:.0e} steps", max_steps);
  for (std::size_t k = 0; k < fixes.size(); ++k) allowed += (k == 0 ? ": " : ", or ") + fixes[k];
  if (!fixes.empty()) allowed += ", the other values as they are";

  const std::string step = automatic ? fmt::format("at the automatic step ({} of the contact, "
                                                   "simulation.time_step_fraction)",
                                                   format_value(sim.time_step_fraction))
                                     : fmt::format("at the largest stable step (1/{:.0f} of the "
                                                   "contact)",
                                                   min_steps_per_contact);
  const std::string why = fmt::format(
      "the {} contact last{} {} s, and a run to simulation.end_time = {} s {} would "
      "take {} steps (allowed: {})",
      shortest->pair, culprit ? "" : "s", format_value(shown), format_value(sim.end_time), step,
      format_value(sim.end_time / (fraction * shown)), allowed);
  if (culprit)
    throw InputError(spec.where(culprit->key), culprit->key,
                     fmt::format("{} {} makes {}",
                                 format_value(user_value(*culprit, culprit->value)), culprit->unit,
                                 why));
  throw InputError(
      spec.where("simulation.end_time"), "simulation.end_time",
      fmt::format("{} s is too long for this case: {}", format_value(sim.end_time), why));
}

} // namespace fluidem
