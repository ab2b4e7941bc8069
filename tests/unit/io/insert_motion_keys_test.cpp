// [[insert]] angular_velocity and fixed (docs/case-file.md): read into InsertSpec, written back
// by the resolved-case writer to the same bits, and every bad value stopped with one line naming
// the key: a non-finite spin, a spin a 2-D run cannot represent (discs in the x-z plane turn about
// y only), and motion given to fixed particles.
#include <gtest/gtest.h>

#include <string>

#include "io/case_reader.hpp"
#include "io/case_writer.hpp"

#include "../../common/case_error.hpp"

namespace fluidem {
namespace {

std::string base(int dimension) {
  return "[simulation]\ndimension = " + std::to_string(dimension) +
         "\nend_time = 0.5\n"
         "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.1, 0.004, 0.1]\n"
         "[[species]]\nname = \"s\"\ndiameter = 0.004\ndensity = 2700.0\n"
         "[[insert]]\nspecies = \"s\"\ncount = 10\n";
}

using fluidem::test::error_of;

TEST(InsertMotionKeys, ReadAndWrittenBack) {
  const CaseSpec c = read_case_string(
      base(3) + "angular_velocity = [1.5, -2.25, 1e3]\n[[insert]]\nspecies = \"s\"\ncount = 4\n"
                "fixed = true\n",
      "case.toml");
  ASSERT_EQ(c.inserts.size(), 2u);
  EXPECT_EQ(c.inserts[0].angular_velocity, (std::array<double, 3>{1.5, -2.25, 1e3}));
  EXPECT_FALSE(c.inserts[0].fixed);
  EXPECT_TRUE(c.inserts[1].fixed);
  EXPECT_EQ(c.inserts[1].angular_velocity, (std::array<double, 3>{0.0, 0.0, 0.0}));
  const CaseSpec r = read_case_string(write_case_toml(c), "resolved.toml");
  EXPECT_EQ(r.inserts[0].angular_velocity, c.inserts[0].angular_velocity);
  EXPECT_EQ(r.inserts[0].fixed, false);
  EXPECT_EQ(r.inserts[1].fixed, true);
  // 2-D: a spin about y is a disc turning in its plane.
  const CaseSpec d = read_case_string(base(2) + "angular_velocity = [0.0, 40.0, 0.0]\n", "c.toml");
  EXPECT_EQ(d.inserts[0].angular_velocity[1], 40.0);
}

TEST(InsertMotionKeys, BadValuesNameTheKey) {
  const struct {
    int dimension;
    std::string body, key, what;
  } cases[] = {
      {3, "angular_velocity = [1.0, nan, 0.0]\n", "insert[0].angular_velocity[1]", "out of range"},
      {3, "angular_velocity = [1.0, inf, 0.0]\n", "insert[0].angular_velocity[1]", "out of range"},
      {3, "angular_velocity = [1.0, 2.0]\n", "insert[0].angular_velocity", "rad/s"},
      {3, "angular_velocity = 3.0\n", "insert[0].angular_velocity", "an array of 3 numbers"},
      {2, "angular_velocity = [1.0, 0.0, 0.0]\n", "insert[0].angular_velocity",
       "turn about y only"},
      {2, "angular_velocity = [0.0, 3.0, -1.0]\n", "insert[0].angular_velocity",
       "turn about y only"},
      {3, "fixed = 1\n", "insert[0].fixed", "expected a boolean"},
      {3, "fixed = true\nvelocity = [0.0, 0.0, -1.0]\n", "insert[0].velocity",
       "must be 0 with fixed = true"},
      {3, "fixed = true\nvelocity_spread = 0.1\n", "insert[0].velocity_spread",
       "must be 0 with fixed = true"},
      {3, "fixed = true\nangular_velocity = [0.0, 1.0, 0.0]\n", "insert[0].angular_velocity",
       "must be 0 with fixed = true"},
  };
  for (const auto& c : cases) {
    const std::string msg = error_of(base(c.dimension) + c.body);
    EXPECT_NE(msg.find(c.key + ":"), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.what), std::string::npos) << msg;
    EXPECT_NE(msg.find("case.toml:"), std::string::npos) << msg; // the file and line
  }
}

} // namespace
} // namespace fluidem
