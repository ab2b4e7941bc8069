#include "app/analyse_bed.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "analysis/energies.hpp"
#include "core/error.hpp"
#include "io/case_reader.hpp"
#include "output/h5md_reader.hpp"

namespace fluidem {

namespace fs = std::filesystem;

namespace {

struct WindowStats {
  double mean = 0.0, std = 0.0;
  std::size_t n = 0;
};

WindowStats window_stats(const Table& t, int col, double t0, double t1) {
  WindowStats w;
  const auto& time = t.data[0];
  const auto& v = t.data[static_cast<std::size_t>(col)];
  for (std::size_t r = 0; r < time.size(); ++r)
    if (time[r] >= t0 && time[r] <= t1) w.mean += v[r], ++w.n;
  if (w.n == 0) return w;
  w.mean /= static_cast<double>(w.n);
  for (std::size_t r = 0; r < time.size(); ++r)
    if (time[r] >= t0 && time[r] <= t1) w.std += (v[r] - w.mean) * (v[r] - w.mean);
  w.std = std::sqrt(w.std / static_cast<double>(w.n));
  return w;
}

// Weight of the particles per unit cross-section normal to gravity, Pa: sum m_i |g| / A, with
// m_i of solid spheres of the species' density (also in 2-D, whose discs are solid spheres
// moving in the x-z plane, the box depth being the gas cells' depth [Hoomans96 eq. 49]).
double weight_per_area(const CaseSpec& spec, const ParticleStore& p) {
  double mass = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto s = static_cast<std::size_t>(p.species[i]);
    if (s >= spec.species.size())
      throw InputError(fmt::format("particles.h5: particle {} has species index {}, the case "
                                   "has {} species",
                                   p.id[i], s, spec.species.size()));
    const double r = p.radius[i];
    mass += spec.species[s].density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  }
  const auto& gv = spec.simulation.gravity;
  const double g = std::sqrt(gv[0] * gv[0] + gv[1] * gv[1] + gv[2] * gv[2]);
  int axis = 0; // the axis gravity points along
  for (int d = 1; d < 3; ++d)
    if (std::fabs(gv[static_cast<std::size_t>(d)]) > std::fabs(gv[static_cast<std::size_t>(axis)]))
      axis = d;
  double area = 1.0;
  for (int d = 0; d < 3; ++d)
    if (d != axis)
      area *=
          spec.domain.hi[static_cast<std::size_t>(d)] - spec.domain.lo[static_cast<std::size_t>(d)];
  return mass * g / area;
}

// The pressure drop against the superficial velocity over the whole run [Chang08 §3.4, Fig.
// 3.17]: rows binned by U (40 bins over its range), apart for the rising (U above the previous
// row's) and the falling branch; a row at the same U as the previous one belongs to the branch
// before it. Written when U varies by more than 5% of its largest value; returns whether it did.
bool pressure_drop_curve(const Table& s, int col_u, int col_dp, double weight,
                         const fs::path& dir) {
  const auto& u = s.data[static_cast<std::size_t>(col_u)];
  const auto& dp = s.data[static_cast<std::size_t>(col_dp)];
  if (u.size() < 2) return false;
  const auto [lo_it, hi_it] = std::minmax_element(u.begin(), u.end());
  const double lo = *lo_it, hi = *hi_it;
  if (!(hi > 0.0) || hi - lo <= 0.05 * hi) return false;
  const double width = (hi - lo) / 40.0;
  const auto bins = static_cast<std::size_t>(40);
  std::array<std::vector<double>, 2> sum{std::vector<double>(bins + 1, 0.0),
                                         std::vector<double>(bins + 1, 0.0)};
  std::array<std::vector<long>, 2> count{std::vector<long>(bins + 1, 0),
                                         std::vector<long>(bins + 1, 0)};
  int branch = 0; // 0 rising, 1 falling
  for (std::size_t r = 1; r < u.size(); ++r) {
    if (u[r] > u[r - 1]) branch = 0;
    if (u[r] < u[r - 1]) branch = 1;
    const auto b = static_cast<std::size_t>(std::lround((u[r] - lo) / width));
    sum[static_cast<std::size_t>(branch)][std::min(b, bins)] += dp[r];
    ++count[static_cast<std::size_t>(branch)][std::min(b, bins)];
  }
  std::ofstream f = open_out(dir / "pressure_drop_velocity.csv");
  f << "superficial_velocity,pressure_drop_rising,pressure_drop_falling,rising_over_weight,"
       "falling_over_weight\n";
  for (std::size_t b = 0; b <= bins; ++b) {
    if (count[0][b] == 0 && count[1][b] == 0) continue;
    f << g(lo + static_cast<double>(b) * width);
    double mean[2];
    for (std::size_t k = 0; k < 2; ++k)
      mean[k] = count[k][b] > 0 ? sum[k][b] / static_cast<double>(count[k][b])
                                : std::numeric_limits<double>::quiet_NaN();
    f << ',' << g(mean[0]) << ',' << g(mean[1]) << ',' << g(mean[0] / weight) << ','
      << g(mean[1] / weight) << '\n';
  }
  fmt::print("pressure drop      against the superficial velocity {:.3g} to {:.3g} m/s: "
             "pressure_drop_velocity.csv\n",
             lo, hi);
  return true;
}

} // namespace

