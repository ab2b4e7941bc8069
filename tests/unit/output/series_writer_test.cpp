// SeriesWriter: CSV header, number formatting, a flush per row, argument checks.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "output/series_writer.hpp"

namespace fs = std::filesystem;
using fluidem::SeriesWriter;

namespace {

std::string temp_file(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return (fs::temp_directory_path() /
          ("fluidem_series_" + std::to_string(::getpid()) + "_" + info->name() + "_" + name))
      .string();
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

} // namespace

TEST(SeriesWriter, FormatsIntegersWithoutDecimalPointAndDoublesWithTenDigits) {
  EXPECT_EQ(SeriesWriter::format_value(0.0), "0");
  EXPECT_EQ(SeriesWriter::format_value(-0.0), "0");
  EXPECT_EQ(SeriesWriter::format_value(3.0), "3");
  EXPECT_EQ(SeriesWriter::format_value(-42.0), "-42");
  EXPECT_EQ(SeriesWriter::format_value(123456789012.0), "123456789012"); // not 1.23456789e+11
  EXPECT_EQ(SeriesWriter::format_value(9007199254740991.0), "9007199254740991");
  EXPECT_EQ(SeriesWriter::format_value(1e17), "1e+17");
  EXPECT_EQ(SeriesWriter::format_value(0.1), "0.1");
  EXPECT_EQ(SeriesWriter::format_value(1.0 / 3.0), "0.3333333333");
  EXPECT_EQ(SeriesWriter::format_value(-2.5e-7), "-2.5e-07");
  EXPECT_EQ(SeriesWriter::format_value(12345.678901234), "12345.6789");
  EXPECT_EQ(SeriesWriter::format_value(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(SeriesWriter::format_value(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(SeriesWriter::format_value(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(SeriesWriter, HeaderThenRowsEachFlushedAtOnce) {
  const std::string path = temp_file("series.csv");
  {
    SeriesWriter s(path, {"time", "step", "e_kin"});
    EXPECT_EQ(slurp(path), "time,step,e_kin\n"); // visible before any row or close
    s.write_row({0.0, 0.0, 1.5});
    EXPECT_EQ(slurp(path), "time,step,e_kin\n0,0,1.5\n");
    s.write_row({1e-3, 100.0, 1.0 / 7.0});
    EXPECT_EQ(slurp(path), "time,step,e_kin\n0,0,1.5\n0.001,100,0.1428571429\n");
    EXPECT_EQ(s.columns().size(), 3u);
    s.close();
    s.close(); // idempotent
    EXPECT_THROW(s.write_row({0, 0, 0}), std::logic_error);
  }
  EXPECT_EQ(slurp(path), "time,step,e_kin\n0,0,1.5\n0.001,100,0.1428571429\n");
  fs::remove(path);
}

TEST(SeriesWriter, RowOfWrongLengthThrows) {
  const std::string path = temp_file("series.csv");
  SeriesWriter s(path, {"a", "b"});
  EXPECT_THROW(s.write_row({1.0}), std::invalid_argument);
  EXPECT_THROW(s.write_row({1.0, 2.0, 3.0}), std::invalid_argument);
  s.write_row({1.0, 2.0});
  EXPECT_EQ(slurp(path), "a,b\n1,2\n");
  fs::remove(path);
}

TEST(SeriesWriter, BadColumnsThrow) {
  const std::string path = temp_file("series.csv");
  EXPECT_THROW(SeriesWriter(path, {}), std::invalid_argument);
  EXPECT_THROW(SeriesWriter(path, {"a", ""}), std::invalid_argument);
  EXPECT_THROW(SeriesWriter(path, {"a,b"}), std::invalid_argument);
  EXPECT_THROW(SeriesWriter(path, {"a\nb"}), std::invalid_argument);
  fs::remove(path);
}

TEST(SeriesWriter, UnwritablePathThrowsNamingTheFile) {
  const std::string path = "/nonexistent-fluidem-dir/series.csv";
  try {
    SeriesWriter s(path, {"time"});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(SeriesWriter, MoveTransfersTheFile) {
  const std::string path = temp_file("series.csv");
  {
    SeriesWriter a(path, {"t"});
    a.write_row({1.0});
    SeriesWriter b(std::move(a));
    b.write_row({2.0});
    SeriesWriter c(temp_file("other.csv"), {"x"});
    c = std::move(b);
    c.write_row({3.0});
    EXPECT_EQ(c.path(), path);
  }
  EXPECT_EQ(slurp(path), "t\n1\n2\n3\n");
  EXPECT_EQ(slurp(temp_file("other.csv")), "x\n");
  fs::remove(path);
  fs::remove(temp_file("other.csv"));
}
