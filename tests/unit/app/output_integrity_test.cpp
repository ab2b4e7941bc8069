// The outputs of a run are the user's: what a restart, a refused restart, a full disk, a planted
// link or a second process can do to them, tried with the real fluidem binary on real files
// (issue 32, items 1-8 and 24). The reference in every case is the files themselves: a refused
// command leaves every byte as it was; a continued run's series and frames have strictly
// increasing times with no gap and no repeat; a link's target is never created or written.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "../../common/cli_runner.hpp"
#include "output/h5md_reader.hpp"

namespace {

namespace fs = std::filesystem;

using fluidem::test::contains;
using fluidem::test::finish;
using fluidem::test::quote;
using fluidem::test::read_file;
using fluidem::test::replace;
using fluidem::test::Result;
using fluidem::test::run_command;
using fluidem::test::series_times;
using fluidem::test::start_fluidem;

struct TempDir : fluidem::test::TempDir {
  explicit TempDir(const std::string& name = "")
      : fluidem::test::TempDir("fluidem_integrity" + name) {}
};

Result fluidem(const std::vector<std::string>& args, const fs::path& cwd) {
  return finish(start_fluidem(args, cwd), cwd);
}

/// `fluidem ARGS` with statvfs reporting `free_bytes` free (tests/common/fake_statvfs.c).
Result fluidem_with_free_space(const std::vector<std::string>& args, const fs::path& cwd,
                               unsigned long long free_bytes) {
  std::string cmd = "ASAN_OPTIONS=$ASAN_OPTIONS:verify_asan_link_order=0 LD_PRELOAD=" +
                    quote(FLUIDEM_FAKE_STATVFS) +
                    " FLUIDEM_FAKE_FREE_BYTES=" + std::to_string(free_bytes) + " " +
                    quote(FLUIDEM_BINARY);
  for (const auto& a : args) cmd += " " + quote(a);
  return run_command(cmd, cwd);
}

// Ten discs in a 2-D box: 0.2 s, checkpoints every 0.05 s, frames every 0.02 s, rows every 0.01 s.
const std::string kCase = R"([simulation]
dimension = 2
end_time = 0.2
time_step = 2e-5

[output]
frame_interval = 0.02
series_interval = 0.01
checkpoint_interval = 0.05

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.04, 0.004, 0.04]

[[species]]
name = "glass"
diameter = 0.004
density = 2700.0

[[insert]]
species = "glass"
count = 10
placement = "random"
seed = 1
velocity_spread = 0.5

[contact]
normal = "linear"
stiffness = 800.0

[walls]
restitution = 1.0
)";

/// Every regular file under `dir` (relative name -> bytes).
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename().string()[0] != '.')
      files[fs::relative(e.path(), dir).string()] = read_file(e.path());
  return files;
}

void expect_unchanged(const std::map<std::string, std::string>& before, const fs::path& dir) {
  const auto after = snapshot(dir);
  for (const auto& [name, bytes] : before) {
    const auto it = after.find(name);
    if (it == after.end())
      ADD_FAILURE() << name << " was removed";
    else
      EXPECT_TRUE(it->second == bytes) << name << " was changed";
  }
  for (const auto& [name, bytes] : after) EXPECT_TRUE(before.count(name)) << name << " was created";
}

/// Rows every `dt` from 0 to `end` without a repeat or a gap; frames strictly increasing.
void expect_continuous(const fs::path& out, double dt, double end) {
  const std::vector<double> t = series_times(out / "series.csv");
  ASSERT_FALSE(t.empty());
  for (std::size_t i = 1; i < t.size(); ++i)
    EXPECT_NEAR(t[i] - t[i - 1], dt, 1e-9) << "row " << i << " at t = " << t[i];
  EXPECT_NEAR(t.back(), end, 1e-9);
  const fluidem::H5mdReader h5((out / "particles.h5").string());
  const std::vector<double>& f = h5.times();
  for (std::size_t k = 1; k < f.size(); ++k)
    EXPECT_GT(f[k], f[k - 1]) << "frame " << k << " repeats or goes back";
  EXPECT_NEAR(f.back(), end, 1e-9);
}

