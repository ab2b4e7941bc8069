#include "coupling/porosity.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "coupling/cube_mapping.hpp"
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace fluidem::coupling {

namespace {
constexpr double pi = 3.14159265358979323846;

/// Volume of the unit ball with x > a, a >= 0: spherical cap of height h = 1 - a.
double unit_cap(double a) {
  if (a >= 1.0) return 0.0;
  const double h = 1.0 - a;
  return pi / 3.0 * h * h * (2.0 + a);
}

/// Volume of the unit ball with x > a, y > b, a, b >= 0: unit_corner(a, b, 0) doubled, i.e.
///   V = 2/3 (al + a b z) - a (3 - a^2)/3 atan2(z, b) - b (3 - b^2)/3 atan2(z, a),
/// z = sqrt(1 - a^2 - b^2) the half length of the edge inside the ball, al = atan2(z, a b) the
/// angle between the two spherical arcs at its end. Identical to the sum of the two "regularized
/// spherical wedges" of [Strobl16] on either side of the plane through the centre and the edge
/// (their two angles atan2(b z, a), atan2(a z, b) add up to al).
/// [Strobl16] S. Strobl, A. Formella, T. Poeschel, Exact calculation of the overlap volume of
/// spheres and mesh elements, J. Comput. Phys. 311 (2016) 158-172, doi:10.1016/j.jcp.2016.02.003.
double unit_wedge(double a, double b) {
  if (a > b) std::swap(a, b); // b largest: (1 - b)(1 + b) below is then accurate
  const double z2 = (1.0 - b) * (1.0 + b) - a * a;
  if (!(z2 > 0.0)) return 0.0;
  const double z = std::sqrt(z2);
  const double v = 2.0 / 3.0 * (std::atan2(z, a * b) + a * b * z) -
                   a * (3.0 - a * a) / 3.0 * std::atan2(z, b) -
                   b * (3.0 - b * b) / 3.0 * std::atan2(z, a);
  return std::max(v, 0.0);
}

/// Volume of the unit ball with x > a, y > b, z > c, a, b, c >= 0 (empty unless
/// a^2 + b^2 + c^2 < 1). Derived here (checked against quadrature and 40-digit values in
/// tests/unit/coupling/porosity_test.cpp):
///  - divergence theorem with the field r/3 (r.n = 1 on the sphere, -a on the face x = a):
///    V = (S - a A_a - b A_b - c A_c)/3, S the area of the spherical triangle cut from the unit
///    sphere, A_a the area of the face on x = a (disc of radius sqrt(1 - a^2) in {y > b, z > c}):
///    A_a = (1 - a^2) th_a / 2 - (b z_ab + c y_ca)/2 + b c (circular sector minus two triangles),
///    th_a the angle of the face's arc seen from the axis x; the triangle's vertices are
///    (a, b, z_ab), (x_bc, b, c), (a, y_ca, c) with z_ab = sqrt(1 - a^2 - b^2) etc.;
///  - Gauss-Bonnet on the unit sphere: S = (al_ab + al_bc + al_ca - pi) - (a th_a + b th_b +
///    c th_c), al_ab = atan2(z_ab, a b) the interior angle at (a, b, z_ab) (cos al_ab = a b /
///    sqrt((1 - a^2)(1 - b^2))), a / sqrt(1 - a^2) the geodesic curvature of the circle x = a
///    and sqrt(1 - a^2) th_a its arc length. Together:
///   V = (al_ab + al_bc + al_ca - pi)/3 - [a (3 - a^2) th_a + b (3 - b^2) th_b +
///       c (3 - c^2) th_c]/6 + (a b z_ab + b c x_bc + c a y_ca)/3 - a b c.
/// With c = 0 it is unit_wedge / 2, with b = c = 0 unit_cap / 4, with a = b = c = 0 pi/6.
/// Numerics: all angles are atan2 of vertex coordinates (no acos/asin near +-1), and V is
/// stationary in each vertex coordinate (dV/dz_ab = -a b z_ab^2 / (3 (1 - a^2)(1 - b^2))), so
/// the rounding of the square roots near tangency (z_ab -> 0) does not propagate: the error is
/// ~1e-16 absolute (the terms are O(1) and cancel for tiny corners: no relative accuracy there).
double unit_corner(double a, double b, double c) {
  if (a > b) std::swap(a, b); // c largest: (1 - c)(1 + c) below is then accurate
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  const double t = (1.0 - c) * (1.0 + c) - a * a - b * b; // 1 - |corner|^2
  if (!(t > 0.0)) return 0.0;
  const double x = std::sqrt((1.0 - c) * (1.0 + c) - b * b); // vertex (x_bc, b, c)
  const double y = std::sqrt((1.0 - c) * (1.0 + c) - a * a); // vertex (a, y_ca, c)
  const double z = std::sqrt((1.0 - b) * (1.0 + b) - a * a); // vertex (a, b, z_ab)
  // Excess al_ab + al_bc + al_ca - pi, in [0, pi/2] (S >= 0): the argument of minus the product
  // (a b + i z)(b c + i x)(c a + i y), one atan2 instead of three.
  const double ur = a * b * b * c - z * x, ui = a * b * x + b * c * z;
  const double qr = ur * c * a - ui * y, qi = ur * y + ui * c * a;
  const double excess = std::atan2(-qi, -qr);
  // Arc angles th_a, th_b, th_c of the faces: angle between the face's two vertices.
  const double th_a = std::atan2(y * z - b * c, b * y + c * z);
  const double th_b = std::atan2(x * z - a * c, a * x + c * z);
  const double th_c = std::atan2(x * y - a * b, a * x + b * y);
  const double v =
      excess / 3.0 -
      (a * (3.0 - a * a) * th_a + b * (3.0 - b * b) * th_b + c * (3.0 - c * c) * th_c) / 6.0 +
      (a * b * z + b * c * x + c * a * y) / 3.0 - a * b * c;
  return std::max(v, 0.0);
}

/// Volume of the unit ball in {x_i > d_i, i < n}, d_i >= 0 (n = 0..3 planes).
double unit_ball_above(const std::array<double, 3>& d, int n) {
  switch (n) {
  case 0:
    return 4.0 / 3.0 * pi;
  case 1:
    return unit_cap(d[0]);
  case 2:
    return unit_wedge(d[0], d[1]);
  default:
    return unit_corner(d[0], d[1], d[2]);
  }
}
} // namespace

void validate(const PorositySettings& s) {
  if (s.method == PorosityMethod::porous_cube &&
      (!std::isfinite(s.cube_factor) || s.cube_factor < std::cbrt(pi / 6.0)))
    throw InputError("coupling.porosity.cube_factor = " + std::to_string(s.cube_factor) +
                     " must be >= (pi/6)^(1/3) = 0.806 [Deen07 eq. 35]");
}

double disc_quadrant_area(double r, double Y, double Z) {
  if (!(r > 0.0) || Y <= -r || Z <= -r) return 0.0;
  Y = std::min(Y, r);
  Z = std::min(Z, r);
  // P(y) = integral of s(y) = sqrt(r^2 - y^2) from 0 to y.
  auto P = [r](double y) {
    const double s = std::sqrt(std::max(r * r - y * y, 0.0));
    return 0.5 * (y * s + r * r * std::asin(std::clamp(y / r, -1.0, 1.0)));
  };
  // Chord length at y below z = Z: clamp(Z + s, 0, 2 s); the kinks are at |y| = yz.
  const double yz = std::sqrt(std::max(r * r - Z * Z, 0.0));
  // P is only ever needed at -r, -yz, yz, r (the interval ends) and Y (an end cut by Y); P is
  // odd (bitwise: y s and asin are), and P(r) = r^2 asin(1) / 2. So at most two asin calls.
  static const double half_pi = std::asin(1.0);
  const double Pr = 0.5 * (r * r * half_pi), Pyz = P(yz);
  double PY = 0.0;
  bool have_Y = false;
  auto Pm = [&](double y) {
    if (y == yz) return Pyz;
    if (y == -yz) return -Pyz;
    if (y == r) return Pr;
    if (y == -r) return -Pr;
    if (!have_Y) { // the only other argument: Y
      PY = P(Y);
      have_Y = true;
    }
    return PY;
  };
  auto two_s = [&](double a, double b) {
    b = std::min(b, Y);
    return b > a ? 2.0 * (Pm(b) - Pm(a)) : 0.0;
  };
  auto z_plus_s = [&](double a, double b) {
    b = std::min(b, Y);
    return b > a ? Z * (b - a) + Pm(b) - Pm(a) : 0.0;
  };
  if (Z >= 0.0) return two_s(-r, -yz) + z_plus_s(-yz, yz) + two_s(yz, r);
  return z_plus_s(-yz, yz);
}

double ball_octant_volume(double R, double X, double Y, double Z) {
  if (!(R > 0.0) || X <= -R || Y <= -R || Z <= -R) return 0.0;
  // Unit ball, u = X / R: a plane with u <= 0 bounds {x < u}, the mirror image of {x > -u}; one
  // with 0 < u < 1 bounds {x < u} = ball - {x > u} (inclusion-exclusion over these); u >= 1 does
  // not cut.
  std::array<double, 3> u{X / R, Y / R, Z / R};
  std::sort(u.begin(), u.end()); // bitwise symmetric under permutations of (X, Y, Z)
  std::array<double, 3> keep{}, flip{};
  int nk = 0, nf = 0;
  for (double v : u) {
    if (v >= 1.0) continue;
    if (v <= 0.0)
      keep[static_cast<std::size_t>(nk++)] = -v;
    else
      flip[static_cast<std::size_t>(nf++)] = v;
  }
  double s = 0.0;
  for (int m = 0; m < (1 << nf); ++m) {
    std::array<double, 3> d = keep;
    int n = nk;
    bool odd = false;
    for (int f = 0; f < nf; ++f)
      if ((m >> f) & 1) {
        d[static_cast<std::size_t>(n++)] = flip[static_cast<std::size_t>(f)];
        odd = !odd;
      }
    s += odd ? -unit_ball_above(d, n) : unit_ball_above(d, n);
  }
  return s * R * R * R;
}

double sphere_box_volume(const Vec3& c, double R, const std::array<double, 3>& lo,
                         const std::array<double, 3>& hi) {
  double v = 0.0;
  for (int m = 0; m < 8; ++m) {
    const double X = ((m & 1) ? hi[0] : lo[0]) - c[0];
    const double Y = ((m & 2) ? hi[1] : lo[1]) - c[1];
    const double Z = ((m & 4) ? hi[2] : lo[2]) - c[2];
    const int n_lo = !(m & 1) + !(m & 2) + !(m & 4);
    v += (n_lo % 2 ? -1.0 : 1.0) * ball_octant_volume(R, X, Y, Z);
  }
  return v;
}

double disc_rect_area(double cx, double cz, double R, double x0, double x1, double z0, double z1) {
  return disc_quadrant_area(R, x1 - cx, z1 - cz) - disc_quadrant_area(R, x0 - cx, z1 - cz) -
         disc_quadrant_area(R, x1 - cx, z0 - cz) + disc_quadrant_area(R, x0 - cx, z0 - cz);
}

double porosity_2d_to_3d(double eps_2d) {
  const double solid = std::max(1.0 - eps_2d, 0.0);
  return 1.0 - 2.0 / std::sqrt(pi * std::sqrt(3.0)) * solid * std::sqrt(solid);
}

namespace {
/// Interior index (1..n) of the unwrapped cell index i along a periodic axis of n cells.
int wrap_index(int i, int n) {
  return ((i - 1) % n + n) % n + 1;
}
/// Unclamped 1-based cell index of coordinate x along axis d.
int raw_cell(const gas::GasGrid& g, int d, double x) {
  return static_cast<int>(std::floor((x - g.lo[d]) / g.h[d])) + 1;
}

/// The cells of the sphere (x, R) along axis d into c0, c1 (unwrapped along a periodic axis).
/// Scalar outputs: a CellRange filled through a runtime axis index and then copied whole made the
/// copy wait on its partial stores (a store-forwarding stall, 30% of the porosity loop's time).
void covered_along(const gas::GasGrid& g, int d, double x, double R, bool wrap, int& c0, int& c1) {
  if (wrap) {
    c0 = raw_cell(g, d, x - R);
    c1 = raw_cell(g, d, x + R);
    return;
  }
  // GasGrid::cell_of along d alone.
  const auto cell = [&](double v) {
    const int i = static_cast<int>((v - g.lo[d]) / g.h[d]) + 1;
    return i < 1 ? 1 : (i > g.n[d] ? g.n[d] : i);
  };
  c0 = cell(x - R);
  c1 = cell(x + R);
}

CellRange covered_cells(const gas::GasGrid& g, const Vec3& x, double R, bool two_d,
                        const std::array<bool, 3>& wrap) {
  int x0 = 1, x1 = 1, y0 = 1, y1 = 1, z0 = 1, z1 = 1;
  covered_along(g, 0, x[0], R, wrap[0], x0, x1);
  if (!two_d) covered_along(g, 1, x[1], R, wrap[1], y0, y1);
  covered_along(g, 2, x[2], R, wrap[2], z0, z1);
  return CellRange{{x0, y0, z0}, {x1, y1, z1}};
}

/// [Deen07 eq. 33]: the exact volume (2-D: area) of sphere i inside each cell of its range,
/// divided by the cell measure `measure`, written to cell[e], part[e] from e = first on, cells in
/// the order k, j, i (i fastest). Each cell is the inclusion-exclusion of the ball octants (2-D:
/// disc quadrants) at its 8 (4) corners, as sphere_box_volume (disc_rect_area) does; a corner
/// is shared by up to 8 (4) cells, so the octant volume of each grid node of the range is
/// evaluated once (nodes at lo + (m - 1) h, m the cell whose low face they are on).
void sphere_cell_parts(const gas::GasGrid& g, const Vec3& x, double R, const CellRange& r,
                       bool two_d, const std::array<bool, 3>& wrap, double measure, long* cell,
                       double* part) {
  // Node offsets from the centre per axis (m = c0 .. c1 + 1).
  auto node = [&](int d, int m) { return g.lo[d] + (m - 1) * g.h[d] - x[d]; };
  // Grid index of cell (i, j, k) of the range, folded onto the domain along periodic axes.
  auto grid_index = [&](int i, int j, int k) {
    return g.idx(wrap[0] ? wrap_index(i, g.n[0]) : i, wrap[1] ? wrap_index(j, g.n[1]) : j,
                 wrap[2] ? wrap_index(k, g.n[2]) : k);
  };
  // A sphere whose cell faces cut it along one axis at most (inside one cell, or a bed one
  // particle deep between its walls, or a row of cells crossed along one axis only): each cell
  // holds the ball minus its caps beyond the cell's faces, which are disjoint,
  // V = 4/3 pi R^3 - sum pi h^2 (3R - h) / 3, h the cap height: the same volume as the octant
  // sums below in a few operations (the common case of the Tsuji beds, ~90% of the spheres).
  // A disc in the x-z plane (2-D) likewise: the disc minus its circular segments, a segment of
  // height h being R^2 theta - (R - h) s with s = sqrt(h (2R - h)), theta = atan2(s, R - h)
  // (half the angle it subtends), against four quadrant areas with two arcsines each per cell
  // (Hoomans' bubble bed, 10 x 20 mm cells and 4 mm discs: 92% of the discs). A segment's h is
  // at most 2R (the whole disc beyond the face); round-off makes it slightly larger for a disc
  // touching a face, and the root would be NaN.
  const auto segment = [R](double h) { // area of the disc's segment of height h > 0
    h = std::min(h, 2.0 * R);
    const double s = std::sqrt(h * (2.0 * R - h));
    return R * R * std::atan2(s, R - h) - (R - h) * s;
  };
  const auto minus_caps = [&](double v, double h_lo, double h_hi) { // caps of height h > 0
    for (double h : {h_lo, h_hi}) {
      if (!(h > 0.0)) continue;
      v -= two_d ? segment(h) : pi * h * h * (3.0 * R - h) / 3.0;
    }
    return v;
  };
  const auto is_axis = [two_d](int d) { return !(two_d && d == 1); }; // 2-D: x and z
  int along = -1, n_along = 0; // the axis along which the range has several cells
  for (int d = 0; d < 3; ++d)
    if (is_axis(d) && r.c1[d] > r.c0[d]) along = d, ++n_along;
  if (n_along <= 1) {
    // The whole ball (disc) minus the caps across the other axes' faces (a face of the range's
    // own cell cuts it where a domain wall clamps the range).
    int cut_axes = n_along;
    double v = two_d ? pi * R * R : 4.0 / 3.0 * pi * R * R * R;
    for (int d = 0; d < 3; ++d) {
      if (d == along || !is_axis(d)) continue;
      const double h_lo = R + node(d, r.c0[d]), h_hi = R - node(d, r.c0[d] + 1);
      if (h_lo <= 0.0 && h_hi <= 0.0) continue;
      ++cut_axes;
      v = minus_caps(v, h_lo, h_hi);
    }
    if (cut_axes <= 1 && n_along == 0) {
      cell[0] = grid_index(r.c0[0], r.c0[1], r.c0[2]);
      part[0] = v / measure;
      return;
    }
    if (cut_axes <= 1 && two_d && r.c1[along] == r.c0[along] + 1) {
      // A disc across one face: its two parts are the segment beyond the face on the smaller side
      // and the rest; one segment (one atan2) gives both.
      const double h1 = R - node(along, r.c0[along] + 1), h0 = R + node(along, r.c0[along] + 1);
      const bool small_in_c1 = h1 <= h0;
      const double seg = segment(std::max(small_in_c1 ? h1 : h0, 0.0));
      std::array<int, 3> c = r.c0;
      cell[0] = grid_index(c[0], c[1], c[2]);
      part[0] = std::max(small_in_c1 ? v - seg : seg, 0.0) / measure;
      ++c[along];
      cell[1] = grid_index(c[0], c[1], c[2]);
      part[1] = std::max(small_in_c1 ? seg : v - seg, 0.0) / measure;
      return;
    }
    if (cut_axes <= 1) {
      std::array<int, 3> c = r.c0;
      for (long e = 0; c[along] <= r.c1[along]; ++c[along], ++e) {
        const double w = minus_caps(v, R + node(along, c[along]), R - node(along, c[along] + 1));
        cell[e] = grid_index(c[0], c[1], c[2]);
        part[e] = std::max(w, 0.0) / measure;
      }
      return;
    }
  }
  if (two_d && r.c1[0] == r.c0[0] + 1 && r.c1[2] == r.c0[2] + 1 && R + node(0, r.c0[0]) <= 0.0 &&
      R - node(0, r.c1[0] + 1) <= 0.0 && R + node(2, r.c0[2]) <= 0.0 &&
      R - node(2, r.c1[2] + 1) <= 0.0) {
    // A disc across one face along x and one along z, inside the range's outer faces: the four
    // parts around the node (X, Z) where the faces cross from the quadrant below-left of it and
    // the parts below Z and left of X (a segment each): one quadrant and two segments instead of
    // the nine nodes of the table below.
    const double X = node(0, r.c0[0] + 1), Z = node(2, r.c0[2] + 1), disc = pi * R * R;
    const auto below = [&](double u) { return u >= 0.0 ? disc - segment(R - u) : segment(R + u); };
    const double q = disc_quadrant_area(R, X, Z), left = below(X), low = below(Z);
    const double parts[4] = {q, low - q, left - q, disc - left - low + q}; // i fastest, then k
    for (int m = 0; m < 4; ++m) {
      cell[m] = grid_index(r.c0[0] + (m & 1), r.c0[1], r.c0[2] + (m >> 1));
      part[m] = std::max(parts[m], 0.0) / measure;
    }
    return;
  }
  constexpr int max_nodes = 4; // per axis for the node table; larger ranges: corners directly
  std::array<int, 3> nn{};
  for (int d = 0; d < 3; ++d) nn[d] = r.c1[d] - r.c0[d] + 2;
  const bool table = two_d ? (nn[0] <= max_nodes && nn[2] <= max_nodes)
                           : (nn[0] <= max_nodes && nn[1] <= max_nodes && nn[2] <= max_nodes);
  std::array<double, max_nodes * max_nodes * max_nodes> oct{};
  auto at = [&](int a, int b, int c) { // table index of node (a, b, c), offsets from c0
    return static_cast<std::size_t>(a + max_nodes * (b + max_nodes * c));
  };
  if (table) {
    for (int c = 0; c < (two_d ? 1 : nn[2]); ++c)
      for (int b = 0; b < (two_d ? nn[2] : nn[1]); ++b)
        for (int a = 0; a < nn[0]; ++a) {
          if (two_d) // node (a, b) in x-z
            oct[at(a, b, 0)] = disc_quadrant_area(R, node(0, r.c0[0] + a), node(2, r.c0[2] + b));
          else
            oct[at(a, b, c)] = ball_octant_volume(R, node(0, r.c0[0] + a), node(1, r.c0[1] + b),
                                                  node(2, r.c0[2] + c));
        }
  }
  long e = 0;
  for (int k = r.c0[2]; k <= r.c1[2]; ++k)
    for (int j = r.c0[1]; j <= r.c1[1]; ++j)
      for (int ii = r.c0[0]; ii <= r.c1[0]; ++ii, ++e) {
        const int a = ii - r.c0[0], b = j - r.c0[1], c = k - r.c0[2];
        double v = 0.0;
        if (two_d) {
          // disc_rect_area: Q(x1, z1) - Q(x0, z1) - Q(x1, z0) + Q(x0, z0).
          auto Q = [&](int da, int dc) {
            return table ? oct[at(a + da, c + dc, 0)]
                         : disc_quadrant_area(R, node(0, ii + da), node(2, k + dc));
          };
          v = Q(1, 1) - Q(0, 1) - Q(1, 0) + Q(0, 0);
        } else {
          // sphere_box_volume: corner m (bit set: high side), sign (-1)^(low sides).
          for (int m = 0; m < 8; ++m) {
            const int da = m & 1, db = (m >> 1) & 1, dc = (m >> 2) & 1;
            const double o =
                table ? oct[at(a + da, b + db, c + dc)]
                      : ball_octant_volume(R, node(0, ii + da), node(1, j + db), node(2, k + dc));
            const int n_lo = 3 - da - db - dc;
            v += (n_lo % 2 ? -1.0 : 1.0) * o;
          }
        }
        cell[e] = grid_index(ii, j, k);
        part[e] = v / measure;
      }
}
/// Fixed-point solid fraction: a particle's part of a cell is at most its measure (volume, 2-D:
/// area) over the cell's.
void start_fixed_sum(const gas::GasGrid& g, const ParticleStore& p, bool two_d, double cell_measure,
                     const RankSum& ranks, FixedPointSum& fixed) {
  double largest = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double R = p.radius[i];
    const double measure = two_d ? pi * R * R : 4.0 / 3.0 * pi * R * R * R;
    largest = std::isnan(measure) ? measure : std::max(largest, measure / cell_measure);
    if (std::isnan(largest)) break;
  }
  const double bounds[1] = {largest};
  fixed.start(g.size(), bounds, static_cast<std::int64_t>(p.size()), ranks);
}

void finish_fixed_sum(const RankSum& ranks, FixedPointSum& fixed, std::vector<double>& out) {
  fixed.reduce(ranks);
  fixed.result(0, out);
}
} // namespace

