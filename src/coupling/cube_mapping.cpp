#include "coupling/cube_mapping.hpp"
#include <algorithm>
#include <cmath>

namespace fluidem::coupling {

namespace {
/// 1-D weights along one axis (n cells of size h from lo): the lengths of the control volumes
/// inside the cube's extent [c - half, c + half], divided by their sum. Control volume i spans
/// [lo + (i - o) h, lo + (i - o + 1) h], o = 1 for cells (i = 1..n), o = 1/2 for the faces
/// normal to the axis (i = 0..n). Walled axis: the extent is shifted into [lo, hi] as in
/// porosity.cpp (clipped to it when wider). Periodic axis: the centre is reduced into the period
/// (which changes nothing but the round-off), unwrapped index i is wrapped into 1..n, and the
/// entries past the first n are folded onto the first n (unwrapped i and i + n are the same
/// control volume), so that each wrapped index appears once.
void axis_weights(double lo, int n, double h, bool face, bool periodic, double c, double half,
                  std::vector<long>& q, std::vector<double>& w) {
  q.clear();
  w.clear();
  const double len = n * h, hi = lo + len;
  double ta = 0.0, tb = len; // the cube's extent, measured from lo
  if (periodic) {
    double s = std::fmod(c - lo, len);
    if (s < 0.0) s += len;
    ta = s - half;
    tb = s + half;
  } else if (hi - lo >= 2.0 * half) {
    const double cc = std::clamp(c, lo + half, hi - half); // the shift of porosity.cpp
    ta = std::max(cc - half - lo, 0.0);
    tb = std::min(cc + half - lo, len);
  } // else: narrower domain than the cube: the cube clipped to the domain, [0, len]
  const double o = face ? 0.5 : 1.0;
  long i0 = static_cast<long>(std::floor(ta / h + o));
  long i1 = static_cast<long>(std::floor(tb / h + o));
  if (!periodic) {
    i0 = std::max(i0, face ? 0L : 1L);
    i1 = std::min(i1, static_cast<long>(n));
  }
  const auto length = [&](long i) { // of control volume i inside the extent
    const double x0 = (static_cast<double>(i) - o) * h, x1 = x0 + h;
    return std::max(std::min(tb, x1) - std::max(ta, x0), 0.0);
  };
  if (!periodic) {
    // Two passes, the sum first: the weights are written once and not read back (normalising
    // them in place made vector loads wait on the scalar stores just made, half of the time).
    double sum = 0.0;
    for (long i = i0; i <= i1; ++i) sum += length(i); // (empty entries add exact zeros)
    for (long i = i0; i <= i1; ++i)
      if (const double l = length(i); l > 0.0) { // drop an end exactly on a boundary
        q.push_back(i);
        w.push_back(l / sum);
      }
    return;
  }
  const long nl = n;
  for (long i = i0; i <= i1; ++i) {
    const double l = length(i);
    const long k = i - i0;
    if (k < nl) {
      q.push_back(((i - 1) % nl + nl) % nl + 1);
      w.push_back(l);
    } else {
      w[static_cast<std::size_t>(k % nl)] += l;
    }
  }
  // Drop empty entries (an end of the extent exactly on a boundary), normalise.
  std::size_t m = 0;
  double sum = 0.0;
  for (std::size_t e = 0; e < w.size(); ++e)
    if (w[e] > 0.0) {
      q[m] = q[e];
      w[m++] = w[e];
      sum += w[e];
    }
  q.resize(m);
  w.resize(m);
  for (double& v : w) v /= sum;
}
} // namespace

namespace {
/// The 1-D weights along axis d (face: the faces normal to d; else the cells), with the one
/// cell across y of a 2-D grid.
void axis_list(const gas::GasGrid& g, int d, bool face, const Vec3& c, double half,
               const std::array<bool, 3>& periodic, std::vector<long>& q, std::vector<double>& w) {
  if (g.dimension == 2 && d == 1) { // one cell across y: area fractions in x-z
    q.assign(1, 1L);
    w.assign(1, 1.0);
    return;
  }
  axis_weights(g.lo[d], g.n[d], g.h[d], face, periodic[d], c[d], half, q, w);
}
} // namespace

void cube_axes(const gas::GasGrid& g, const Vec3& c, double half,
               const std::array<bool, 3>& periodic, CubeAxes& out) {
  for (int d = 0; d < 3; ++d) {
    const auto k = static_cast<std::size_t>(d);
    axis_list(g, d, false, c, half, periodic, out.cell_q[k], out.cell_w[k]);
    axis_list(g, d, true, c, half, periodic, out.face_q[k], out.face_w[k]);
  }
}

void cube_axes(const gas::GasGrid& g, int component, const Vec3& c, double half,
               const std::array<bool, 3>& periodic, CubeAxes& out) {
  for (int d = 0; d < 3; ++d) {
    const auto k = static_cast<std::size_t>(d);
    if (component == d)
      axis_list(g, d, true, c, half, periodic, out.face_q[k], out.face_w[k]);
    else
      axis_list(g, d, false, c, half, periodic, out.cell_q[k], out.cell_w[k]);
  }
}

void cube_weights(const gas::GasGrid& g, int component, const Vec3& c, double half,
                  const std::array<bool, 3>& periodic, CubeWeights& out) {
  out.clear();
  if (g.dimension == 2 && component == 1) return; // no v_y in 2-D
  cube_axes(g, component, c, half, periodic, out.axes);
  for_cube_weights(g, out.axes, component, [&](long q, double w) {
    out.q.push_back(q);
    out.w.push_back(w);
  });
}

} // namespace fluidem::coupling