struct FinishedRun {
  TempDir dir; ///< (named apart, so that two runs of one test get two folders)
  fs::path out;
  explicit FinishedRun(const std::string& text = kCase, const std::vector<std::string>& extra = {},
                       const std::string& name = "")
      : dir(name) {
    const fs::path c = dir.write("case.toml", text);
    out = dir.path / "out";
    std::vector<std::string> args{"run", c.string(), "--out", out.string(), "--threads", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = fluidem(args, dir.path);
    EXPECT_EQ(r.code, 0) << r.out << r.err;
  }
  Result restart(const std::string& checkpoint, const std::vector<std::string>& sets = {}) const {
    std::vector<std::string> args{"run", "--restart", (out / checkpoint).string(), "--threads",
                                  "1"};
    for (const auto& s : sets) args.insert(args.end(), {"--set", s});
    return fluidem(args, dir.path);
  }
};

// Item 1 and 4: restarting a finished run (0 steps to go) or to an end before its checkpoint is
// refused (exit 2) and adds nothing; extending it continues without a repeated row or frame.
TEST(OutputIntegrity, FinishedRunRestartedWithNothingToDoChangesNothing) {
  const FinishedRun run;
  const auto before = snapshot(run.out);
  Result r = run.restart("checkpoint.h5");
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "nothing to run")) << r.err;
  r = run.restart("checkpoint.h5", {"simulation.end_time=0.1"});
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "simulation.end_time = 0.1 s is not after")) << r.err;
  expect_unchanged(before, run.out);
  r = run.restart("checkpoint.h5", {"simulation.end_time=0.3"});
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  expect_continuous(run.out, 0.01, 0.3);
}

// Item 2: a restart that is refused touches no file, whatever refuses it.
TEST(OutputIntegrity, RefusedRestartLeavesEveryFileAsItWas) {
  const FinishedRun run;
  const auto before = snapshot(run.out);
  // An output the continued run did not write, switched on (it used to cut particles.h5 and
  // series.csv, then fail on collisions.csv).
  Result r =
      run.restart("checkpoint.prev.h5", {"output.collisions=true", "simulation.end_time=0.5"});
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "collisions.csv")) << r.err;
  expect_unchanged(before, run.out);
  // The checkpoint of another case (same box and count, hard spheres) in its place.
  const FinishedRun hard(
      replace(kCase, "[simulation]\n", "[simulation]\nengine = \"hard_sphere\"\n"), {}, "_hard");
  fs::copy_file(hard.out / "checkpoint.h5", run.out / "checkpoint.h5",
                fs::copy_options::overwrite_existing);
  auto expected = before;
  expected["checkpoint.h5"] = read_file(run.out / "checkpoint.h5");
  r = run.restart("checkpoint.h5", {"simulation.end_time=0.5"});
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  expect_unchanged(expected, run.out);
}

// Item 3: outputs that stop short of the checkpoint (a gap), or belong to another run (another
// insertion seed), are refused, naming the file.
TEST(OutputIntegrity, GapsAndAnotherRunsOutputsAreRefused) {
  const FinishedRun run;
  const std::string series = read_file(run.out / "series.csv");
  std::string cut = series.substr(0, series.find("0.1,")); // the rows up to 0.09 s
  std::ofstream(run.out / "series.csv", std::ios::binary) << cut;
  auto before = snapshot(run.out);
  Result r = run.restart("checkpoint.h5", {"simulation.end_time=0.5"});
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "series.csv")) << r.err;
  EXPECT_TRUE(contains(r.err, "gap")) << r.err;
  expect_unchanged(before, run.out);
  std::ofstream(run.out / "series.csv", std::ios::binary) << series;

  const FinishedRun other(replace(kCase, "seed = 1", "seed = 2"), {}, "_other");
  fs::copy_file(other.out / "checkpoint.h5", run.out / "checkpoint.h5",
                fs::copy_options::overwrite_existing);
  before = snapshot(run.out);
  r = run.restart("checkpoint.h5", {"simulation.end_time=0.5"});
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "belongs to run")) << r.err;
  expect_unchanged(before, run.out);
}