void solid_fraction(const gas::GasGrid& g, const ParticleStore& p, const PorositySettings& s,
                    std::vector<double>& out, const std::array<bool, 3>& periodic) {
  PorosityScratch scratch;
  solid_fraction(g, p, s, out, periodic, scratch);
}

void solid_fraction(const gas::GasGrid& g, const ParticleStore& p, const PorositySettings& s,
                    std::vector<double>& out, const std::array<bool, 3>& periodic,
                    PorosityScratch& scratch, const RankSum* ranks) {
  out.assign(g.size(), 0.0);
  const bool two_d = g.dimension == 2;
  const std::array<int, 3> axes_3d{0, 1, 2};
  const int na = two_d ? 2 : 3;
  const std::array<int, 3> axes = two_d ? std::array<int, 3>{0, 2, 1} : axes_3d;
  // 2-D: solid area per unit cell area; 3-D: solid volume per cell volume.
  const double cell_measure = two_d ? g.h[0] * g.h[2] : g.cell_volume();
  std::array<bool, 3> wrap{};
  for (int m = 0; m < na; ++m) {
    const int d = axes[static_cast<std::size_t>(m)];
    wrap[d] = periodic[d];
  }
  if (s.method == PorosityMethod::porous_cube) {
    // [Deen07 eq. 36-37]: the cube of side a d carries the particle's volume (2-D: disc area)
    // spread uniformly; the cell gets the fraction of the cube inside it, the weights of
    // cube_mapping.hpp (shifted into the domain at walls, wrapped at periodic axes).
    CubeAxes& a = scratch.cube.axes;
    if (ranks) start_fixed_sum(g, p, two_d, cell_measure, *ranks, scratch.fixed);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double R = p.radius[i];
      const double measure = two_d ? pi * R * R : 4.0 / 3.0 * pi * R * R * R;
      cube_axes(g, cell_component, p.position(i), s.cube_factor * R, wrap, a);
      for_cube_weights(g, a, cell_component, [&](long q, double w) {
        const double part = measure * w / cell_measure;
        if (ranks)
          scratch.fixed.add(0, static_cast<std::size_t>(q), part);
        else
          out[static_cast<std::size_t>(q)] += part;
      });
    }
    if (ranks) finish_fixed_sum(*ranks, scratch.fixed, out);
    return;
  }
  // Cell method: each particle's parts are computed independently (threaded), then added to
  // the cells in particle order by one thread, so the sums do not depend on the thread count.
  const std::size_t n = p.size();
  std::vector<long>& offset = scratch.offset;
  std::vector<CellRange>& range = scratch.range;
  offset.resize(n + 1);
  range.resize(n);
  offset[0] = 0;
  const bool threaded = threaded_particles(n);
  parallel_for(n, threaded, [&](std::size_t i) {
    const CellRange r = covered_cells(g, p.position(i), p.radius[i], two_d, wrap);
    range[i] = r;
    offset[i + 1] = (r.c1[0] - r.c0[0] + 1) * (r.c1[1] - r.c0[1] + 1) * (r.c1[2] - r.c0[2] + 1);
  });
  for (std::size_t i = 0; i < n; ++i) offset[i + 1] += offset[i];
  const auto total = static_cast<std::size_t>(offset[n]);
  if (scratch.cell.size() < total) { // with slack: the count changes a little from step to step
    scratch.cell.resize(total + total / 4);
    scratch.part.resize(total + total / 4);
  }
  long* cell = scratch.cell.data();
  double* part = scratch.part.data();
  parallel_for(n, threaded, [&](std::size_t i) {
    const Vec3 x = p.position(i);
    const double R = p.radius[i];
    sphere_cell_parts(g, x, R, range[i], two_d, wrap, cell_measure, cell + offset[i],
                      part + offset[i]);
  });
  if (ranks) {
    start_fixed_sum(g, p, two_d, cell_measure, *ranks, scratch.fixed);
    for (std::size_t e = 0; e < total; ++e)
      scratch.fixed.add(0, static_cast<std::size_t>(cell[e]), part[e]);
    finish_fixed_sum(*ranks, scratch.fixed, out);
    return;
  }
  for (std::size_t e = 0; e < total; ++e) out[static_cast<std::size_t>(cell[e])] += part[e];
}