void analyse_bed(const fs::path& out, double t0, double t1, std::vector<SummaryRow>& summary) {
  std::error_code ec;
  const fs::path series_path = out / "series.csv";
  if (!fs::exists(series_path, ec)) {
    fmt::print("bed                no {}: bed quantities left out\n", series_path.string());
    return;
  }
  const Table s = read_csv(series_path);
  const auto& time = s.data[0];
  std::size_t in_window = 0;
  for (double t : time) in_window += (t >= t0 && t <= t1) ? 1 : 0;
  if (in_window == 0)
    throw InputError(
        fmt::format("'{}' has no row in [{}, {}] s", series_path.string(), g(t0), g(t1)));
  std::optional<CaseSpec> spec;
  try {
    spec = read_case_file((out / "case.resolved.toml").string());
  } catch (const std::exception& e) {
    fmt::print("bed                {}: weight-based quantities left out\n", e.what());
  }
  std::unique_ptr<H5mdReader> reader;
  ParticleStore first, last;
  if (fs::exists(out / "particles.h5", ec)) {
    try {
      reader = std::make_unique<H5mdReader>((out / "particles.h5").string());
      if (reader->frames() > 0) {
        reader->read_frame(0, first);
        reader->read_frame(reader->frames() - 1, last);
      } else {
        reader.reset();
      }
    } catch (const std::runtime_error& e) {
      throw InputError(e.what());
    }
  }

  if (const int c = s.column("pressure_drop"); c >= 0) {
    const WindowStats w = window_stats(s, c, t0, t1);
    summary.push_back({"pressure_drop_mean", w.mean, "Pa"});
    summary.push_back({"pressure_drop_std", w.std, "Pa"});
    const double W = spec && reader ? weight_per_area(*spec, first) : 0.0;
    if (W > 0.0) { // no gravity (a periodic suspension): no weight to compare with
      summary.push_back({"bed_weight_per_area", W, "Pa"});
      summary.push_back({"pressure_drop_over_weight", w.mean / W, "1"});
      summary.push_back({"pressure_drop_std_over_weight", w.std / W, "1"});
      fmt::print("pressure drop      mean {:.5g} Pa = {:.4f} W, std {:.4g} Pa = {:.4f} W "
                 "(W = bed weight / area = {:.5g} Pa)\n",
                 w.mean, w.mean / W, w.std, w.std / W, W);
    } else {
      fmt::print("pressure drop      mean {:.5g} Pa, std {:.4g} Pa\n", w.mean, w.std);
    }
  }
  if (const int cu = s.column("superficial_velocity"), cp = s.column("pressure_drop");
      cu >= 0 && cp >= 0) {
    const double W =
        spec && reader ? weight_per_area(*spec, first) : std::numeric_limits<double>::quiet_NaN();
    pressure_drop_curve(s, cu, cp, W, out / "analysis");
  }
  if (const int c = s.column("bed_height"); c >= 0) {
    const WindowStats w = window_stats(s, c, t0, t1);
    const double h0 = s.data[static_cast<std::size_t>(c)].front();
    summary.push_back({"bed_height_initial", h0, "m"});
    summary.push_back({"bed_height_mean", w.mean, "m"});
    summary.push_back({"bed_height_std", w.std, "m"});
    if (h0 > 0.0) summary.push_back({"bed_expansion", w.mean / h0, "1"});
    fmt::print("bed height         mean {:.4g} m (std {:.3g} m), initial {:.4g} m\n", w.mean, w.std,
               h0);
  }
  if (const int c = s.column("n_collisions"); c >= 0) {
    // Cumulative count: the rate over the window is the difference of its ends.
    const auto& n = s.data[static_cast<std::size_t>(c)];
    std::size_t a = time.size(), b = 0;
    for (std::size_t r = 0; r < time.size(); ++r)
      if (time[r] >= t0 && time[r] <= t1) a = std::min(a, r), b = std::max(b, r);
    summary.push_back({"collisions_total", n.back(), "1"});
    if (b > a) {
      const double rate = (n[b] - n[a]) / (time[b] - time[a]);
      summary.push_back({"collisions_per_second", rate, "1/s"});
      fmt::print("collisions         {:.4g} per simulated second in the window, {:.0f} in all\n",
                 rate, n.back());
    }
  }
  // The energy balance of a run without gas [Hoomans96 §5.1]: e_total (kinetic + rotational +
  // potential + elastic + dissipated) is constant up to the integration error.
  if (const int c = s.column("e_total"); c >= 0 && !(spec && spec->gas)) {
    const auto& e = s.data[static_cast<std::size_t>(c)];
    double worst = 0.0;
    for (double v : e) worst = std::max(worst, std::fabs(v - e.front()));
    if (e.front() != 0.0) {
      summary.push_back({"energy_balance_error", worst / std::fabs(e.front()), "1"});
      fmt::print("energy balance     largest |e_total - e_total(0)| = {:.3g} of e_total(0)\n",
                 worst / std::fabs(e.front()));
    }
  }
  // The settled area fraction of a 2-D bed at the last frame [Hoomans96 §5.1] (runs without
  // gas: a fluidised bed has no settled surface).
  if (reader && reader->dimension() == 2 && spec && !spec->gas) {
    const auto& b = reader->box();
    const double phi = settled_area_fraction(last, b.lo[0], b.hi[0], b.lo[2]);
    summary.push_back({"area_fraction_last_frame", phi, "1"});
    fmt::print("area fraction      {:.4f} at t = {:.4g} s (disc area / width x surface height)\n",
               phi, reader->times().back());
  }
}

} // namespace fluidem
