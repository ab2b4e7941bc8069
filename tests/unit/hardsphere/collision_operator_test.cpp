// The binary collision operator hardsphere::collide() against closed-form results derived here,
// independently of the operator's own formulas, from Newton's laws for two rigid spheres and
// the three-parameter collision model [Deen07 eq. 13-21; Hoomans96 eq. 1-29]:
//
//   Geometry: n is the unit normal from b to a; the contact point is x_c = x_a - R_a n =
//   x_b + R_b n. Contact-point velocity of a relative to b (rigid-body kinematics):
//     u = (v_a + w_a x (x_c - x_a)) - (v_b + w_b x (x_c - x_b)),  u_n = u.n,  u_t = u - u_n n.
//   Newton: an impulse J acts on a at x_c and -J on b at x_c:
//     m_a dv_a = J,  I_a dw_a = (x_c - x_a) x J,  m_b dv_b = -J,  I_b dw_b = (x_c - x_b) x (-J).
//   Model, 1/m_ab = 1/m_a + 1/m_b (a wall: m_b = infinity, m_ab = m_a), solid spheres
//   I = 2/5 m R^2:
//     J_n = -(1 + e) m_ab u_n                                 (normal restitution e)
//     sticking, mu J_n >= 2/7 (1 + beta0) m_ab |u_t|:  J_t = -2/7 (1 + beta0) m_ab u_t
//     sliding otherwise:                               J_t = -mu J_n u_t/|u_t|
//   so that after the collision u_n' = -e u_n and, when sticking, u_t' = -beta0 u_t.
//   Energy: the kinetic energy of two rigid bodies changes by dE = J.(u + u')/2 under an impulse
//   pair at the contact point, which gives the dissipated energy (cf. [Hoomans96 eq. 23, 27,
//   29]), with m_t = 2/7 m_ab:
//     normal part     1/2 m_ab (1 - e^2) u_n^2
//     sticking        1/2 m_t (1 - beta0^2) |u_t|^2 = 1/7 m_ab (1 - beta0^2) |u_t|^2
//     sliding         mu J_n |u_t| - (mu J_n)^2 / (2 m_t)
//
// Checks and tolerances, for every collision below:
//  * post-collision v and w of both bodies equal the Newton/model reference within 1e-12
//    relative (of the largest speed in the problem, V; angular velocities of V/R);
//  * the post-collision contact velocity is u_n' = -e u_n and u_t' = -beta0 u_t (sticking) or
//    u_t (1 - mu J_n/(m_t |u_t|)) (sliding), within 1e-12 of V;
//  * linear momentum (pairs) is conserved to round-off: 1e-14 of sum m|v| + |J|;
//  * angular momentum about the contact point, sum (x_i - x_c) x m_i v_i + I_i w_i, is conserved
//    to round-off (1e-14 of the sum of the magnitudes of its terms), for a wall the particle's
//    own (the wall's reaction acts at x_c);
//  * the kinetic energy lost (computed from the velocities) is >= 0 (to round-off, 1e-14 of the
//    initial energy) and equals the closed form above within 1e-12 of the initial energy;
//  * the regime (sticking/sliding) flag is the one of the criterion above.
// A separating or grazing pair (u_n >= 0) must come back bit-for-bit unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include <fmt/format.h>

#include "hardsphere/collision_operator.hpp"

