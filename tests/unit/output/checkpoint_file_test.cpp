// The checkpoint file (output/checkpoint_file.hpp): arrays of every type come back bitwise; a
// truncated file, a flipped byte, a missing array or a wrong type are CheckpointErrors naming
// the file (and the previous checkpoint when there is one); a commit that fails (here: the
// temporary file cannot be created) throws and leaves the existing checkpoint intact and
// loadable; a second commit keeps the first as checkpoint.prev.h5.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "output/checkpoint_file.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;

struct Dir {
  fs::path path;
  Dir() {
    path = fs::temp_directory_path() /
           ("fluidem_ckpt_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Dir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

void spit(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f.write(text.data(), static_cast<std::streamsize>(text.size()));
}

void write_sample(const std::string& path, double marker) {
  CheckpointWriter w(path);
  w.put("a/doubles", std::vector<double>{marker, -0.0, 1e-300, std::numeric_limits<double>::max(),
                                         std::numeric_limits<double>::quiet_NaN()});
  w.put("a/b/int64", std::vector<std::int64_t>{-5, 1LL << 62});
  w.put("int32", std::vector<std::int32_t>{-7, 7});
  w.put("uint32", std::vector<std::uint32_t>{0u, 4294967295u});
  w.put("bytes", std::vector<std::uint8_t>{0, 255, 10});
  w.put("empty", std::vector<double>{});
  w.put_string("text", "line one\nline \"two\"");
  w.put_scalar("scalar", 2.5);
  w.commit();
}

TEST(CheckpointFile, EveryTypeRoundTripsBitwise) {
  Dir d;
  const std::string p = (d.path / "checkpoint.h5").string();
  write_sample(p, 1.0 / 3.0);
  const CheckpointReader r(p);
  const auto v = r.doubles("a/doubles");
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v[0], 1.0 / 3.0);
  EXPECT_TRUE(std::signbit(v[1]));
  EXPECT_EQ(v[2], 1e-300);
  EXPECT_EQ(v[3], std::numeric_limits<double>::max());
  EXPECT_TRUE(std::isnan(v[4]));
  EXPECT_EQ(r.int64s("a/b/int64"), (std::vector<std::int64_t>{-5, 1LL << 62}));
  EXPECT_EQ(r.int32s("int32"), (std::vector<std::int32_t>{-7, 7}));
  EXPECT_EQ(r.uint32s("uint32"), (std::vector<std::uint32_t>{0u, 4294967295u}));
  EXPECT_EQ(r.bytes("bytes"), (std::vector<std::uint8_t>{0, 255, 10}));
  EXPECT_TRUE(r.doubles("empty").empty());
  EXPECT_EQ(r.string("text"), "line one\nline \"two\"");
  EXPECT_EQ(r.scalar("scalar"), 2.5);
  EXPECT_FALSE(fs::exists(p + ".tmp"));
}

// put_view stores no copy: the file must be the one put (a copy) gives, byte for byte
// (same arrays, same checksum), for every type; an empty view and a view replaced by a copy
// under the same name included.
TEST(CheckpointFile, ViewsWriteTheSameFileAsCopies) {
  Dir d;
  const std::vector<double> dbl{1.0 / 3.0, -0.0, 1e-300};
  const std::vector<std::int64_t> i64{-5, 1LL << 62};
  const std::vector<std::int32_t> i32{-7, 7};
  const std::vector<std::uint32_t> u32{0u, 4294967295u};
  const std::vector<std::uint8_t> u8{0, 255, 10};
  const std::vector<double> empty;
  const std::string copied = (d.path / "copied.h5").string();
  const std::string viewed = (d.path / "viewed.h5").string();
  {
    CheckpointWriter w(copied);
    w.put("a/doubles", dbl), w.put("i64", i64), w.put("i32", i32), w.put("u32", u32);
    w.put("u8", u8), w.put("empty", empty), w.put("replaced", i32);
    w.commit();
  }
  {
    CheckpointWriter w(viewed);
    w.put_view("a/doubles", dbl), w.put_view("i64", i64), w.put_view("i32", i32);
    w.put_view("u32", u32), w.put_view("u8", u8), w.put_view("empty", empty);
    w.put_view("replaced", dbl);
    w.put("replaced", i32);
    w.commit();
  }
  const CheckpointReader r(viewed); // checksum verified here
  EXPECT_EQ(r.doubles("a/doubles").size(), 3u);
  EXPECT_TRUE(std::signbit(r.doubles("a/doubles")[1]));
  EXPECT_EQ(r.int64s("i64"), i64);
  EXPECT_EQ(r.int32s("replaced"), i32);
  EXPECT_EQ(slurp(copied), slurp(viewed));
}

TEST(CheckpointFile, MissingArrayAndWrongTypeNameTheFile) {
  Dir d;
  const std::string p = (d.path / "checkpoint.h5").string();
  write_sample(p, 1.0);
  const CheckpointReader r(p);
  try {
    r.doubles("no/such");
    ADD_FAILURE();
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no/such"), std::string::npos) << e.what();
  }
  EXPECT_THROW(r.int32s("a/doubles"), CheckpointError);
  EXPECT_THROW(r.scalar("a/doubles"), CheckpointError); // 5 values, not a scalar
}

TEST(CheckpointFile, DamageIsDetectedAndThePreviousCheckpointIsNamed) {
  Dir d;
  const std::string p = (d.path / "checkpoint.h5").string();
  write_sample(p, 1.0);
  write_sample(p, 2.0); // the first becomes checkpoint.prev.h5
  const std::string prev = previous_checkpoint_path(p);
  EXPECT_EQ(fs::path(prev).filename(), "checkpoint.prev.h5");
  EXPECT_EQ(CheckpointReader(prev).doubles("a/doubles")[0], 1.0);
  const std::string good = slurp(p);
  int detected = 0, tried = 0;
  // Truncations at several lengths, and single flipped bytes all over the file: each either
  // fails to open or fails the checksum; none is silently accepted with changed contents.
  for (std::size_t len : {std::size_t{0}, good.size() / 4, good.size() / 2, good.size() - 1}) {
    spit(p, good.substr(0, len));
    ++tried;
    try {
      CheckpointReader r(p);
    } catch (const CheckpointError& e) {
      ++detected;
      EXPECT_NE(std::string(e.what()).find(prev), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(detected, tried) << "a truncated checkpoint was accepted";
  int accepted_changed = 0;
  for (std::size_t at = 0; at < good.size(); at += 97) {
    std::string bad = good;
    bad[at] = static_cast<char>(bad[at] ^ 0x20);
    spit(p, bad);
    try {
      CheckpointReader r(p);
      // Accepted: only allowed if the byte was not part of the data (e.g. free space).
      if (r.doubles("a/doubles")[0] != 2.0 || r.string("text") != "line one\nline \"two\"")
        ++accepted_changed;
    } catch (const CheckpointError&) {
    }
  }
  EXPECT_EQ(accepted_changed, 0) << "a corrupted checkpoint was accepted with changed contents";
  spit(p, good);
  EXPECT_NO_THROW(CheckpointReader{p});
}

TEST(CheckpointFile, FailedCommitLeavesTheExistingCheckpointIntact) {
  Dir d;
  const std::string p = (d.path / "checkpoint.h5").string();
  write_sample(p, 1.0);
  const std::string before = slurp(p);
  fs::create_directories(p + ".tmp"); // the temporary file cannot be created
  EXPECT_THROW(write_sample(p, 2.0), std::runtime_error);
  EXPECT_EQ(slurp(p), before);
  EXPECT_EQ(CheckpointReader(p).doubles("a/doubles")[0], 1.0);
}

} // namespace
} // namespace fluidem
