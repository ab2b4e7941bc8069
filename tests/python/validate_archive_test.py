#!/usr/bin/python3
"""The archive of the full-size validation runs (python/fluidem_validate.py, --archive): a run of
hours made on one machine at one commit is reported at a later commit on another machine.

- archive_run keeps the small outputs (CSV, TOML, the analysis tables and pictures) and the
  record, not the HDF5 files (hundreds of MB for a full-size run) nor the checkpoints; the
  record's command line is written with cases/ and WORK/ in place of the folders.
- archived_run recognises the same run made in another checkout, work folder and thread count,
  and not a run with other overrides.
- `--report-only` with an empty work folder takes the run from the archive: the report shows
  the archived value and the archived record's commit, thread count and wall time.
- A long run carried across machines: `--park` keeps a stopped run's checkpoint, record and
  small outputs in ARCHIVE/<run>.parked; `--resume` in a fresh work folder continues it from
  that checkpoint into new output files (`fluidem run --restart`), and when it finishes the
  archive holds its time series joined over the pieces (no row twice, none lost), the wall
  times and commits of all pieces, and no parked copy.
"""
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(SOURCE, "python"))
import fluidem_validate as fv  # noqa: E402

# The summary rows the velocity_ideal quantities read (the values of the 3 s run of 2026-12-07).
SUMMARY = """name,value,unit
velocity_kurtosis_x,4.727292273,1
velocity_kurtosis_z,4.685608785,1
velocity_kurtosis_local_x,2.939926068,1
velocity_kurtosis_local_z,2.938986443,1
anisotropy,1.012217219,1
"""


def make_run(work, cases, name, extra=()):
    out = os.path.join(work, name)
    os.makedirs(os.path.join(out, "analysis"))
    for f, text in (("series.csv", "time,x\n0,1\n"), ("case.resolved.toml", "[simulation]\n"),
                    ("particles.h5", "not small"), ("fields.h5", "not small"),
                    ("checkpoint.h5", "not small"), ("particles.xmf", "<Xdmf/>"),
                    (os.path.join("analysis", "summary.csv"), SUMMARY),
                    (os.path.join("analysis", "velocity_distribution.png"), "png")):
        with open(os.path.join(out, f), "w") as fh:
            fh.write(text)
    words = (["run", os.path.join(cases, "deen07", "velocity_ideal.toml"), "--out", out,
              "--force"] + list(extra) + ["--threads", "1"])
    done = os.path.join(work, name + ".done")
    with open(done, "w") as fh:
        fh.write(" ".join(words) + "\n2544.6\nabc1234\n1\n")
    return out, done, words


