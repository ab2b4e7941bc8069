#include "coupling/porosity.hpp"
#include "core/error.hpp"
#include <algorithm>
#include <cmath>
#include <string>

namespace fluidem::coupling {

namespace {
constexpr double pi = 3.14159265358979323846;

/// Nodes and weights of tanh-sinh quadrature on [-1, 1] (step 1/16, |t| <= 3.2), with the
/// distance of each node to its nearer end stored separately (no cancellation near the ends).
struct TanhSinh {
  static constexpr int half = 51; // t = k h, k = -half..half
  std::array<double, 2 * half + 1> gap{}, sign{}, w{};
  TanhSinh() {
    const double h = 1.0 / 16.0;
    for (int k = -half; k <= half; ++k) {
      const double t = k * h;
      const double u = 0.5 * pi * std::sinh(t);
      const double c = std::cosh(u);
      const std::size_t n = static_cast<std::size_t>(k + half);
      gap[n] = 1.0 / (std::exp(2.0 * std::abs(u)) + 1.0) * 2.0; // 1 - |tanh u|
      sign[n] = k < 0 ? -1.0 : 1.0;
      w[n] = h * 0.5 * pi * std::cosh(t) / (c * c);
    }
  }
};
const TanhSinh& tanh_sinh() {
  static const TanhSinh q;
  return q;
}

/// Integral of f over [a, b] by tanh-sinh (endpoint algebraic singularities are harmless).
template <class F>
double integrate(F&& f, double a, double b) {
  if (!(b > a)) return 0.0;
  const TanhSinh& q = tanh_sinh();
  const double hw = 0.5 * (b - a);
  double s = 0.0;
  for (std::size_t n = 0; n < q.w.size(); ++n) {
    const double x = q.sign[n] < 0.0 ? a + hw * q.gap[n] : b - hw * q.gap[n];
    s += q.w[n] * f(x);
  }
  return s * hw;
}

/// Volume of the ball of radius R with x < X (spherical cap or its complement).
double ball_below(double R, double X) {
  X = std::clamp(X, -R, R);
  return pi * (R * R * (X + R) - (X * X * X + R * R * R) / 3.0);
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
  auto two_s = [&](double a, double b) {
    b = std::min(b, Y);
    return b > a ? 2.0 * (P(b) - P(a)) : 0.0;
  };
  auto z_plus_s = [&](double a, double b) {
    b = std::min(b, Y);
    return b > a ? Z * (b - a) + P(b) - P(a) : 0.0;
  };
  if (Z >= 0.0) return two_s(-r, -yz) + z_plus_s(-yz, yz) + two_s(yz, r);
  return z_plus_s(-yz, yz);
}

double ball_octant_volume(double R, double X, double Y, double Z) {
  if (!(R > 0.0) || X <= -R || Y <= -R || Z <= -R) return 0.0;
  std::array<double, 3> c{std::min(X, R), std::min(Y, R), std::min(Z, R)};
  // Integrate along the axis of the largest bound; the others cut the slices.
  std::sort(c.begin(), c.end());
  const double Xe = c[2], Ya = c[0], Za = c[1];
  if (Za >= R) return ball_below(R, Ya); // one plane: spherical cap (closed form)
  // Breakpoints of A(r(x), Ya, Za), r(x)^2 = R^2 - x^2: r = |Ya|, r = |Za|, r^2 = Ya^2 + Za^2.
  std::array<double, 8> br{};
  int nb = 0;
  br[static_cast<std::size_t>(nb++)] = -R;
  for (double r2 : {R * R - Ya * Ya, R * R - Za * Za, R * R - Ya * Ya - Za * Za})
    if (r2 > 0.0) {
      const double xb = std::sqrt(r2);
      for (double x : {-xb, xb})
        if (x > -R && x < Xe) br[static_cast<std::size_t>(nb++)] = x;
    }
  br[static_cast<std::size_t>(nb++)] = Xe;
  for (int a = 1; a < nb; ++a) // insertion sort (std::sort trips GCC 12's -Warray-bounds)
    for (int b = a; b > 0 && br[static_cast<std::size_t>(b - 1)] > br[static_cast<std::size_t>(b)];
         --b)
      std::swap(br[static_cast<std::size_t>(b - 1)], br[static_cast<std::size_t>(b)]);
  auto area = [&](double x) {
    return disc_quadrant_area(std::sqrt(std::max(R * R - x * x, 0.0)), Ya, Za);
  };
  double v = 0.0;
  for (int m = 0; m + 1 < nb; ++m)
    v += integrate(area, br[static_cast<std::size_t>(m)], br[static_cast<std::size_t>(m + 1)]);
  return v;
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

void solid_fraction(const gas::GasGrid& g, const ParticleStore& p, const PorositySettings& s,
                    std::vector<double>& out) {
  out.assign(g.size(), 0.0);
  const bool two_d = g.dimension == 2;
  const std::array<int, 3> axes_3d{0, 1, 2};
  const int na = two_d ? 2 : 3;
  const std::array<int, 3> axes = two_d ? std::array<int, 3>{0, 2, 1} : axes_3d;
  // 2-D: solid area per unit cell area; 3-D: solid volume per cell volume.
  const double cell_measure = two_d ? g.h[0] * g.h[2] : g.cell_volume();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 x = p.position(i);
    const double R = p.radius[i];
    // Half extent of the particle's footprint, and (cube) its centre shifted into the domain.
    const double half = s.method == PorosityMethod::porous_cube ? 0.5 * s.cube_factor * 2.0 * R : R;
    Vec3 c = x;
    std::array<int, 3> c0{1, 1, 1}, c1{1, 1, 1};
    for (int m = 0; m < na; ++m) {
      const int d = axes[static_cast<std::size_t>(m)];
      const double lo = g.lo[d], hi = g.lo[d] + g.n[d] * g.h[d];
      if (s.method == PorosityMethod::porous_cube && hi - lo >= 2.0 * half)
        c[d] = std::clamp(c[d], lo + half, hi - half);
      Vec3 a = c, b = c;
      a[d] -= half;
      b[d] += half;
      c0[d] = g.cell_of(a)[d];
      c1[d] = g.cell_of(b)[d];
    }
    const double measure = two_d ? pi * R * R : 4.0 / 3.0 * pi * R * R * R;
    const double cube_measure = two_d ? 4.0 * half * half : 8.0 * half * half * half;
    for (int k = c0[2]; k <= c1[2]; ++k)
      for (int j = c0[1]; j <= c1[1]; ++j)
        for (int ii = c0[0]; ii <= c1[0]; ++ii) {
          std::array<double, 3> blo{}, bhi{};
          const std::array<int, 3> ijk{ii, j, k};
          for (int d = 0; d < 3; ++d) {
            blo[d] = g.lo[d] + (ijk[d] - 1) * g.h[d];
            bhi[d] = blo[d] + g.h[d];
          }
          double part = 0.0;
          if (s.method == PorosityMethod::cell) {
            part = two_d ? disc_rect_area(c[0], c[2], R, blo[0], bhi[0], blo[2], bhi[2])
                         : sphere_box_volume(c, R, blo, bhi);
          } else {
            double ov = 1.0;
            for (int m = 0; m < na; ++m) {
              const int d = axes[static_cast<std::size_t>(m)];
              ov *= std::max(0.0, std::min(bhi[d], c[d] + half) - std::max(blo[d], c[d] - half));
            }
            part = measure * ov / cube_measure; // [Deen07 eq. 36-37]
          }
          out[static_cast<std::size_t>(g.idx(ii, j, k))] += part / cell_measure;
        }
  }
}

void compute_porosity(const gas::GasGrid& g, const ParticleStore& p, const PorositySettings& s,
                      std::vector<double>& eps) {
  std::vector<double> solid;
  solid_fraction(g, p, s, solid);
  eps.resize(g.size(), 1.0);
  for (int k = 1; k <= g.n[2]; ++k)
    for (int j = 1; j <= g.n[1]; ++j)
      for (int i = 1; i <= g.n[0]; ++i) {
        const auto q = static_cast<std::size_t>(g.idx(i, j, k));
        const double e = g.dimension == 2 ? porosity_2d_to_3d(1.0 - solid[q]) : 1.0 - solid[q];
        if (!(e > 0.0))
          throw InstabilityError("porosity " + std::to_string(e) + " <= 0 in gas cell (" +
                                 std::to_string(i) + ", " + std::to_string(j) + ", " +
                                 std::to_string(k) + "): overlapping particles");
        eps[q] = e;
      }
}

} // namespace fluidem::coupling
