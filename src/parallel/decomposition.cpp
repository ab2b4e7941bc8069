#include "parallel/decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace fluidem {

namespace {

std::string cells_str(const std::array<int, 3>& c) {
  std::ostringstream s;
  s << c[0] << " x " << c[1] << " x " << c[2];
  return s.str();
}

/// p parts along an axis of n cells fit when the axis is not cut or every part keeps min_cells.
bool axis_fits(int n, int p, int min_cells) {
  return p == 1 || static_cast<std::int64_t>(n) >= static_cast<std::int64_t>(p) * min_cells;
}

std::vector<int> even_cuts(int cells, int parts) {
  std::vector<int> c(static_cast<std::size_t>(parts) + 1);
  for (int k = 0; k <= parts; ++k)
    c[static_cast<std::size_t>(k)] = static_cast<int>(static_cast<std::int64_t>(k) * cells / parts);
  return c;
}

/// Gap between the intervals [a0, a1] and [b0, b1] (0 when they overlap or touch).
double interval_gap(double a0, double a1, double b0, double b1) {
  return std::max({0.0, b0 - a1, a0 - b1});
}

/// Distance from v to [lo, hi] (0 inside).
double interval_distance(double v, double lo, double hi) {
  return std::max({0.0, lo - v, v - hi});
}

} // namespace

Decomposition::Decomposition(const DecompositionGrid& grid, int ranks, int vertical_axis,
                             std::array<int, 3> forced, int min_cells)
    : grid_(grid), min_cells_(min_cells) {
  if (ranks < 1)
    throw std::invalid_argument("Decomposition: ranks must be >= 1, got " + std::to_string(ranks));
  if (vertical_axis < 0 || vertical_axis > 2)
    throw std::invalid_argument("Decomposition: vertical_axis must be 0, 1 or 2, got " +
                                std::to_string(vertical_axis));
  if (min_cells < 1)
    throw std::invalid_argument("Decomposition: min_cells must be >= 1, got " +
                                std::to_string(min_cells));
  for (int a = 0; a < 3; ++a) {
    if (grid.cells[a] < 1)
      throw std::invalid_argument("Decomposition: axis " + std::to_string(a) +
                                  " has no cells (cells " + cells_str(grid.cells) + ")");
    if (!(grid.hi[a] > grid.lo[a]))
      throw std::invalid_argument("Decomposition: axis " + std::to_string(a) +
                                  " needs hi > lo (an empty box)");
  }
  const auto fits = [&](const std::array<int, 3>& p) {
    for (int a = 0; a < 3; ++a)
      if (!axis_fits(grid.cells[a], p[a], min_cells)) return false;
    return true;
  };

  if (forced != std::array<int, 3>{0, 0, 0}) {
    // Each factor in 1 .. ranks keeps the int64 products below 2^62 (no overflow).
    const auto factor_ok = [&](int f) { return f >= 1 && f <= ranks; };
    const bool factors_ok = factor_ok(forced[0]) && factor_ok(forced[1]) && factor_ok(forced[2]);
    if (!factors_ok || static_cast<std::int64_t>(forced[0]) * forced[1] != ranks / forced[2] ||
        ranks % forced[2] != 0)
      throw std::invalid_argument("Decomposition: the forced process grid " + cells_str(forced) +
                                  " is not a factorisation of " + std::to_string(ranks) +
                                  " ranks (each part >= 1, product == ranks)");
    if (!fits(forced))
      throw std::invalid_argument("Decomposition: the forced process grid " + cells_str(forced) +
                                  " does not fit cells " + cells_str(grid.cells) +
                                  " with at least " + std::to_string(min_cells) +
                                  " cells per part (min_cells)");
    parts_ = forced;
  } else {
    const std::array<double, 3> len{grid.hi[0] - grid.lo[0], grid.hi[1] - grid.lo[1],
                                    grid.hi[2] - grid.lo[2]};
    const auto cut_area = [&](const std::array<int, 3>& p) {
      return (p[0] - 1) * len[1] * len[2] + (p[1] - 1) * len[0] * len[2] +
             (p[2] - 1) * len[0] * len[1];
    };
    bool found = false;
    std::array<int, 3> best{1, 1, 1};
    double best_area = 0.0;
    // Better: fewer vertical parts, then less cut area, then more parts on the lower axis index
    // (enumeration from large px, then large py, keeps the first of equal candidates).
    for (int px = ranks; px >= 1; --px) {
      if (ranks % px != 0) continue;
      for (int py = ranks / px; py >= 1; --py) {
        if ((ranks / px) % py != 0) continue;
        const std::array<int, 3> p{px, py, ranks / px / py};
        if (!fits(p)) continue;
        const double area = cut_area(p);
        if (!found) {
          found = true;
          best = p;
          best_area = area;
          continue;
        }
        const int pv = p[vertical_axis], bv = best[vertical_axis];
        const double tol = 1e-12 * std::max(std::abs(area), std::abs(best_area));
        if (pv < bv || (pv == bv && area < best_area - tol)) {
          best = p;
          best_area = area;
        }
      }
    }
    if (!found)
      throw std::invalid_argument("Decomposition: no process grid of " + std::to_string(ranks) +
                                  " ranks fits cells " + cells_str(grid.cells) + " with at least " +
                                  std::to_string(min_cells) +
                                  " cells per part (min_cells); use fewer ranks or a finer grid");
    parts_ = best;
  }
  for (int a = 0; a < 3; ++a) cuts_[a] = even_cuts(grid.cells[a], parts_[a]);
}