// Item 2 (the cut itself): a restart from the earlier checkpoint drops what came after it and
// continues; no temporary file is left behind.
TEST(OutputIntegrity, RestartFromAnEarlierCheckpointContinuesWithoutRepeats) {
  const FinishedRun run;
  const Result r = run.restart("checkpoint.prev.h5", {"simulation.end_time=0.25"});
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  expect_continuous(run.out, 0.01, 0.25);
  for (const auto& e : fs::directory_iterator(run.out))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

// Item 5: a disk that fills up mid-run: exit 4 with the system's reason, the last good
// checkpoint kept (the run continues from it once there is room), no temporary file left, no
// crash at exit (HDF5's exit handler used to SIGSEGV on the checkpoint whose close had failed).
// The disk: a 16 MB tmpfs in a private mount namespace (unshare), filled up once the run has
// written its first checkpoint; where mounts are not allowed, a file size limit (ulimit -f:
// EFBIG on the checkpoint instead of ENOSPC, the same error path).
TEST(OutputIntegrity, DiskFullMidRunExits4AndKeepsTheLastCheckpoint) {
  const TempDir dir;
  const fs::path c = dir.write("case.toml", replace(kCase, "end_time = 0.2", "end_time = 5.0"));
  const std::string run = quote(FLUIDEM_BINARY) + " run " + quote(c.string()) +
                          " --out run --threads 1 --set output.checkpoint_interval=0.01";
  const std::string restart = quote(FLUIDEM_BINARY) +
                              " run --restart run/checkpoint.h5 --set simulation.end_time=5.5 "
                              "--threads 1 > ../restart.out 2>&1; echo $? > ../restart_rc; ls -a "
                              "run > ../listing2";
  // The mount and the cd happen in the foreground shell, so that the filler lands in the tmpfs;
  // dd writes at most 32 MB (twice the tmpfs) wherever it lands.
  const std::string script =
      "set -u; cd " + quote(dir.path.string()) +
      "; if unshare -Urm true 2>/dev/null; then mode=tmpfs; else mode=ulimit; fi; echo $mode > "
      "mode\n"
      "if [ $mode = tmpfs ]; then exec unshare -Urm sh -c '"
      "mkdir -p disk && mount -t tmpfs -o size=16m tmpfs disk || exit 9; cd disk || exit 9; "
      "(" +
      run +
      " > ../run.out 2>&1; echo $? > ../rc) & "
      "i=0; while [ ! -f run/checkpoint.h5 ] && [ $i -lt 600 ]; do sleep 0.05; i=$((i+1)); done; "
      "dd if=/dev/zero of=filler bs=64k count=512 >/dev/null 2>&1; wait; "
      "ls -a run > ../listing; rm -f filler; " +
      restart +
      "'\n"
      "else mkdir -p disk && cd disk && (trap \"\" XFSZ; ulimit -f 200; " +
      run + " > ../run.out 2>&1; echo $? > ../rc); ls -a run > ../listing; " + restart + "; fi";
  std::ofstream(dir.path / "disk_full.sh") << script;
  run_command("sh disk_full.sh", dir.path);
  const std::string out = read_file(dir.path / "run.out");
  EXPECT_EQ(read_file(dir.path / "rc"), "4\n") << read_file(dir.path / "mode") << out;
  EXPECT_TRUE(contains(out, "No space left on device") || contains(out, "File too large")) << out;
  EXPECT_TRUE(contains(out, "the last good checkpoint")) << out;
  const std::string listing = read_file(dir.path / "listing");
  EXPECT_TRUE(contains(listing, "checkpoint.h5\n")) << listing;
  EXPECT_FALSE(contains(listing, ".tmp")) << listing;
  EXPECT_FALSE(contains(listing, ".fluidem-write-test")) << listing;
  EXPECT_EQ(read_file(dir.path / "restart_rc"), "0\n") << read_file(dir.path / "restart.out");
  EXPECT_FALSE(contains(read_file(dir.path / "listing2"), ".tmp"));
}

// Item 5: the disk check counts the series rows (a fine series_interval used to pass the check
// and fill the disk). Item 24: frames come at most once a step (frame_interval = 1e-12 used to
// be refused as needing 2.3e5 MB).
TEST(OutputIntegrity, DiskCheckCountsRowsAndClampsFramesToSteps) {
  const TempDir dir;
  const fs::path c = dir.write("case.toml", kCase);
  Result r = fluidem_with_free_space(
      {"run", c.string(), "--out", "rows", "--set", "simulation.end_time=50", "--set",
       "output.series_interval=2e-5", "--set", "output.frame_interval=50"},
      dir.path, 100'000'000ULL);
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "not enough disk space")) << r.err;
  EXPECT_FALSE(fs::exists(dir.path / "rows" / "series.csv"));
  r = fluidem_with_free_space({"run", c.string(), "--out", "frames", "--set",
                               "simulation.end_time=0.002", "--set", "output.frame_interval=1e-12"},
                              dir.path, 1'000'000'000ULL);
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_EQ(fluidem::H5mdReader((dir.path / "frames" / "particles.h5").string()).frames(), 101u);
}

