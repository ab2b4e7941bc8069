// [body_force] keys (docs/case-file.md): read into CaseSpec::body_force, written back by the
// resolved-case writer to the same bits, and every bad key stops the reader with one line naming
// the key (and, for keys in the file, its line).
#include <gtest/gtest.h>

#include <string>

#include "io/case_reader.hpp"
#include "io/case_writer.hpp"

#include "../../common/case_error.hpp"

namespace fluidem {
namespace {

const std::string kBase = "[simulation]\nend_time = 0.5\ngravity = [0.0, 0.0, 0.0]\n"
                          "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.1, 0.1, 0.1]\n"
                          "periodic = [true, true, true]\n"
                          "[[species]]\nname = \"s\"\ndiameter = 0.005\ndensity = 2700.0\n"
                          "[[insert]]\nspecies = \"s\"\ncount = 10\n";

using fluidem::test::error_of;

TEST(BodyForceKeys, ReadAndWrittenBack) {
  const CaseSpec c = read_case_string(kBase + "[body_force]\ntype = \"sinusoidal_cube\"\n"
                                              "amplitude = -0.1\nwavelength = 0.05\n"
                                              "origin = [0.01, 0.0, 0.025]\n",
                                      "case.toml");
  ASSERT_TRUE(c.body_force.has_value());
  EXPECT_EQ(c.body_force->type, BodyForceType::SinusoidalCube);
  EXPECT_EQ(c.body_force->amplitude, -0.1);
  EXPECT_EQ(c.body_force->wavelength, 0.05);
  EXPECT_EQ(c.body_force->origin[2], 0.025);
  const CaseSpec r = read_case_string(write_case_toml(c), "resolved.toml");
  ASSERT_TRUE(r.body_force.has_value());
  EXPECT_EQ(r.body_force->amplitude, c.body_force->amplitude);
  EXPECT_EQ(r.body_force->wavelength, c.body_force->wavelength);
  EXPECT_EQ(r.body_force->origin, c.body_force->origin);
  EXPECT_FALSE(read_case_string(kBase, "case.toml").body_force.has_value());
  // --set reaches the table like any other.
  const CaseSpec s = read_case_string(kBase + "[body_force]\ntype = \"sinusoidal_cube\"\n"
                                              "amplitude = 0.1\nwavelength = 0.1\n",
                                      "case.toml", {"body_force.amplitude=0.3"});
  EXPECT_EQ(s.body_force->amplitude, 0.3);
}

TEST(BodyForceKeys, BadKeysNameTheKey) {
  const std::string head = kBase + "[body_force]\n";
  const struct {
    std::string body, key, what;
  } cases[] = {
      {"type = \"sinusoidal_cube\"\namplitude = 0.1\nwavelength = 0.1\namplitud = 1\n",
       "body_force.amplitud", "unknown key"},
      {"amplitude = 0.1\nwavelength = 0.1\n", "body_force.type", "missing required key"},
      {"type = \"sine\"\namplitude = 0.1\nwavelength = 0.1\n", "body_force.type",
       "unknown value \"sine\""},
      {"type = \"sinusoidal_cube\"\nwavelength = 0.1\n", "body_force.amplitude",
       "missing required key"},
      {"type = \"sinusoidal_cube\"\namplitude = 0.1\n", "body_force.wavelength",
       "missing required key"},
      {"type = \"sinusoidal_cube\"\namplitude = 0.1\nwavelength = -0.1\n", "body_force.wavelength",
       "out of range"},
      {"type = \"sinusoidal_cube\"\namplitude = \"big\"\nwavelength = 0.1\n",
       "body_force.amplitude", "expected a number"},
      {"type = \"sinusoidal_cube\"\namplitude = 0.1\nwavelength = 0.03\n", "body_force.wavelength",
       "does not divide the periodic box length"},
      {"type = \"sinusoidal_cube\"\namplitude = 0.1\nwavelength = 0.2\n", "body_force.wavelength",
       "does not divide the periodic box length"},
      {"type = \"sinusoidal_cube\"\namplitude = 0.1\nwavelength = 0.1\norigin = [0, 0]\n",
       "body_force.origin", ""},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.body);
    const std::string msg = error_of(head + c.body);
    EXPECT_NE(msg.find(": " + c.key + ": "), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.what), std::string::npos) << msg;
    EXPECT_EQ(msg.rfind("case.toml:", 0), 0u) << msg;
  }
  // A bad override names --set.
  const std::string msg = error_of(head + "type = \"sinusoidal_cube\"\namplitude = 0.1\n"
                                          "wavelength = 0.1\n",
                                   {"body_force.wavelength=0"});
  EXPECT_EQ(msg.rfind("--set: body_force.wavelength:", 0), 0u) << msg;
}

TEST(HoldGasAtRestKey, ReadWrittenAndNeedsAPeriodicAxis) {
  const std::string gas = "[gas]\ncells = [4, 4, 4]\neos = \"incompressible\"\ndensity = 1000.0\n"
                          "[coupling]\nhold_gas_at_rest = true\n";
  const CaseSpec c = read_case_string(kBase + gas, "case.toml");
  EXPECT_TRUE(c.coupling.hold_gas_at_rest);
  EXPECT_TRUE(read_case_string(write_case_toml(c), "resolved.toml").coupling.hold_gas_at_rest);
  EXPECT_FALSE(read_case_string(kBase + "[gas]\ncells = [4, 4, 4]\n", "case.toml")
                   .coupling.hold_gas_at_rest);
  std::string closed = kBase;
  closed.replace(closed.find("periodic = [true, true, true]"), 29,
                 "periodic = [false, false, false]");
  const std::string msg = error_of(closed + gas);
  EXPECT_NE(msg.find(": coupling.hold_gas_at_rest: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("periodic"), std::string::npos) << msg;
  const std::string bad = error_of(kBase + "[gas]\ncells = [4, 4, 4]\n[coupling]\n"
                                           "hold_gas_at_rest = 1\n");
  EXPECT_NE(bad.find(": coupling.hold_gas_at_rest: "), std::string::npos) << bad;
}

} // namespace
} // namespace fluidem
