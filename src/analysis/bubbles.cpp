// Bubbles in the porosity field and their continuation between frames (bubbles.hpp).
#include "analysis/bubbles.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace fluidem {

BubbleFrame find_bubbles(const CellGrid& grid, const std::vector<double>& eps, double threshold) {
  const int nx = grid.cells[0], ny = grid.cells[1], nz = grid.cells[2];
  if (nx < 1 || ny < 1 || nz < 1)
    throw std::invalid_argument("find_bubbles: the grid has no cells");
  for (const double h : grid.spacing)
    if (!(h > 0.0)) throw std::invalid_argument("find_bubbles: cell sizes must be > 0");
  const std::size_t n = grid.size();
  if (eps.size() != n)
    throw std::invalid_argument("find_bubbles: " + std::to_string(eps.size()) +
                                " porosity values for " + std::to_string(n) + " cells");
  const long sx = 1, sy = nx, sz = static_cast<long>(nx) * ny;
  const double cell_volume = grid.spacing[0] * grid.spacing[1] * grid.spacing[2];
  const double cell_size =
      grid.planar() ? grid.spacing[0] * grid.spacing[2] : cell_volume; // area or volume

  BubbleFrame f;
  constexpr int unvisited = -3, bed = -1, freeboard = -2;
  f.label.assign(n, unvisited);
  std::vector<long> region, stack;
  std::size_t freeboard_cells = 0;
  for (std::size_t start = 0; start < n; ++start) {
    if (f.label[start] != unvisited) continue;
    if (!(eps[start] > threshold)) { // dense (or NaN: not dilute)
      f.label[start] = bed;
      continue;
    }
    // Flood fill of the dilute region holding `start`, across the faces of the cells.
    region.clear();
    stack.assign(1, static_cast<long>(start));
    f.label[start] = static_cast<int>(f.bubbles.size()); // provisional: visited
    bool top = false, wall = false;
    while (!stack.empty()) {
      const long c = stack.back();
      stack.pop_back();
      region.push_back(c);
      const int i = static_cast<int>(c % nx), j = static_cast<int>((c / nx) % ny),
                k = static_cast<int>(c / sz);
      top = top || k == nz - 1;
      wall = wall || i == 0 || i == nx - 1 || k == 0 || (!grid.planar() && (j == 0 || j == ny - 1));
      const auto visit = [&](bool exists, long q) {
        if (!exists || f.label[static_cast<std::size_t>(q)] != unvisited) return;
        if (!(eps[static_cast<std::size_t>(q)] > threshold)) return; // labelled bed in its turn
        f.label[static_cast<std::size_t>(q)] = f.label[start];
        stack.push_back(q);
      };
      visit(i > 0, c - sx);
      visit(i < nx - 1, c + sx);
      visit(j > 0, c - sy);
      visit(j < ny - 1, c + sy);
      visit(k > 0, c - sz);
      visit(k < nz - 1, c + sz);
    }
    if (top) { // connected to the top layer: the freeboard, not a bubble
      for (const long c : region) f.label[static_cast<std::size_t>(c)] = freeboard;
      freeboard_cells += region.size();
      continue;
    }
    Bubble b;
    b.cells = region.size();
    b.size = static_cast<double>(b.cells) * cell_size;
    b.equivalent_diameter = grid.planar() ? std::sqrt(4.0 * b.size / std::numbers::pi)
                                          : std::cbrt(6.0 * b.size / std::numbers::pi);
    b.touches_wall = wall;
    std::array<double, 3> sum{};
    int k_lo = nz, k_hi = -1;
    for (const long c : region) {
      const int idx[3] = {static_cast<int>(c % nx), static_cast<int>((c / nx) % ny),
                          static_cast<int>(c / sz)};
      for (int d = 0; d < 3; ++d) sum[static_cast<std::size_t>(d)] += idx[d] + 0.5;
      k_lo = std::min(k_lo, idx[2]);
      k_hi = std::max(k_hi, idx[2]);
    }
    for (std::size_t d = 0; d < 3; ++d)
      b.centroid[d] = grid.lo[d] + sum[d] / static_cast<double>(b.cells) * grid.spacing[d];
    b.z_extent = {grid.lo[2] + k_lo * grid.spacing[2], grid.lo[2] + (k_hi + 1) * grid.spacing[2]};
    f.bubble_volume += static_cast<double>(b.cells) * cell_volume;
    f.bubbles.push_back(b);
  }
  f.bed_volume = static_cast<double>(n - freeboard_cells) * cell_volume;
  return f;
}

std::vector<int> continue_bubbles(const BubbleFrame& prev, const BubbleFrame& next) {
  if (prev.label.size() != next.label.size())
    throw std::invalid_argument("continue_bubbles: the frames are on different grids");
  // Overlaps (next bubble, prev bubble) -> cells, in a fixed order.
  std::map<std::pair<int, int>, std::size_t> overlap;
  for (std::size_t c = 0; c < next.label.size(); ++c)
    if (next.label[c] >= 0 && prev.label[c] >= 0) ++overlap[{next.label[c], prev.label[c]}];
  // Each next bubble's largest overlap (ties: the lower prev index, met first in the map).
  std::vector<int> best(next.bubbles.size(), -1);
  std::vector<std::size_t> best_cells(next.bubbles.size(), 0);
  for (const auto& [key, cells] : overlap)
    if (cells > best_cells[static_cast<std::size_t>(key.first)]) {
      best[static_cast<std::size_t>(key.first)] = key.second;
      best_cells[static_cast<std::size_t>(key.first)] = cells;
    }
  // Per prev bubble, the next bubble that continues it: the largest overlap (ties: lower index).
  std::vector<int> heir(prev.bubbles.size(), -1);
  for (std::size_t j = 0; j < best.size(); ++j) {
    if (best[j] < 0) continue;
    int& h = heir[static_cast<std::size_t>(best[j])];
    if (h < 0 || best_cells[j] > best_cells[static_cast<std::size_t>(h)]) h = static_cast<int>(j);
  }
  std::vector<int> out(next.bubbles.size(), -1);
  for (std::size_t i = 0; i < heir.size(); ++i)
    if (heir[i] >= 0) out[static_cast<std::size_t>(heir[i])] = static_cast<int>(i);
  return out;
}

} // namespace fluidem
