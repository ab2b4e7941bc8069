// [[insert]] size_distribution (docs/case-file.md): each kind read into InsertSpec, inline or as
// an [insert.size_distribution] table, the truncation defaults resolved (normal: mean -+ 3 std;
// log_normal: median /* sigma_g^3), written back by the resolved-case writer and read again to
// the same bits; every bad value stopped with one line naming the file, the key and what is
// allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/case_reader.hpp"
#include "io/case_writer.hpp"

#include "../../common/case_error.hpp"

namespace fluidem {
namespace {

using Kind = SizeDistributionSpec::Kind;
using Basis = SizeDistributionSpec::Basis;

std::string base(const std::string& placement = "random") {
  return "[simulation]\nend_time = 0.5\n"
         "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.1, 0.1, 0.1]\n"
         "[[species]]\nname = \"s\"\ndiameter = 0.004\ndensity = 2700.0\n"
         "[[insert]]\nspecies = \"s\"\nplacement = \"" +
         placement + "\"\n" +
         (placement == "file" ? "file = \"" FLUIDEM_SOURCE_DIR "/CMakeLists.txt\"\n"
                              : "count = 10\n");
}

using fluidem::test::error_of;

SizeDistributionSpec read_back(const std::string& text) {
  const CaseSpec c = read_case_string(text, "case.toml");
  EXPECT_TRUE(c.inserts[0].size_distribution.has_value());
  const CaseSpec r = read_case_string(write_case_toml(c), "resolved.toml");
  const auto& a = *c.inserts[0].size_distribution;
  const auto& b = *r.inserts[0].size_distribution;
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.basis, b.basis);
  EXPECT_EQ(a.mean, b.mean);
  EXPECT_EQ(a.std, b.std);
  EXPECT_EQ(a.median, b.median);
  EXPECT_EQ(a.geometric_std, b.geometric_std);
  EXPECT_EQ(a.min, b.min);
  EXPECT_EQ(a.max, b.max);
  EXPECT_EQ(a.diameters, b.diameters);
  EXPECT_EQ(a.cumulative, b.cumulative);
  EXPECT_EQ(a.fractions, b.fractions);
  return a;
}

TEST(SizeDistributionKeys, EachKindReadAndWrittenBack) {
  const auto n = read_back(base() + "size_distribution = { kind = \"normal\", mean = 0.004, "
                                    "std = 0.0005 }\n");
  EXPECT_EQ(n.kind, Kind::Normal);
  EXPECT_EQ(n.basis, Basis::Number);
  EXPECT_EQ(n.min, 0.004 - 3.0 * 0.0005);
  EXPECT_EQ(n.max, 0.004 + 3.0 * 0.0005);
  const auto l = read_back(base() + "[insert.size_distribution]\nkind = \"log_normal\"\n"
                                    "basis = \"mass\"\nmedian = 0.003\ngeometric_std = 1.4\n"
                                    "max = 0.006\n");
  EXPECT_EQ(l.kind, Kind::LogNormal);
  EXPECT_EQ(l.basis, Basis::Mass);
  EXPECT_EQ(l.min, 0.003 / std::pow(1.4, 3.0));
  EXPECT_EQ(l.max, 0.006);
  const auto t = read_back(base() + "size_distribution = { kind = \"table\", diameters = [0.002, "
                                    "0.003, 0.005], cumulative = [0.0, 0.4, 1.0] }\n");
  EXPECT_EQ(t.cumulative, (std::vector<double>{0.0, 0.4, 1.0}));
  const auto d = read_back(base() + "size_distribution = { kind = \"discrete\", basis = \"mass\", "
                                    "diameters = [0.002, 0.004], fractions = [0.3, 0.7] }\n");
  EXPECT_EQ(d.fractions, (std::vector<double>{0.3, 0.7}));
  // Without the key: no distribution.
  EXPECT_FALSE(read_case_string(base(), "case.toml").inserts[0].size_distribution.has_value());
}

TEST(SizeDistributionKeys, BadValuesNameTheKey) {
  const std::string p = "insert[0].size_distribution";
  const struct {
    std::string body, key, what;
  } cases[] = {
      {"size_distribution = { mean = 0.004, std = 0.001 }", p + ".kind", "missing required key"},
      {"size_distribution = { kind = \"gamma\" }", p + ".kind", "\"log_normal\""},
      {"size_distribution = { kind = \"normal\", mean = 0.004, std = 0.001, spread = 1 }",
       p + ".spread", "unknown key"},
      {"size_distribution = { kind = \"normal\", mean = 0.004, std = 0.001, median = 0.004 }",
       p + ".median", "not a key of kind = \"normal\""},
      {"size_distribution = { kind = \"normal\", basis = \"volume\", mean = 0.004, std = 0.001 }",
       p + ".basis", "\"mass\""},
      {"size_distribution = { kind = \"normal\", mean = 0.004, std = 0.0 }", p + ".std",
       "out of range"},
      {"size_distribution = { kind = \"normal\", mean = 0.004, std = -0.001 }", p + ".std",
       "out of range"},
      {"size_distribution = { kind = \"normal\", mean = 0.004 }", p + ".std",
       "missing required key"},
      {"size_distribution = { kind = \"normal\", mean = 0.004, std = 0.002 }", p + ".std",
       "reaches d <= 0"},
      {"size_distribution = { kind = \"normal\", mean = 0.004, std = 0.001, min = 0.0 }",
       p + ".min", "out of range"},
      {"size_distribution = { kind = \"normal\", mean = 0.004, std = 0.001, min = 0.005, max = "
       "0.003 }",
       p + ".max", "min < max"},
      {"size_distribution = { kind = \"log_normal\", median = 0.004, geometric_std = 1.0 }",
       p + ".geometric_std", "> 1"},
      {"size_distribution = { kind = \"log_normal\", median = 0.004, geometric_std = 0.5 }",
       p + ".geometric_std", "out of range"},
      {"size_distribution = { kind = \"table\", diameters = [0.003, 0.002], cumulative = [0.0, "
       "1.0] }",
       p + ".diameters", "strictly increasing"},
      {"size_distribution = { kind = \"table\", diameters = [0.002, 0.003, 0.004], cumulative = "
       "[0.0, 0.6, 0.5] }",
       p + ".cumulative", "non-decreasing"},
      {"size_distribution = { kind = \"table\", diameters = [0.002, 0.003], cumulative = [0.0, "
       "0.9] }",
       p + ".cumulative", "to 1 within 1e-6"},
      {"size_distribution = { kind = \"table\", diameters = [0.002, 0.003], cumulative = [0.1, "
       "1.0] }",
       p + ".cumulative", "from 0"},
      {"size_distribution = { kind = \"table\", diameters = [0.002, 0.003], cumulative = [0.0] }",
       p + ".cumulative", "one per diameter"},
      {"size_distribution = { kind = \"discrete\", diameters = [0.002, 0.003], fractions = [0.5, "
       "0.4] }",
       p + ".fractions", "sum to 0.9"},
      {"size_distribution = { kind = \"discrete\", diameters = [0.0, 0.003], fractions = [0.5, "
       "0.5] }",
       p + ".diameters[0]", "out of range"},
      {"size_distribution = { kind = \"discrete\", diameters = [0.002, 0.003], fractions = [-0.5, "
       "1.5] }",
       p + ".fractions[0]", "out of range"},
      {"size_distribution = { kind = \"discrete\", diameters = [0.002] }", p + ".fractions",
       "missing required key"},
      {"size_distribution = 0.004", p, "expected a table"},
  };
  for (const auto& c : cases) {
    const std::string e = error_of(base() + c.body + "\n");
    EXPECT_NE(e.find("case.toml:"), std::string::npos) << e;
    EXPECT_NE(e.find(c.key), std::string::npos) << c.body << "\n -> " << e;
    EXPECT_NE(e.find(c.what), std::string::npos) << c.body << "\n -> " << e;
  }
  // Within 1e-6 of 1 is accepted (the sampler divides by the sum).
  EXPECT_NO_THROW((void)read_case_string(base() + "size_distribution = { kind = \"discrete\", "
                                                  "diameters = [0.002, 0.003], fractions = "
                                                  "[0.5, 0.4999995] }\n",
                                         "case.toml"));
}

// --set reaches the sub-table's keys, and refuses a key of no kind naming it.
TEST(SizeDistributionKeys, SetOverrides) {
  const std::string text =
      base() + "size_distribution = { kind = \"normal\", mean = 0.004, std = 0.0005 }\n";
  const CaseSpec c =
      read_case_string(text, "case.toml", {"insert[0].size_distribution.std=0.0002"});
  EXPECT_EQ(c.inserts[0].size_distribution->std, 0.0002);
  EXPECT_EQ(c.inserts[0].size_distribution->min, 0.004 - 3.0 * 0.0002);
  try {
    (void)read_case_string(text, "case.toml", {"insert[0].size_distribution.sigma=1"});
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("insert[0].size_distribution.sigma"), std::string::npos)
        << e.what();
  }
}

TEST(SizeDistributionKeys, NotWithAFile) {
  const std::string e =
      error_of(base("file") + "size_distribution = { kind = \"normal\", mean = 0.004, std = "
                              "0.0005 }\n");
  EXPECT_NE(e.find("insert[0].size_distribution"), std::string::npos) << e;
  EXPECT_NE(e.find("placement = \"file\""), std::string::npos) << e;
}

} // namespace
} // namespace fluidem