// Item 6: --force checks everything before it deletes anything, then removes fluidem's files
// (the pictures, the analysis and the movie too), and nothing else.
TEST(OutputIntegrity, ForceChecksBeforeDeletingAndRemovesOnlyFluidemsFiles) {
  const FinishedRun run;
  fs::create_directories(run.out / "analysis");
  fs::create_directories(run.out / "movie_frames");
  for (const char* f :
       {"snapshot.png", "movie.mp4", "analysis/summary.csv", "analysis/spectrum_p1.png",
        "movie_frames/frame_00001.png", "analysis/my_notes.txt", "my_notes.txt"})
    std::ofstream(run.out / f) << "x";
  const auto before = snapshot(run.out);
  const fs::path c = run.dir.path / "case.toml";
  Result r = fluidem_with_free_space(
      {"run", c.string(), "--out", run.out.string(), "--force", "--set", "simulation.end_time=50"},
      run.dir.path, 1000);
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "not enough disk space")) << r.err;
  expect_unchanged(before, run.out);
  r = fluidem({"run", c.string(), "--out", run.out.string(), "--force", "--set",
               "simulation.end_time=0.05"},
              run.dir.path);
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  for (const char* gone : {"snapshot.png", "movie.mp4", "analysis/summary.csv",
                           "analysis/spectrum_p1.png", "movie_frames", "checkpoint.prev.h5"})
    EXPECT_FALSE(fs::exists(run.out / gone)) << gone;
  for (const char* kept : {"analysis/my_notes.txt", "my_notes.txt"})
    EXPECT_TRUE(fs::exists(run.out / kept)) << kept;
  expect_continuous(run.out, 0.01, 0.05);
}

// Item 7: a symbolic link under one of fluidem's names is refused (exit 2, naming it), dangling
// or not; its target is never created or written. The old write-test name is no longer used.
TEST(OutputIntegrity, LinksUnderFluidemsNamesAreNeverWrittenThrough) {
  const TempDir dir;
  const fs::path c = dir.write("case.toml", kCase);
  for (const std::string name :
       {"series.csv", "particles.h5", "checkpoint.h5.tmp", "case.resolved.toml", "fields.xmf"}) {
    const fs::path out = dir.path / ("out_" + name), victim = dir.path / ("victim_" + name);
    fs::create_directories(out);
    fs::create_symlink(victim, out / name);
    const Result r = fluidem({"run", c.string(), "--out", out.string()}, dir.path);
    EXPECT_EQ(r.code, 2) << name << ": " << r.out << r.err;
    EXPECT_TRUE(contains(r.err, (out / name).string() + "' is a symbolic link")) << r.err;
    EXPECT_FALSE(fs::exists(fs::symlink_status(victim))) << name << ": the link was followed";
  }
  const fs::path out = dir.path / "out_probe", victim = dir.path / "victim_probe";
  fs::create_directories(out);
  fs::create_symlink(victim, out / ".fluidem-write-test");
  const Result r = fluidem(
      {"run", c.string(), "--out", out.string(), "--set", "simulation.end_time=0.02"}, dir.path);
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_FALSE(fs::exists(fs::symlink_status(victim)));
  // analyse writes into analysis/: a link there is refused too.
  fs::create_directories(out / "analysis");
  fs::create_symlink(victim, out / "analysis" / "summary.csv");
  const Result a = fluidem({"analyse", out.string()}, dir.path);
  EXPECT_EQ(a.code, 2) << a.out << a.err;
  EXPECT_FALSE(fs::exists(fs::symlink_status(victim)));
}