namespace fluidem {
namespace {

using hardsphere::Body;
using hardsphere::CollisionLaw;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A solid sphere, or a wall (m = infinity).
struct Sphere {
  double m = kInf;
  double r = 0.0;
  Vec3 v, w;
  bool wall() const { return std::isinf(m); }
  double inertia() const { return 0.4 * m * r * r; }
};

Sphere ball(double m, double r, const Vec3& v, const Vec3& w = {}) {
  return {m, r, v, w};
}
Sphere a_wall() {
  return {};
}

Body body_of(const Sphere& s) {
  if (s.wall()) return Body{{}, {}, s.r, 0.0, 0.0};
  return Body{s.v, s.w, s.r, 1.0 / s.m, 1.0 / s.inertia()};
}

struct Reference {
  Sphere a, b; // after the collision
  Vec3 j;      // impulse on a
  Vec3 u0, u1; // contact velocity before and after
  bool sliding = false;
  double dissipated = 0.0; // closed form
};

Vec3 contact_velocity_of(const Sphere& a, const Sphere& b, const Vec3& n) {
  const Vec3 ca = n * -a.r; // x_c - x_a
  const Vec3 cb = n * b.r;  // x_c - x_b
  return (a.v + cross(a.w, ca)) - (b.v + cross(b.w, cb));
}

Reference reference(const Sphere& a, const Sphere& b, const Vec3& n, const CollisionLaw& law) {
  Reference ref;
  ref.a = a;
  ref.b = b;
  const Vec3 u = contact_velocity_of(a, b, n);
  ref.u0 = u;
  const double un = dot(u, n);
  const Vec3 ut = u - n * un;
  const double ut_abs = norm(ut);
  const double mab = b.wall() ? a.m : a.m * b.m / (a.m + b.m);
  const double mt = 2.0 / 7.0 * mab;
  const double jn = -(1.0 + law.e_n) * mab * un;
  Vec3 jt;
  double lost_t = 0.0;
  if (law.mu * jn >= 2.0 / 7.0 * (1.0 + law.beta0) * mab * ut_abs) {
    jt = ut * (-2.0 / 7.0 * (1.0 + law.beta0) * mab);
    lost_t = mab / 7.0 * (1.0 - law.beta0 * law.beta0) * ut_abs * ut_abs;
    ref.u1 = n * (-law.e_n * un) - ut * law.beta0;
  } else {
    ref.sliding = true;
    jt = ut * (-law.mu * jn / ut_abs);
    lost_t = law.mu * jn * ut_abs - law.mu * law.mu * jn * jn / (2.0 * mt);
    ref.u1 = n * (-law.e_n * un) + ut * (1.0 - law.mu * jn / (mt * ut_abs));
  }
  ref.dissipated = 0.5 * mab * (1.0 - law.e_n * law.e_n) * un * un + lost_t;
  ref.j = n * jn + jt;
  // Newton's laws for the impulse J on a at x_c and -J on b at x_c.
  ref.a.v = a.v + ref.j / a.m;
  ref.a.w = a.w + cross(n * -a.r, ref.j) / a.inertia();
  if (!b.wall()) {
    ref.b.v = b.v - ref.j / b.m;
    ref.b.w = b.w + cross(n * b.r, -ref.j) / b.inertia();
  }
  return ref;
}

double kinetic(const Sphere& s) {
  return s.wall() ? 0.0 : 0.5 * s.m * norm2(s.v) + 0.5 * s.inertia() * norm2(s.w);
}

/// Angular momentum about the contact point x_c, and the sum of its terms' magnitudes (scale).
struct Moment {
  Vec3 l;
  double scale = 0.0;
};
Moment angular_momentum(const Sphere& a, const Sphere& b, const Vec3& n) {
  Moment m;
  auto add = [&](const Sphere& s, const Vec3& arm) { // arm = x_i - x_c
    if (s.wall()) return;
    const Vec3 orbital = cross(arm, s.v * s.m);
    const Vec3 spin = s.w * s.inertia();
    m.l += orbital + spin;
    m.scale += norm(orbital) + norm(spin);
  };
  add(a, n * a.r);
  add(b, n * -b.r);
  return m;
}

struct Outcome {
  Sphere a, b;
  hardsphere::CollisionResult res;
};

/// Run the operator on copies of a and b; check everything listed at the top of the file
/// against the reference; return the result for test-specific checks.
Outcome check_collision(const Sphere& a, const Sphere& b, const Vec3& n, const CollisionLaw& law) {
  const Reference ref = reference(a, b, n, law);
  EXPECT_LT(dot(ref.u0, n), 0.0) << "test set-up: the bodies must approach";
  Body ba = body_of(a), bb = body_of(b);
  const auto res = hardsphere::collide(ba, bb, n, law);
  Outcome out{a, b, res};
  out.a.v = ba.v, out.a.w = ba.w;
  if (!b.wall()) out.b.v = bb.v, out.b.w = bb.w;

  EXPECT_TRUE(res.approaching);
  EXPECT_EQ(res.sliding, ref.sliding);

  // Velocity scale V: the largest speed in the problem.
  double vs = std::max({norm(a.v), a.r * norm(a.w), norm(ref.u0)});
  if (!b.wall()) vs = std::max({vs, norm(b.v), b.r * norm(b.w)});
  const double tol = 1e-12 * vs;
  auto near = [&](const Vec3& got, const Vec3& want, double t, const char* what) {
    EXPECT_LE(norm(got - want), t)
        << what << ": got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x
        << ", " << want.y << ", " << want.z << ")";
  };
  near(out.a.v, ref.a.v, tol, "v_a");
  near(out.a.w, ref.a.w, tol / a.r, "w_a");
  if (b.wall()) {
    EXPECT_EQ(norm2(bb.v), 0.0) << "the wall must not move";
    EXPECT_EQ(norm2(bb.w), 0.0) << "the wall must not turn";
  } else {
    near(out.b.v, ref.b.v, tol, "v_b");
    near(out.b.w, ref.b.w, tol / b.r, "w_b");
  }
  near(res.impulse, ref.j, 1e-12 * norm(ref.j), "impulse J");
  near(contact_velocity_of(out.a, out.b, n), ref.u1, tol, "post-collision contact velocity");

  // Linear momentum of a pair.
  if (!b.wall()) {
    const Vec3 p0 = a.v * a.m + b.v * b.m, p1 = out.a.v * a.m + out.b.v * b.m;
    const double scale = a.m * norm(a.v) + b.m * norm(b.v) + norm(ref.j);
    EXPECT_LE(norm(p1 - p0), 1e-14 * scale) << "linear momentum";
  }
  // Angular momentum about the contact point.
  const Moment l0 = angular_momentum(a, b, n), l1 = angular_momentum(out.a, out.b, n);
  EXPECT_LE(norm(l1.l - l0.l), 1e-14 * std::max(l0.scale, l1.scale))
      << "angular momentum about the contact point";

  // Energy.
  const double e0 = kinetic(a) + kinetic(b);
  const double lost = e0 - kinetic(out.a) - kinetic(out.b);
  EXPECT_GE(ref.dissipated, 0.0);
  EXPECT_GE(lost, -1e-14 * e0) << "a collision must not create energy";
  EXPECT_NEAR(lost, ref.dissipated, 1e-12 * e0) << "dissipated energy";
  return out;
}

/// Orthonormal frame (n, t1, t2) with n = normalize(n0) and t1 in the plane of n0 and hint.
struct Frame {
  Vec3 n, t1, t2;
  Vec3 operator()(double cn, double c1, double c2) const { return n * cn + t1 * c1 + t2 * c2; }
};
Frame frame(const Vec3& n0, const Vec3& hint) {
  Frame f;
  f.n = n0 / norm(n0);
  const Vec3 t = hint - f.n * dot(hint, f.n);
  f.t1 = t / norm(t);
  f.t2 = cross(f.n, f.t1);
  return f;
}

// Glass-like spheres: d = 4 mm, 2700 kg/m^3.
constexpr double kR = 0.002;
const double kM = 4.0 / 3.0 * std::numbers::pi * kR * kR * kR * 2700.0;
const Frame kX = frame({1.0, 0.0, 0.0}, {0.0, 1.0, 0.0});      // n = x, t1 = y
const Frame kSkew = frame({1.0, 2.0, -2.0}, {3.0, -1.0, 0.5}); // a generic orientation

// --- Head-on --------------------------------------------------------------------------------

TEST(CollisionOperator, HeadOnReboundIsE) {
  // Textbook 1-D collision (momentum + restitution): with v = velocities along n,
  //   v_a' = (m_a v_a + m_b v_b - m_b e (v_a - v_b)) / (m_a + m_b), and b symmetrically.
  for (const double e : {1.0, 0.9, 0.5, 0.0}) {
    for (const Frame& f : {kX, kSkew}) {
      SCOPED_TRACE(fmt::format("e = {}", e));
      const double ma = kM, mb = 3.0 * kM, va = -1.5, vb = 0.5; // a approaches b along -n
      const auto out = check_collision(ball(ma, kR, f(va, 0, 0)), ball(mb, 1.5 * kR, f(vb, 0, 0)),
                                       f.n, {e, 0.3, 0.0});
      const double va1 = (ma * va + mb * vb - mb * e * (va - vb)) / (ma + mb);
      const double vb1 = (ma * va + mb * vb - ma * e * (vb - va)) / (ma + mb);
      EXPECT_NEAR(dot(out.a.v, f.n), va1, 1e-12 * 1.5);
      EXPECT_NEAR(dot(out.b.v, f.n), vb1, 1e-12 * 1.5);
      EXPECT_NEAR((dot(out.a.v, f.n) - dot(out.b.v, f.n)) / (va - vb), -e, 1e-12)
          << "rebound: separation speed = e x approach speed";
      EXPECT_LE(norm(out.a.w) + norm(out.b.w), 1e-12) << "no spin from a head-on impact";
      EXPECT_FALSE(out.res.sliding);
    }
  }
}

// --- Oblique, sticking --------------------------------------------------------------------------

TEST(CollisionOperator, ObliqueStickingBeta0StopsTheContactPoint) {
  // u_n = -2, u_t = 0.5: mu J_n = 0.5 * 1.9 * 2 m_ab = 1.9 m_ab >= 2/7 * 0.5 m_ab: sticking.
  for (const Frame& f : {kX, kSkew}) {
    const Sphere a = ball(kM, kR, f(-2.0, 0.5, 0.0)), b = ball(kM, kR, {});
    const auto out = check_collision(a, b, f.n, {0.9, 0.5, 0.0});
    EXPECT_FALSE(out.res.sliding);
    const Vec3 u1 = contact_velocity_of(out.a, out.b, f.n);
    EXPECT_NEAR(dot(u1, f.t1), 0.0, 1e-12 * 2.0) << "beta0 = 0: the contact point stops";
    EXPECT_NEAR(dot(u1, f.t2), 0.0, 1e-12 * 2.0);
    EXPECT_NEAR(dot(u1, f.n), 0.9 * 2.0, 1e-12 * 2.0);
  }
}

TEST(CollisionOperator, ObliqueStickingBeta04ReversesTheContactPoint) {
  for (const Frame& f : {kX, kSkew}) {
    const Sphere a = ball(kM, kR, f(-2.0, 0.5, -0.3)), b = ball(kM, kR, {});
    const auto out = check_collision(a, b, f.n, {0.9, 0.5, 0.4});
    EXPECT_FALSE(out.res.sliding);
    const Vec3 u1 = contact_velocity_of(out.a, out.b, f.n);
    EXPECT_NEAR(dot(u1, f.t1), -0.4 * 0.5, 1e-12 * 2.0) << "u_t' = -beta0 u_t";
    EXPECT_NEAR(dot(u1, f.t2), -0.4 * -0.3, 1e-12 * 2.0);
  }
}

// --- Oblique, sliding -----------------------------------------------------------------------

TEST(CollisionOperator, ObliqueSlidingTangentialImpulseIsMuJn) {
  // u_n = -1, |u_t| = 3, mu = 0.1: mu J_n = 0.19 m_ab < 2/7 * 3 m_ab = 0.857 m_ab: sliding.
  for (const Frame& f : {kX, kSkew}) {
    const Sphere a = ball(kM, kR, f(-1.0, 3.0, 0.0)), b = ball(kM, kR, {});
    const auto out = check_collision(a, b, f.n, {0.9, 0.1, 0.4});
    EXPECT_TRUE(out.res.sliding);
    const double jn = dot(out.res.impulse, f.n);
    const Vec3 jt = out.res.impulse - f.n * jn;
    EXPECT_NEAR(norm(jt), 0.1 * jn, 1e-12 * jn) << "|J_t| = mu J_n";
    EXPECT_NEAR(dot(jt, f.t1), -norm(jt), 1e-12 * jn) << "J_t opposes u_t";
  }
}

TEST(CollisionOperator, InfiniteFrictionSticksAtAnyAngle) {
  // friction = inf: the sticking limit of the operator (perfectly rough spheres for beta0 = 1).
  // A grazing impact, |u_t| / |u_n| = 1000, would slide with any finite mu below 2/7 (1 + beta0)
  // * 1000 / (1 + e) = 188; with mu = inf the contact point's tangential velocity is reversed by
  // -beta0 (the reference's sticking branch, in pairs and on a wall).
  for (const double beta0 : {0.0, 0.4, 1.0}) {
    SCOPED_TRACE(fmt::format("beta0 = {}", beta0));
    for (const Frame& f : {kX, kSkew}) {
      const Sphere a = ball(kM, kR, f(-0.01, 10.0, 0.0)), b = ball(2.0 * kM, kR, {});
      const auto out = check_collision(a, b, f.n, {0.9, kInf, beta0});
      EXPECT_FALSE(out.res.sliding);
      const Vec3 u1 = contact_velocity_of(out.a, out.b, f.n);
      EXPECT_NEAR(dot(u1, f.t1), -beta0 * 10.0, 1e-12 * 10.0) << "u_t' = -beta0 u_t";
      const auto wall = check_collision(a, a_wall(), f.n, {0.9, kInf, beta0});
      EXPECT_FALSE(wall.res.sliding);
    }
  }
}

TEST(CollisionOperator, BothSidesOfTheStickingSlidingBoundary) {
  // Critical tangential speed: mu (1 + e) m_ab |u_n| = 2/7 (1 + beta0) m_ab |u_t*|. Just below it
  // the collision sticks, just above it slides; the two impulses differ by the relative margin
  // (1e-6), far above the 1e-12 tolerance, so a wrong branch fails the velocity checks.
  for (const double beta0 : {0.0, 0.35}) {
    const double e = 0.8, mu = 0.2, un = 1.3;
    const double ut_crit = mu * (1.0 + e) * un / (2.0 / 7.0 * (1.0 + beta0));
    for (const double side : {1.0 - 1e-6, 1.0 + 1e-6}) {
      SCOPED_TRACE(fmt::format("beta0 = {}, |u_t| / |u_t*| = {}", beta0, side));
      const Sphere a = ball(kM, kR, kSkew(-un, side * ut_crit, 0.0)), b = ball(kM, kR, {});
      const auto out = check_collision(a, b, kSkew.n, {e, mu, beta0});
      EXPECT_EQ(out.res.sliding, side > 1.0);
    }
  }
}

// --- Unequal masses and radii, spinning particles ----------------------------------------------

TEST(CollisionOperator, UnequalMassesAndRadiiSpinning) {
  // a: twice the radius of b and 3 times its mass (different densities); both spin about
  // arbitrary axes (with components along n: a twist that no impulse at x_c can change).
  const Sphere a = ball(3.0 * kM, 2.0 * kR, kSkew(-0.7, 0.2, -0.4), {120.0, -340.0, 75.0});
  const Sphere b = ball(kM, kR, kSkew(0.6, -0.3, 0.1), {-500.0, 210.0, 900.0});
  int sliding = 0, sticking = 0;
  for (const double mu : {0.05, 0.2, 1.0}) {
    for (const double beta0 : {0.0, 0.4, 1.0}) {
      SCOPED_TRACE(fmt::format("mu = {}, beta0 = {}", mu, beta0));
      const auto out = check_collision(a, b, kSkew.n, {0.7, mu, beta0});
      (out.res.sliding ? sliding : sticking)++;
      // Spin about n is untouched: I dw = (x_c - x) x J is normal to n.
      EXPECT_NEAR(dot(out.a.w, kSkew.n), dot(a.w, kSkew.n), 1e-12 * norm(a.w));
      EXPECT_NEAR(dot(out.b.w, kSkew.n), dot(b.w, kSkew.n), 1e-12 * norm(b.w));
    }
  }
  EXPECT_GT(sliding, 0) << "both regimes must be covered";
  EXPECT_GT(sticking, 0) << "both regimes must be covered";
}

TEST(CollisionOperator, RandomPairsInRandomFrames) {
  // 2000 random collisions: masses 0.1-10 m0, radii 0.3-3 R0, random velocities, spins,
  // normals and coefficients. Every check of the file applies to each.
  std::mt19937_64 rng(2007);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  int sliding = 0, sticking = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 n0{u(rng), u(rng), u(rng)};
    if (norm(n0) < 0.1) continue;
    const Vec3 n = n0 / norm(n0);
    const double ra = kR * std::pow(10.0, u(rng) * 0.5), rb = kR * std::pow(10.0, u(rng) * 0.5);
    const double ma = kM * std::pow(10.0, u(rng)), mb = kM * std::pow(10.0, u(rng));
    Sphere a = ball(ma, ra, {u(rng), u(rng), u(rng)}, Vec3{u(rng), u(rng), u(rng)} * (1.0 / ra));
    Sphere b = ball(mb, rb, {u(rng), u(rng), u(rng)}, Vec3{u(rng), u(rng), u(rng)} * (1.0 / rb));
    const bool with_wall = k % 4 == 3;
    if (with_wall) b = a_wall();
    const double un = dot(contact_velocity_of(a, b, n), n);
    if (un >= -1e-3) continue; // separating or grazing: not a collision (tested below)
    const CollisionLaw law{pos(rng), 2.0 * pos(rng), pos(rng)};
    SCOPED_TRACE(fmt::format("random collision {} ({})", k, with_wall ? "wall" : "pair"));
    const auto out = check_collision(a, b, n, law);
    (out.res.sliding ? sliding : sticking)++;
  }
  std::cout << fmt::format("random collisions: {} sticking, {} sliding\n", sticking, sliding);
  EXPECT_GT(sliding, 100);
  EXPECT_GT(sticking, 100);
}

// --- Particle-wall (inv_m = inv_i = 0) ----------------------------------------------------------

TEST(CollisionOperator, WallStickingBeta0GivesRolling) {
  // A non-spinning sphere hits the floor (n = +z, from the wall into the particle) with
  // tangential speed V and sticks with beta0 = 0: classical result, from angular momentum about
  // the contact point m V R = m v' R + I w' and rolling v' = w' R: v' = 5/7 V, w' = 5/7 V / R.
  const double vx = 1.4;
  const Sphere a = ball(kM, kR, {vx, 0.0, -2.0});
  const auto out = check_collision(a, a_wall(), {0.0, 0.0, 1.0}, {0.6, 0.5, 0.0});
  EXPECT_FALSE(out.res.sliding);
  EXPECT_NEAR(out.a.v.x, 5.0 / 7.0 * vx, 1e-12 * 2.0);
  EXPECT_NEAR(out.a.w.y, 5.0 / 7.0 * vx / kR, 1e-12 * 2.0 / kR);
  EXPECT_NEAR(out.a.v.z, 0.6 * 2.0, 1e-12 * 2.0);
}

TEST(CollisionOperator, WallSlidingAndSpinning) {
  // A spinning sphere hitting a side wall (n = -x: the x_hi face), sliding and sticking.
  const Vec3 n{-1.0, 0.0, 0.0};
  const Sphere a = ball(2.0 * kM, 1.5 * kR, {3.0, 0.4, -1.1}, {250.0, -800.0, 410.0});
  for (const double mu : {0.02, 0.3, 5.0}) {
    for (const double beta0 : {0.0, 0.5}) {
      SCOPED_TRACE(fmt::format("mu = {}, beta0 = {}", mu, beta0));
      check_collision(a, a_wall(), n, {0.85, mu, beta0});
    }
  }
}

TEST(CollisionOperator, FrictionlessAndElastic) {
  // mu = 0: no tangential impulse, spins and tangential velocities unchanged. e = 1, and
  // beta0 = 1 with large mu (perfectly rough): no energy lost.
  const Sphere a = ball(kM, kR, kSkew(-1.0, 0.7, 0.2), {300.0, 100.0, -50.0});
  const Sphere b = ball(2.0 * kM, 0.7 * kR, kSkew(0.3, -0.2, 0.4), {-90.0, 40.0, 10.0});
  const auto smooth = check_collision(a, b, kSkew.n, {0.8, 0.0, 0.0});
  const Vec3 jt = smooth.res.impulse - kSkew.n * dot(smooth.res.impulse, kSkew.n);
  EXPECT_LE(norm(jt), 1e-15 * norm(smooth.res.impulse)) << "mu = 0: no tangential impulse";
  EXPECT_NEAR(norm(smooth.a.w - a.w), 0.0, 1e-12 * norm(a.w));
  EXPECT_NEAR(dot(smooth.a.v - a.v, kSkew.t1), 0.0, 1e-12);
  for (const CollisionLaw law : {CollisionLaw{1.0, 0.0, 0.0}, CollisionLaw{1.0, 100.0, 1.0}}) {
    const auto out = check_collision(a, b, kSkew.n, law);
    const double e0 = kinetic(a) + kinetic(b);
    EXPECT_NEAR(kinetic(out.a) + kinetic(out.b), e0, 1e-13 * e0) << "elastic: no loss";
  }
}

// --- Separating and grazing pairs -------------------------------------------------------------

TEST(CollisionOperator, SeparatingOrGrazingPairIsLeftUnchanged) {
  struct Pair {
    Sphere a, b;
    Vec3 n;
  };
  const Pair pairs[] = {
      {ball(kM, kR, kSkew(1.0, 0.5, 0.0), {10.0, 0.0, 0.0}), ball(kM, kR, kSkew(-0.5, 0, 0)),
       kSkew.n},
      // grazing: u_n = 0 exactly (n = x)
      {ball(kM, kR, {0.0, 2.0, 0.0}, {0.0, 30.0, 70.0}), ball(2 * kM, kR, {0.0, -1.0, 1.0}), kX.n},
      {ball(kM, kR, kSkew(0.3, 1.0, 0.0), {0.0, 50.0, 0.0}), a_wall(), kSkew.n},
  };
  for (const auto& p : pairs) {
    const Vec3& n = p.n;
    Body ba = body_of(p.a), bb = body_of(p.b);
    const Body a0 = ba, b0 = bb;
    ASSERT_GE(dot(contact_velocity_of(p.a, p.b, n), n), 0.0) << "set-up: not approaching";
    const auto res = hardsphere::collide(ba, bb, n, {0.5, 0.3, 0.2});
    EXPECT_FALSE(res.approaching);
    EXPECT_EQ(norm2(res.impulse), 0.0);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(ba.v[c], a0.v[c]);
      EXPECT_EQ(ba.w[c], a0.w[c]);
      EXPECT_EQ(bb.v[c], b0.v[c]);
      EXPECT_EQ(bb.w[c], b0.w[c]);
    }
  }
}

