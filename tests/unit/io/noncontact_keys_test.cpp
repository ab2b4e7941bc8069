// [van_der_waals], [electrostatics], [liquid_bridge] and the particles' charge and liquid
// (docs/case-file.md): read into CaseSpec::noncontact, written back by the resolved-case writer
// to the same bits, and every bad key stops the reader with one line naming the file, the line
// and the key, and what is allowed.
#include <gtest/gtest.h>

#include <string>

#include "io/case_reader.hpp"
#include "io/case_writer.hpp"

#include "../../common/case_error.hpp"

namespace fluidem {
namespace {

const std::string kBase = "[simulation]\nend_time = 0.5\n"
                          "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.1, 0.1, 0.1]\n"
                          "periodic = [true, false, false]\n"
                          "[[species]]\nname = \"s\"\ndiameter = 0.005\ndensity = 2700.0\n"
                          "charge = -2e-12\nliquid_fraction = 1e-3\n"
                          "[[insert]]\nspecies = \"s\"\ncount = 10\ncharge = 3e-12\n";
const std::string kForces = "[van_der_waals]\nhamaker = 6.5e-20\nmin_separation = 1.65e-10\n"
                            "range = 1e-6\nwall_hamaker = 1e-19\n"
                            "[electrostatics]\ncutoff = 0.02\nrelative_permittivity = 1.5\n"
                            "conducting_walls = [\"z_lo\", \"y_hi\"]\n"
                            "[liquid_bridge]\nsurface_tension = 0.0728\ncontact_angle = 20\n"
                            "viscosity = 1e-3\nmin_gap = 1e-6\nwalls = false\n";

using fluidem::test::error_of;

TEST(NonContactKeys, ReadAndWrittenBackToTheSameBits) {
  const CaseSpec c = read_case_string(kBase + kForces, "case.toml");
  ASSERT_TRUE(c.noncontact.van_der_waals && c.noncontact.electrostatics &&
              c.noncontact.liquid_bridge);
  EXPECT_EQ(c.species[0].charge, -2e-12);
  EXPECT_EQ(c.species[0].liquid_fraction, 1e-3);
  EXPECT_EQ(*c.inserts[0].charge, 3e-12);
  EXPECT_EQ(c.noncontact.van_der_waals->hamaker, 6.5e-20);
  EXPECT_EQ(*c.noncontact.van_der_waals->wall_hamaker, 1e-19);
  EXPECT_TRUE(c.noncontact.electrostatics->conducting[4]); // z_lo
  EXPECT_TRUE(c.noncontact.electrostatics->conducting[3]); // y_hi
  EXPECT_FALSE(c.noncontact.electrostatics->conducting[0]);
  EXPECT_EQ(c.noncontact.liquid_bridge->contact_angle_degrees, 20.0);
  EXPECT_FALSE(c.noncontact.liquid_bridge->walls);
  const CaseSpec r = read_case_string(write_case_toml(c), "resolved.toml");
  EXPECT_EQ(r.species[0].charge, c.species[0].charge);
  EXPECT_EQ(r.species[0].liquid_fraction, c.species[0].liquid_fraction);
  EXPECT_EQ(*r.inserts[0].charge, *c.inserts[0].charge);
  EXPECT_EQ(r.noncontact.van_der_waals->min_separation, c.noncontact.van_der_waals->min_separation);
  EXPECT_EQ(r.noncontact.van_der_waals->range, c.noncontact.van_der_waals->range);
  EXPECT_EQ(*r.noncontact.van_der_waals->wall_hamaker, *c.noncontact.van_der_waals->wall_hamaker);
  EXPECT_EQ(r.noncontact.electrostatics->cutoff, c.noncontact.electrostatics->cutoff);
  EXPECT_EQ(r.noncontact.electrostatics->relative_permittivity, 1.5);
  EXPECT_EQ(r.noncontact.electrostatics->conducting, c.noncontact.electrostatics->conducting);
  EXPECT_EQ(r.noncontact.liquid_bridge->contact_angle(),
            c.noncontact.liquid_bridge->contact_angle());
  EXPECT_EQ(r.noncontact.liquid_bridge->min_gap, 1e-6);
  EXPECT_EQ(r.noncontact.liquid_bridge->walls, false);
  EXPECT_FALSE(read_case_string(kBase, "case.toml").noncontact.any());
}

TEST(NonContactKeys, BadKeysNameTheFileLineAndKey) {
  const struct {
    std::string body, key, what;
  } cases[] = {
      {"[van_der_waals]\nhamaker = 1e-19\nmin_separation = 4e-10\nrange = 1e-6\nhamacker = 1\n",
       "van_der_waals.hamacker", "did you mean \"hamaker\"?"},
      {"[van_der_waals]\nmin_separation = 4e-10\nrange = 1e-6\n", "van_der_waals.hamaker",
       "missing required key"},
      {"[van_der_waals]\nhamaker = -1e-19\nmin_separation = 4e-10\nrange = 1e-6\n",
       "van_der_waals.hamaker", "out of range (allowed: a number > 0"},
      {"[van_der_waals]\nhamaker = 1e-19\nmin_separation = 4e-10\nrange = 1e-10\n",
       "van_der_waals.range", "is not beyond min_separation"},
      {"[electrostatics]\ncutoff = 0.06\n", "electrostatics.cutoff",
       "not below half the periodic box"},
      {"[electrostatics]\ncutoff = 0.02\nrelative_permittivity = 0.5\n",
       "electrostatics.relative_permittivity", "a number >= 1"},
      {"[electrostatics]\ncutoff = 0.02\nconducting_walls = [\"floor\"]\n",
       "electrostatics.conducting_walls", "unknown face"},
      {"[electrostatics]\ncutoff = 0.02\nconducting_walls = [\"x_lo\"]\n",
       "electrostatics.conducting_walls", "periodic axis"},
      {"[liquid_bridge]\ncontact_angle = 10\n", "liquid_bridge.surface_tension",
       "missing required key"},
      {"[liquid_bridge]\nsurface_tension = 0.07\ncontact_angle = 60\n",
       "liquid_bridge.contact_angle", "0 <= angle < 50 degrees"},
      {"[liquid_bridge]\nsurface_tension = 0.07\nviscosity = 1e-3\n", "liquid_bridge.min_gap",
       "missing required key"},
      {"[liquid_bridge]\nsurface_tension = 0.07\nwalls = 1\n", "liquid_bridge.walls", ""},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.body);
    const std::string msg = error_of(kBase + c.body);
    EXPECT_NE(msg.find("case.toml:"), std::string::npos) << msg;
    EXPECT_NE(msg.find(": " + c.key + ": "), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.what), std::string::npos) << msg;
  }
  // The particles' own keys.
  std::string wet = kBase;
  wet.replace(wet.find("liquid_fraction = 1e-3"), 22, "liquid_fraction = 0.5");
  std::string msg = error_of(wet);
  EXPECT_NE(msg.find("species[0].liquid_fraction: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("2e-5 to 0.01"), std::string::npos) << msg;
  std::string dry = kBase;
  dry.replace(dry.find("liquid_fraction = 1e-3"), 22, "liquid_fraction = 0");
  msg = error_of(dry + "[liquid_bridge]\nsurface_tension = 0.07\n");
  EXPECT_NE(msg.find("liquid_bridge: no species has liquid"), std::string::npos) << msg;
  std::string q = kBase;
  q.replace(q.find("charge = 3e-12"), 14, "charge = \"a lot\"");
  msg = error_of(q);
  EXPECT_NE(msg.find("insert[0].charge: expected a number"), std::string::npos) << msg;
}

} // namespace
} // namespace fluidem
