// The collision-statistics keys of a case ([output] collisions, [[output.collision_region]]):
// parsed values, the resolved-case round trip (write -> read gives the same settings), and the
// errors, each at the line of the offending key, naming it and what is allowed.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "io/case_reader.hpp"
#include "io/case_writer.hpp"

namespace fluidem {
namespace {

const std::string kBase = R"([simulation]
end_time = 1.0

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.1, 0.1, 0.1]
periodic = [true, true, true]

[[species]]
name = "glass"
diameter = 0.01
density = 2700.0

[[insert]]
species = "glass"
count = 10
)";

const std::string kRegions = R"(
[output]
collisions = true

[[output.collision_region]]
name = "GC"
centre = [0.05, 0.05, 0.05]
radius = 0.01

[[output.collision_region]]
name = "CC1"
centre = [0.025, 0.025, 0.025]
radius = 0.01
)";

long line_of(const std::string& text, const std::string& marker) {
  const auto pos = text.find(marker);
  if (pos == std::string::npos) return 0;
  return 1 +
         static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

/// Expects an InputError at the line of `marker`, naming `key`, containing `what`.
void expect_error_at(const std::string& text, const std::string& marker, const std::string& key,
                     const std::string& what) {
  std::string msg;
  try {
    (void)read_case_string(text, "case.toml");
    ADD_FAILURE() << "expected an InputError for:\n" << text;
    return;
  } catch (const InputError& e) {
    msg = e.what();
  }
  const std::string where = "case.toml:" + std::to_string(line_of(text, marker)) + ":";
  EXPECT_EQ(msg.rfind(where, 0), 0u) << "expected location " << where << " in: " << msg;
  EXPECT_NE(msg.find(": " + key + ": "), std::string::npos)
      << "expected key " << key << ": " << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << "expected '" << what << "' in: " << msg;
}

TEST(CollisionOutputCase, OffByDefault) {
  const CaseSpec c = read_case_string(kBase, "case.toml");
  EXPECT_FALSE(c.output.collisions);
  EXPECT_TRUE(c.output.collision_regions.empty());
  EXPECT_EQ(write_case_toml(c).find("collision"), std::string::npos);
}

TEST(CollisionOutputCase, RegionsParseAndRoundTrip) {
  const CaseSpec c = read_case_string(kBase + kRegions, "case.toml");
  EXPECT_TRUE(c.output.collisions);
  ASSERT_EQ(c.output.collision_regions.size(), 2u);
  EXPECT_EQ(c.output.collision_regions[0].name, "GC");
  EXPECT_EQ(c.output.collision_regions[1].centre, (std::array<double, 3>{0.025, 0.025, 0.025}));
  EXPECT_EQ(c.output.collision_regions[1].radius, 0.01);
  const CaseSpec r = read_case_string(write_case_toml(c), "case.resolved.toml");
  EXPECT_TRUE(r.output.collisions);
  ASSERT_EQ(r.output.collision_regions.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(r.output.collision_regions[k].name, c.output.collision_regions[k].name);
    EXPECT_EQ(r.output.collision_regions[k].centre, c.output.collision_regions[k].centre);
    EXPECT_EQ(r.output.collision_regions[k].radius, c.output.collision_regions[k].radius);
  }
}

TEST(CollisionOutputCase, Errors) {
  auto with = [](const std::string& from, const std::string& to) {
    std::string t = kBase + kRegions;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  expect_error_at(with("radius = 0.01\n\n[[", "radius = -0.01\n\n[["), "radius = -0.01",
                  "output.collision_region[0].radius", "(allowed: ");
  expect_error_at(with("radius = 0.01\n\n[[", "radius = 0.0\n\n[["), "radius = 0.0",
                  "output.collision_region[0].radius", "out of range");
  expect_error_at(with("centre = [0.05, 0.05, 0.05]", "centre = [0.05, 0.2, 0.05]"),
                  "centre = [0.05, 0.2", "output.collision_region[0].centre", "outside the domain");
  expect_error_at(with("name = \"CC1\"", "name = \"GC\""), "name = \"GC\"\ncentre = [0.025",
                  "output.collision_region[1].name", "duplicate collision region name \"GC\"");
  expect_error_at(with("name = \"CC1\"", "name = \"a,b\""), "name = \"a,b\"",
                  "output.collision_region[1].name", "comma");
  expect_error_at(with("collisions = true", "collisions = \"yes\""), "collisions = \"yes\"",
                  "output.collisions", "(allowed: true or false)");
  expect_error_at(with("radius = 0.01\n\n[[", "radus = 0.01\n\n[["), "radus",
                  "output.collision_region[0].radus", "did you mean \"radius\"?");
  // Regions without the statistics switched on.
  expect_error_at(with("collisions = true", "collisions = false"), "[[output.collision_region]]",
                  "output.collision_region", "needs output.collisions = true");
}

} // namespace
} // namespace fluidem