class Archive(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = self.tmp.name
        self.work = os.path.join(self.root, "work")
        self.archive = os.path.join(self.root, "archive")

    def tearDown(self):
        self.tmp.cleanup()

    def test_keeps_the_small_outputs_and_a_portable_record(self):
        cases = os.path.join(self.root, "checkout", "cases")
        out, done, words = make_run(self.work, cases, "velocity_ideal")
        fv.archive_run(out, done, self.archive, "velocity_ideal", cases, self.work)
        kept = os.path.join(self.archive, "velocity_ideal")
        self.assertEqual(sorted(os.listdir(kept)),
                         ["analysis", "case.resolved.toml", "series.csv"])
        self.assertEqual(sorted(os.listdir(os.path.join(kept, "analysis"))),
                         ["summary.csv", "velocity_distribution.png"])
        with open(os.path.join(self.archive, "velocity_ideal.done")) as fh:
            lines = fh.read().split("\n")
        self.assertEqual(lines[0], "run cases/deen07/velocity_ideal.toml --out "
                         "WORK/velocity_ideal --force")
        self.assertEqual(lines[1:4], ["2544.6", "abc1234", "1"])
        # Archiving again replaces the copy (no folder left behind).
        fv.archive_run(out, done, self.archive, "velocity_ideal", cases, self.work)
        self.assertEqual(sorted(os.listdir(self.archive)),
                         ["velocity_ideal", "velocity_ideal.done"])

        # The same run seen from another checkout, work folder and thread count...
        other_cases = os.path.join(self.root, "ci", "cases")
        other_work = os.path.join(self.root, "other")
        same = ["run", os.path.join(other_cases, "deen07", "velocity_ideal.toml"), "--out",
                os.path.join(other_work, "velocity_ideal"), "--force", "--threads", "2"]
        self.assertTrue(fv.archived_run(self.archive, "velocity_ideal", same, other_cases,
                                        other_work))
        # ... but not a run with another override.
        self.assertFalse(fv.archived_run(self.archive, "velocity_ideal",
                                         same + ["--set", "simulation.end_time=1"],
                                         other_cases, other_work))
        self.assertFalse(fv.archived_run(self.archive, "velocity_nonideal", same, other_cases,
                                         other_work))

    def test_report_only_takes_an_archived_run(self):
        out, done, _ = make_run(self.work, fv.CASES, "velocity_ideal")
        fv.archive_run(out, done, self.archive, "velocity_ideal", fv.CASES, self.work)
        empty = os.path.join(self.root, "empty")
        report = os.path.join(self.root, "report", "README.md")
        r = subprocess.run([sys.executable, os.path.join(SOURCE, "python", "fluidem_validate.py"),
                            "--fluidem", "/bin/true", "--long", "--report-only", "--only",
                            "velocity_ideal", "--work", empty, "--archive", self.archive,
                            "--report", report], capture_output=True, text=True)
        self.assertIn("taken from the archive", r.stdout, r.stdout + r.stderr)
        with open(report) as fh:
            text = fh.read()
        # The archived values: kurtosis 4.73 pooled (the farther of x and z), 2.94 local.
        rows = [line for line in text.split("\n") if line.startswith("| velocity_ideal | [")]
        self.assertEqual(len(rows), 2, text)
        self.assertIn("| 4.73 |", rows[0])
        self.assertIn("| 2.94 |", rows[1])
        # The runs table: the archived record's commit, threads and wall time.
        self.assertIn("| abc1234 | 1 | 2545 s |", text)
        # The reduced case, neither in the work folder nor archived: not run.
        self.assertIn("not run for this report", text)


# A stand-in for the fluidem binary: `run` writes the series of times START..END (step 0.25)
# into OUT/series.csv and a checkpoint, where START is 0 or the time in the checkpoint file it
# restarts from and END is the environment's FAKE_END (the run "stopped" there: exit 143 when
# FAKE_END is below the case's 60 s); `analyse` writes OUT/analysis/segregation.csv (s = t/100
# per frame); every call is logged to FAKE_LOG.
FAKE = r"""#!/usr/bin/python3
import os, sys
args = sys.argv[1:]
with open(os.environ["FAKE_LOG"], "a") as f:
    f.write(" ".join(args) + "\n")
out = args[args.index("--out") + 1] if "--out" in args else args[1]
if args[0] == "run":
    start = 0.0
    if "--restart" in args:
        with open(args[args.index("--restart") + 1]) as f:
            start = float(f.read())
    end = float(os.environ["FAKE_END"])
    os.makedirs(out, exist_ok=True)
    times = [start + 0.25 * k for k in range(int(round((end - start) / 0.25)) + 1)]
    with open(os.path.join(out, "series.csv"), "w") as f:
        f.write("time,pressure_drop\n" + "".join(f"{t},{t * 2}\n" for t in times))
    with open(os.path.join(out, "checkpoint.h5"), "w") as f:
        f.write(str(end))
    sys.exit(0 if end >= 60.0 else 143)
if args[0] == "analyse":
    with open(os.path.join(out, "series.csv")) as f:
        times = [float(line.split(",")[0]) for line in f.read().splitlines()[1:]]
    os.makedirs(os.path.join(out, "analysis"), exist_ok=True)
    with open(os.path.join(out, "analysis", "segregation.csv"), "w") as f:
        f.write("time,s\n" + "".join(f"{t},{t / 100}\n" for t in times))
"""


class Parked(unittest.TestCase):
    """A long run made in three pieces on three "machines" (fresh work folders)."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = self.tmp.name
        self.archive = os.path.join(self.root, "archive")
        self.fake = os.path.join(self.root, "fluidem")
        with open(self.fake, "w") as f:
            f.write(FAKE)
        os.chmod(self.fake, 0o755)
        self.log = os.path.join(self.root, "calls.log")

    def tearDown(self):
        self.tmp.cleanup()

    def validate(self, work, *args, end=60.0):
        env = dict(os.environ, FAKE_LOG=self.log, FAKE_END=str(end))
        return subprocess.run([sys.executable, os.path.join(SOURCE, "python",
                                                            "fluidem_validate.py"),
                               "--fluidem", self.fake, "--long", "--only",
                               "segregation_standard", "--work", work, "--archive",
                               self.archive, "--report", os.path.join(work, "report.md"),
                               "--threads", "1"] + list(args),
                              capture_output=True, text=True, env=env)

    def calls(self):
        with open(self.log) as f:
            return [line.split(" ") for line in f.read().splitlines()]

    def test_three_pieces_make_one_run(self):
        parked = os.path.join(self.archive, "segregation_standard.parked")
        # Machine 1: stopped at 20 s, then parked.
        w1 = os.path.join(self.root, "m1")
        r = self.validate(w1, "--resume", end=20.0)
        self.assertEqual(r.returncode, 143, r.stdout + r.stderr)
        self.assertFalse(os.path.exists(parked))
        r = self.validate(w1, "--park")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertEqual(sorted(os.listdir(parked)), ["checkpoint.h5", "pieces",
                                                      "record.started"])
        with open(os.path.join(parked, "record.started")) as f:
            rec = f.read().split("\n")
        self.assertTrue(rec[0].startswith("run cases/deen07/segregation_standard.toml --out "
                                          "WORK/segregation_standard --force"), rec[0])
        self.assertEqual(rec[4], "1")
        # Machine 2: continues from the parked checkpoint into new files, stopped at 45 s.
        w2 = os.path.join(self.root, "m2")
        r = self.validate(w2, "--resume", end=45.0)
        self.assertEqual(r.returncode, 143, r.stdout + r.stderr)
        run = self.calls()[-1]
        self.assertEqual(run[:5], ["run", "--restart", os.path.join(parked, "checkpoint.h5"),
                                   "--out", os.path.join(w2, "segregation_standard")])
        self.assertIn("--force", run)
        self.assertEqual(self.validate(w2, "--park").returncode, 0)
        self.assertEqual(sorted(os.listdir(os.path.join(parked, "pieces"))), ["001", "002"])
        # Machine 3: the last piece, to 60 s; then the archive holds one run.
        w3 = os.path.join(self.root, "m3")
        r = self.validate(w3, "--resume", end=60.0)
        self.assertIn("archived", r.stdout, r.stdout + r.stderr)
        self.assertFalse(os.path.exists(parked))
        kept = os.path.join(self.archive, "segregation_standard")
        self.assert_whole_series(kept)
        with open(os.path.join(self.archive, "segregation_standard.done")) as f:
            done = f.read().split("\n")
        self.assertEqual(done[0], rec[0])
        self.assertEqual(done[3:5], ["1", "3"])  # threads, the last piece's number
        # Reused and archived again (re-analysed at a later commit): the earlier pieces come
        # from the archived copy, which still covers 0-60 s.
        r = self.validate(w3, "--reuse")
        self.assertIn("run reused", r.stdout, r.stdout + r.stderr)
        self.assert_whole_series(kept)

    def test_a_run_started_over_is_not_joined_to_parked_pieces(self):
        # Parked at 20 s, then run again from the start in one piece (no --resume): the
        # archive holds that run alone, and the stale parked copy of it is removed.
        w1 = os.path.join(self.root, "m1")
        self.validate(w1, "--resume", end=20.0)
        self.assertEqual(self.validate(w1, "--park").returncode, 0)
        r = self.validate(os.path.join(self.root, "m2"), end=60.0)
        self.assertIn("archived", r.stdout, r.stdout + r.stderr)
        self.assert_whole_series(os.path.join(self.archive, "segregation_standard"))
        self.assertFalse(os.path.exists(os.path.join(self.archive,
                                                     "segregation_standard.parked")))

    def assert_whole_series(self, kept):
        for name, column in (("series.csv", 2.0), (os.path.join("analysis", "segregation.csv"),
                                                   0.01)):
            with open(os.path.join(kept, name)) as f:
                lines = f.read().splitlines()
            times = [float(line.split(",")[0]) for line in lines[1:]]
            # Every time of 0-60 s once, in order: 241 rows, the pieces' seams (20 s, 45 s)
            # not doubled.
            self.assertEqual(times, [0.25 * k for k in range(241)], name)
            self.assertAlmostEqual(float(lines[-1].split(",")[1]), 60.0 * column)

    def test_a_parked_run_of_another_case_setting_is_not_continued(self):
        w1 = os.path.join(self.root, "m1")
        self.validate(w1, "--resume", end=20.0)
        self.assertEqual(self.validate(w1, "--park").returncode, 0)
        rec = os.path.join(self.archive, "segregation_standard.parked", "record.started")
        with open(rec) as f:
            lines = f.read().split("\n")
        lines[0] += " --set simulation.end_time=30"
        with open(rec, "w") as f:
            f.write("\n".join(lines))
        w2 = os.path.join(self.root, "m2")
        self.validate(w2, "--resume", end=20.0)
        self.assertNotIn("--restart", self.calls()[-1])

    def test_nothing_to_park(self):
        r = self.validate(os.path.join(self.root, "empty"), "--park")
        self.assertEqual(r.returncode, 1)
        self.assertIn("no stopped full-size run to park", r.stderr)


if __name__ == "__main__":
    unittest.main()