int Decomposition::ranks() const {
  return parts_[0] * parts_[1] * parts_[2];
}

void Decomposition::set_cuts(int axis, std::vector<int> cuts) {
  if (axis < 0 || axis > 2)
    throw std::invalid_argument("Decomposition::set_cuts: axis must be 0, 1 or 2, got " +
                                std::to_string(axis));
  const int parts = parts_[axis], cells = grid_.cells[axis];
  const std::string what = "Decomposition::set_cuts: axis " + std::to_string(axis) + ": ";
  if (cuts.size() != static_cast<std::size_t>(parts) + 1)
    throw std::invalid_argument(what + "needs " + std::to_string(parts + 1) + " cuts (" +
                                std::to_string(parts) + " parts + 1), got " +
                                std::to_string(cuts.size()));
  if (cuts.front() != 0)
    throw std::invalid_argument(what + "the first cut must be 0, got " +
                                std::to_string(cuts.front()));
  if (cuts.back() != cells)
    throw std::invalid_argument(what + "the last cut must be the cell count " +
                                std::to_string(cells) + ", got " + std::to_string(cuts.back()));
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    if (cuts[k + 1] <= cuts[k])
      throw std::invalid_argument(what + "the cuts must increase, got " + std::to_string(cuts[k]) +
                                  " then " + std::to_string(cuts[k + 1]) + " at index " +
                                  std::to_string(k));
    if (parts > 1 && cuts[k + 1] - cuts[k] < min_cells_)
      throw std::invalid_argument(what + "part " + std::to_string(k) + " has " +
                                  std::to_string(cuts[k + 1] - cuts[k]) +
                                  " cells, fewer than min_cells " + std::to_string(min_cells_));
  }
  cuts_[axis] = std::move(cuts);
}

int Decomposition::rank_of(std::array<int, 3> coords) const {
  for (int a = 0; a < 3; ++a)
    if (coords[a] < 0 || coords[a] >= parts_[a])
      throw std::out_of_range("Decomposition::rank_of: coordinates " + cells_str(coords) +
                              " outside the process grid " + cells_str(parts_));
  return (coords[0] * parts_[1] + coords[1]) * parts_[2] + coords[2];
}

std::array<int, 3> Decomposition::coords_of(int rank) const {
  if (rank < 0 || rank >= ranks())
    throw std::out_of_range("Decomposition::coords_of: rank " + std::to_string(rank) +
                            " outside 0 .. " + std::to_string(ranks() - 1));
  const int cz = rank % parts_[2];
  const int rest = rank / parts_[2];
  return {rest / parts_[1], rest % parts_[1], cz};
}

int Decomposition::cell_of(int axis, double v) const {
  const int cells = grid_.cells[axis];
  const double h = (grid_.hi[axis] - grid_.lo[axis]) / cells;
  const double t = std::floor((v - grid_.lo[axis]) / h);
  // Compare as doubles before the conversion: NaN, below lo and far beyond hi never reach the
  // (otherwise undefined) out-of-range cast to int.
  if (!(t >= 0.0)) return 0;
  if (t >= static_cast<double>(cells - 1)) return cells - 1;
  return static_cast<int>(t);
}

int Decomposition::owner(double x, double y, double z) const {
  const std::array<double, 3> p{x, y, z};
  std::array<int, 3> coords{};
  for (int a = 0; a < 3; ++a) {
    const int c = cell_of(a, p[a]);
    const auto& cuts = cuts_[a];
    const auto it = std::upper_bound(cuts.begin(), cuts.end(), c);
    coords[a] = std::clamp(static_cast<int>(it - cuts.begin()) - 1, 0, parts_[a] - 1);
  }
  return rank_of(coords);
}