// Item 8: one process at a time writes into a directory: a second run, or analyse, started
// while a run goes is refused (exit 2) and the run's series stays one run's.
TEST(OutputIntegrity, SecondProcessIntoARunningDirectoryIsRefused) {
  const TempDir dir;
  const fs::path c = dir.write("case.toml", replace(kCase, "end_time = 0.2", "end_time = 1000"));
  const fs::path out = dir.path / "out";
  const fs::path first = dir.path / "first", second = dir.path / "second";
  fs::create_directories(first);
  fs::create_directories(second);
  const pid_t pid =
      start_fluidem({"run", c.string(), "--out", out.string(), "--threads", "1"}, first);
  const auto t0 = std::chrono::steady_clock::now();
  while (!fs::exists(out / "series.csv") &&
         std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  Result r =
      fluidem({"run", c.string(), "--out", out.string(), "--threads", "1", "--force"}, second);
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "in use by another fluidem process")) << r.err;
  r = fluidem({"analyse", out.string()}, second);
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_TRUE(contains(r.err, "in use by another fluidem process")) << r.err;
  ::kill(pid, SIGTERM);
  r = finish(pid, first);
  EXPECT_EQ(r.code, 143) << r.out << r.err;
  const std::vector<double> t = series_times(out / "series.csv");
  for (std::size_t i = 1; i < t.size(); ++i) EXPECT_GT(t[i], t[i - 1]) << "row " << i;
}

// Item 8, started together (both used to pass the checks within the 0.2 s busy-core probe):
// exactly one runs.
TEST(OutputIntegrity, TwoRunsStartedTogetherIntoOneDirectoryOneIsRefused) {
  const TempDir dir;
  const fs::path c = dir.write("case.toml", kCase);
  const fs::path out = dir.path / "out", a = dir.path / "a", b = dir.path / "b";
  fs::create_directories(a);
  fs::create_directories(b);
  const pid_t pa = start_fluidem({"run", c.string(), "--out", out.string(), "--threads", "2"}, a);
  const pid_t pb = start_fluidem({"run", c.string(), "--out", out.string(), "--threads", "2"}, b);
  const Result ra = finish(pa, a), rb = finish(pb, b);
  EXPECT_EQ((ra.code == 0) + (rb.code == 0), 1) << ra.err << rb.err;
  EXPECT_EQ((ra.code == 2) + (rb.code == 2), 1) << ra.err << rb.err;
  expect_continuous(out, 0.01, 0.2);
}

// Item 10: the command line says what is wrong in one line.
TEST(OutputIntegrity, CommandLineMistakesAreNamed) {
  const TempDir dir;
  const fs::path c = dir.write("case.toml", kCase);
  for (const std::string bad : {"-1", "abc", "0", "2000"}) {
    const Result r = fluidem({"run", c.string(), "--threads", bad}, dir.path);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
    EXPECT_TRUE(contains(r.err, "from 1 to 1024")) << r.err;
    EXPECT_LT(r.err.size(), 400u) << r.err;
  }
  Result r = fluidem(
      {"run", c.string(), "--out", "many", "--threads", "64", "--set", "simulation.end_time=0.01"},
      dir.path);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "--threads 64 on a machine with")) << r.err;
  r = fluidem({"frobnicate"}, dir.path);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "unknown command 'frobnicate'")) << r.err;
  r = fluidem({"run", c.string(), "--out", ""}, dir.path);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "empty path")) << r.err;
}

} // namespace
