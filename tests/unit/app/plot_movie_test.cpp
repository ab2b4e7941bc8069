// `fluidem plot OUT --movie --every N`: one picture per N-th frame of particles.h5 in
// OUT/movie_frames/, joined into OUT/movie.mp4 by ffmpeg. References: the frame count follows
// from the case (end_time / frame_interval + 1 frames, every N-th kept), a PNG file starts with
// "\x89PNG", an MP4 file with an "ftyp" box at byte 4 (ISO/IEC 14496-12 §4.3). Without ffmpeg the
// frames stay and the exit code is 3 with the install command.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "../../common/bouncing_spheres.hpp"
#include "../../common/cli_runner.hpp"

namespace {

using fluidem::test::contains;
using fluidem::test::fluidem;
using fluidem::test::read_file;
using fluidem::test::Result;
using fluidem::test::run_command;
using fluidem::test::TempDir;
namespace fs = std::filesystem;

// Ten discs falling for 0.05 s, a frame every 0.01 s: frames at 0, 0.01, ..., 0.05 (six).
const std::string kCase = fluidem::test::bouncing_spheres_case({.dimension = 2,
                                                                .end_time = 0.05,
                                                                .time_step = std::nullopt,
                                                                .frame_interval = 0.01,
                                                                .series_interval = std::nullopt,
                                                                .engine_key = false,
                                                                .moving = false});

TEST(PlotMovie, EveryNthFrameAndTheMovie) {
  if (run_command(std::string(FLUIDEM_PYTHON) + " -c 'import matplotlib, h5py, numpy'", ".").code !=
      0)
    GTEST_SKIP() << FLUIDEM_PYTHON << " lacks matplotlib/h5py/numpy";
  TempDir dir("fluidem_movie");
  dir.write("fall.toml", kCase);
  const Result run = fluidem({"run", "fall.toml", "--out", "out"}, dir.path);
  ASSERT_EQ(run.code, 0) << run.err;
  const Result r = fluidem({"plot", "out", "--movie", "--every", "2"}, dir.path);
  const fs::path frames = dir.path / "out" / "movie_frames";
  // Frames 0, 2, 4 of six.
  for (const char* f : {"frame_00000.png", "frame_00001.png", "frame_00002.png"}) {
    const std::string png = read_file(frames / f);
    ASSERT_GT(png.size(), 8u) << f;
    EXPECT_EQ(png.substr(0, 4), "\x89PNG") << f;
  }
  EXPECT_FALSE(fs::exists(frames / "frame_00003.png"));
  EXPECT_TRUE(contains(r.out, "3 frames in")) << r.out;
  const bool have_ffmpeg = run_command("command -v ffmpeg", ".").code == 0;
  if (have_ffmpeg) {
    ASSERT_EQ(r.code, 0) << r.out << r.err;
    const std::string mp4 = read_file(dir.path / "out" / "movie.mp4");
    ASSERT_GT(mp4.size(), 12u);
    EXPECT_EQ(mp4.substr(4, 4), "ftyp");
  } else {
    EXPECT_EQ(r.code, 3) << r.out << r.err;
    EXPECT_TRUE(contains(r.err, "apt-get install ffmpeg")) << r.err;
  }
  const Result bad = fluidem({"plot", "out", "--movie", "--every", "0"}, dir.path);
  EXPECT_NE(bad.code, 0);
}

} // namespace
