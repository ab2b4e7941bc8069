#include "app/analyse_bubbles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "analysis/bubbles.hpp"
#include "core/error.hpp"
#include "output/fields_reader.hpp"

namespace fluidem {

void analyse_bubbles(const std::filesystem::path& fields_path, const std::filesystem::path& dir,
                     double t0, double t1, double void_porosity, std::vector<SummaryRow>& summary) {
  std::unique_ptr<FieldsReader> reader;
  try {
    reader = std::make_unique<FieldsReader>(fields_path.string());
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
  if (!reader->has_scalar("porosity")) {
    fmt::print("bubbles            {} has no porosity field: no bubbles\n", fields_path.string());
    return;
  }
  CellGrid grid;
  grid.cells = reader->cells();
  grid.lo = reader->lo();
  grid.spacing = reader->spacing();
  const std::vector<double>& time = reader->times();

  std::ofstream rows = open_out(dir / "bubbles.csv");
  rows
      << "time,id,x,y,z,z_bottom,z_top,cells,size,equivalent_diameter,rise_velocity,touches_wall\n";
  std::ofstream frames = open_out(dir / "bubble_frames.csv");
  frames << "time,bubbles,bubble_fraction,bed_volume,largest_diameter\n";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BubbleFrame prev;
  std::vector<long> prev_id;
  long next_id = 0;
  std::vector<double> eps;
  // Window sums: frames, bubble fraction, bubbles; bubble rows, their diameters; tracked rows,
  // their rise velocities.
  double n_frames = 0, sum_fraction = 0, sum_count = 0, n_rows = 0, sum_d = 0, max_d = 0,
         n_tracked = 0, sum_rise = 0;
  for (std::size_t k = 0; k < time.size(); ++k) {
    reader->read_scalar("porosity", k, eps);
    BubbleFrame b = find_bubbles(grid, eps, void_porosity);
    const std::vector<int> from =
        k > 0 ? continue_bubbles(prev, b) : std::vector<int>(b.bubbles.size(), -1);
    std::vector<long> id(b.bubbles.size());
    const bool in_window = time[k] >= t0 && time[k] <= t1;
    double largest = 0.0;
    for (std::size_t j = 0; j < b.bubbles.size(); ++j) {
      const Bubble& u = b.bubbles[j];
      const int p = from[j];
      id[j] = p >= 0 ? prev_id[static_cast<std::size_t>(p)] : next_id++;
      const double rise =
          p >= 0 && time[k] > time[k - 1]
              ? (u.centroid[2] - prev.bubbles[static_cast<std::size_t>(p)].centroid[2]) /
                    (time[k] - time[k - 1])
              : nan;
      rows << g(time[k]) << ',' << id[j] << ',' << g(u.centroid[0]) << ',' << g(u.centroid[1])
           << ',' << g(u.centroid[2]) << ',' << g(u.z_extent[0]) << ',' << g(u.z_extent[1]) << ','
           << u.cells << ',' << g(u.size) << ',' << g(u.equivalent_diameter) << ',' << g(rise)
           << ',' << (u.touches_wall ? 1 : 0) << '\n';
      largest = std::max(largest, u.equivalent_diameter);
      if (in_window) {
        ++n_rows;
        sum_d += u.equivalent_diameter;
        max_d = std::max(max_d, u.equivalent_diameter);
        if (std::isfinite(rise)) {
          ++n_tracked;
          sum_rise += rise;
        }
      }
    }
    frames << g(time[k]) << ',' << b.bubbles.size() << ',' << g(b.bubble_fraction()) << ','
           << g(b.bed_volume) << ',' << g(largest) << '\n';
    if (in_window) {
      ++n_frames;
      sum_fraction += b.bubble_fraction();
      sum_count += static_cast<double>(b.bubbles.size());
    }
    prev = std::move(b);
    prev_id = std::move(id);
  }
  if (n_frames == 0) {
    fmt::print("bubbles            no frame of {} in the window: bubbles.csv only\n",
               fields_path.string());
    return;
  }
  const auto mean = [&](double s, double n) { return n > 0 ? s / n : nan; };
  summary.push_back({"bubble_void_porosity", void_porosity, "1"});
  summary.push_back({"bubble_fraction_mean", sum_fraction / n_frames, "1"});
  summary.push_back({"bubble_count_mean", sum_count / n_frames, "1"});
  summary.push_back({"bubble_diameter_mean", mean(sum_d, n_rows), "m"});
  summary.push_back({"bubble_diameter_max", n_rows > 0 ? max_d : nan, "m"});
  summary.push_back({"bubble_rise_velocity_mean", mean(sum_rise, n_tracked), "m/s"});
  fmt::print("bubbles            {:.3g} per frame, bubble fraction {:.4f}, mean equivalent "
             "diameter {:.4g} m, mean rise velocity {:.4g} m/s ({} frames; porosity > {})\n",
             sum_count / n_frames, sum_fraction / n_frames, mean(sum_d, n_rows),
             mean(sum_rise, n_tracked), n_frames, void_porosity);
}

} // namespace fluidem
