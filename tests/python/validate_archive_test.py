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


if __name__ == "__main__":
    unittest.main()