void compute_porosity(const gas::GasGrid& g, const ParticleStore& p, const PorositySettings& s,
                      std::vector<double>& eps, const std::array<bool, 3>& periodic) {
  PorosityScratch scratch;
  compute_porosity(g, p, s, eps, periodic, scratch);
}

void compute_porosity(const gas::GasGrid& g, const ParticleStore& p, const PorositySettings& s,
                      std::vector<double>& eps, const std::array<bool, 3>& periodic,
                      PorosityScratch& scratch, const RankSum* ranks) {
  std::vector<double>& solid = scratch.solid;
  solid_fraction(g, p, s, solid, periodic, scratch, ranks);
  eps.resize(g.size(), 1.0);
  for (int k = 1; k <= g.n[2]; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i) {
        const auto q = static_cast<std::size_t>(g.idx(i, j, k));
        const double e = g.dimension == 2 ? porosity_2d_to_3d(1.0 - solid[q]) : 1.0 - solid[q];
        if (!(e >= min_porosity))
          throw InstabilityError(
              "porosity " + std::to_string(e) + " (no gas) in gas cell (" + std::to_string(i) +
              ", " + std::to_string(j) + ", " + std::to_string(k) +
              "): overlapping particles, or gas cells smaller than the particles (use larger "
              "cells or coupling.porosity = \"porous_cube\")");
        eps[q] = e;
      }
  // Periodic axes: the ghost cells hold the images (ghost 0 = cell n, ghost n + 1 = cell 1), as
  // the gas solver keeps them, so that the cell-centre stencil may read them.
  std::array<bool, 3> wrap = periodic;
  if (g.dimension == 2) wrap[1] = false;
  gas::fill_periodic_ghosts(g, wrap, eps);
}

} // namespace fluidem::coupling