Decomposition::Box Decomposition::box(int rank) const {
  const std::array<int, 3> coords = coords_of(rank);
  Box b;
  for (int a = 0; a < 3; ++a) {
    const int k = coords[a];
    const auto& cuts = cuts_[a];
    const double h = (grid_.hi[a] - grid_.lo[a]) / grid_.cells[a];
    b.cell_lo[a] = cuts[static_cast<std::size_t>(k)];
    b.cell_hi[a] = cuts[static_cast<std::size_t>(k) + 1];
    b.lo[a] = k == 0 ? grid_.lo[a] : grid_.lo[a] + b.cell_lo[a] * h;
    b.hi[a] = k == parts_[a] - 1 ? grid_.hi[a] : grid_.lo[a] + b.cell_hi[a] * h;
  }
  return b;
}

double Decomposition::distance2(int rank, double x, double y, double z) const {
  const Box b = box(rank);
  const std::array<double, 3> p{x, y, z};
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    double d = interval_distance(p[a], b.lo[a], b.hi[a]);
    if (grid_.periodic[a]) {
      const double len = grid_.hi[a] - grid_.lo[a];
      d = std::min({d, interval_distance(p[a] + len, b.lo[a], b.hi[a]),
                    interval_distance(p[a] - len, b.lo[a], b.hi[a])});
    }
    d2 += d * d;
  }
  return d2;
}

std::vector<int> Decomposition::neighbours(int rank, double width) const {
  const Box me = box(rank);
  std::vector<int> out;
  const int n = ranks();
  for (int r = 0; r < n; ++r) {
    if (r == rank) continue;
    const Box other = box(r);
    double g2 = 0.0;
    for (int a = 0; a < 3; ++a) {
      double g = interval_gap(me.lo[a], me.hi[a], other.lo[a], other.hi[a]);
      if (grid_.periodic[a]) {
        const double len = grid_.hi[a] - grid_.lo[a];
        g = std::min({g, interval_gap(me.lo[a], me.hi[a], other.lo[a] + len, other.hi[a] + len),
                      interval_gap(me.lo[a], me.hi[a], other.lo[a] - len, other.hi[a] - len)});
      }
      g2 += g * g;
    }
    if (g2 <= width * width) out.push_back(r);
  }
  return out;
}

std::vector<int> Decomposition::balanced_cuts(const std::vector<double>& layer_cost, int parts,
                                              int min_cells) {
  if (parts < 1)
    throw std::invalid_argument("Decomposition::balanced_cuts: parts must be >= 1, got " +
                                std::to_string(parts));
  const int m = std::max(min_cells, 1);
  const std::size_t size = layer_cost.size();
  if (static_cast<std::int64_t>(size) < static_cast<std::int64_t>(parts) * m)
    throw std::invalid_argument("Decomposition::balanced_cuts: " + std::to_string(size) +
                                " layers cannot make " + std::to_string(parts) +
                                " parts of at least " + std::to_string(m) + " cells (min_cells)");
  const int n = static_cast<int>(size);
  std::vector<double> prefix(size + 1, 0.0);
  for (std::size_t i = 0; i < size; ++i) {
    const double c = layer_cost[i];
    if (!(c >= 0.0) || !std::isfinite(c))
      throw std::invalid_argument("Decomposition::balanced_cuts: the cost of layer " +
                                  std::to_string(i) + " is negative or not finite");
    prefix[i + 1] = prefix[i] + c;
  }
  const double total = prefix[size];
  if (!(total > 0.0)) return even_cuts(n, parts);

  std::vector<int> cuts(static_cast<std::size_t>(parts) + 1, 0);
  cuts.back() = n;
  for (int k = 1; k < parts; ++k) {
    const double target = k * total / parts;
    // The boundary whose cumulative cost is nearest the target; the lower index on a tie.
    int best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i) {
      const double d = std::abs(prefix[static_cast<std::size_t>(i)] - target);
      if (d < best_d) {
        best_d = d;
        best = i;
      }
    }
    // Every interval keeps min_cells: after the previous cut, and room for the parts left.
    const int lower = cuts[static_cast<std::size_t>(k) - 1] + m;
    const int upper = n - (parts - k) * m;
    cuts[static_cast<std::size_t>(k)] = std::clamp(best, lower, upper);
  }
  return cuts;
}

} // namespace fluidem
