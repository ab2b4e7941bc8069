// The rotation of the contact history from an unnormalised previous separation
// (kernels::rotate_with_separation, used by the contact loop) against the unit-normal Rodrigues
// form (kernels::rotate_with_contact, checked against hand values in
// tests/models/history_rotation.toml) and against the defining properties of a rotation that
// takes n0 onto n [Deen07 eq. 31-32]: lengths kept, n0 carried onto n.
#include <gtest/gtest.h>

#include <random>

#include "contact/kernels/history_rotation.hpp"

namespace fluidem {
namespace {

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  const Vec3 v{g(rng), g(rng), g(rng)};
  return v / norm(v);
}

TEST(HistoryRotation, SeparationFormEqualsUnitNormalForm) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> len(1e-4, 1e-2), turn(1e-6, 0.5);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 n0 = random_unit(rng);
    // n: n0 turned by up to 0.5 rad (a contact turns by far less within one step).
    Vec3 n = n0 + random_unit(rng) * turn(rng);
    n = n / norm(n);
    const Vec3 a = n0 * len(rng); // previous separation: any length along n0
    const Vec3 v = random_unit(rng) * 1e-5;
    const Vec3 r1 = kernels::rotate_with_separation(v, a, n);
    const Vec3 r2 = kernels::rotate_with_contact(v, n0, n);
    // Tolerance: a few ulps of |v| (both are the same rotation written two ways).
    EXPECT_NEAR(r1.x, r2.x, 1e-19);
    EXPECT_NEAR(r1.y, r2.y, 1e-19);
    EXPECT_NEAR(r1.z, r2.z, 1e-19);
    EXPECT_NEAR(norm(r1), norm(v), 1e-19); // a rotation keeps lengths
    const Vec3 m = kernels::rotate_with_separation(n0, a, n);
    EXPECT_NEAR(norm(m - n), 0.0, 1e-14); // and takes n0 onto n
  }
}

TEST(HistoryRotation, FlippedNormalReversesTheHistory) {
  const Vec3 v{1e-5, 2e-5, 0.0};
  const Vec3 r = kernels::rotate_with_separation(v, Vec3{0, 0, 3e-3}, Vec3{0, 0, -1});
  EXPECT_EQ(r.x, -v.x);
  EXPECT_EQ(r.y, -v.y);
}

} // namespace
} // namespace fluidem