// --- The spin never decides whether a pair approaches -------------------------------------------

// (w x n) . n = 0 for any w [Deen07 eq. 11], so whether a pair approaches depends on the linear
// velocities alone. The event scheduler judges a touching pair by (v_a - v_b) . n; the operator
// must give the same verdict bit for bit, however fast the particles spin, or a grazing pair is
// rescheduled at the same instant forever. Random normals, spins of 1e3 rad/s (spin term
// ~1e3 m/s at R = 1 m, whose round-off alone is ~1e-13 m/s) and normal approach speeds of
// +-1e-15 m/s, far below that round-off: the verdict must equal sign((v_a - v_b) . n) in all
// 10^4 cases.
TEST(CollisionOperator, SpinRoundOffNeverFlipsTheApproachVerdict) {
  std::mt19937_64 rng(20261201);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int approaching = 0;
  for (int k = 0; k < 10000; ++k) {
    Vec3 n{u(rng), u(rng), u(rng)};
    n = n / norm(n);
    const Vec3 w_a{1e3 * u(rng), 1e3 * u(rng), 1e3 * u(rng)};
    const Vec3 w_b{1e3 * u(rng), 1e3 * u(rng), 1e3 * u(rng)};
    const double sign = (k % 2 == 0) ? -1.0 : 1.0;
    Body a{n * (sign * 1e-15), w_a, 1.0, 1.0, 2.5};
    Body b{{0.0, 0.0, 0.0}, w_b, 1.0, 1.0, 2.5};
    const bool expected = dot(a.v - b.v, n) < 0.0;
    const auto res = hardsphere::collide(a, b, n, {0.9, 0.3, 0.0});
    ASSERT_EQ(res.approaching, expected) << "case " << k;
    approaching += res.approaching ? 1 : 0;
  }
  EXPECT_GT(approaching, 0);
  EXPECT_LT(approaching, 10000);
}

} // namespace
} // namespace fluidem
