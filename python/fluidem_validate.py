#!/usr/bin/python3
"""fluidem's validation report: run the seeds' cases, compare with the published numbers.

Called by `fluidem validate [--quick]` (docs/validation/README.md says how to read the report):

    fluidem_validate.py --fluidem BIN [--quick] [--work DIR] [--report FILE] [--only TEXT]
                        [--threads N] [--list]

Each run is `fluidem run CASE --set ...` into WORK/<run>, then `fluidem analyse` (and `fluidem
plot` for the pictures); each compared quantity is read from the run's outputs (the
summary.csv rows and tables of `fluidem analyse`, series.csv) and set beside the published
value with the criterion it is judged by. The report is a Markdown file with one table and the
pictures copied beside it. Full runs (the default) write docs/validation/README.md of the source
tree; `--quick` runs short versions (ctest label `regression`): their numbers are not comparable
with the papers and the report says so; the quick mode checks that every run completes and every
quantity is extracted.

The published values are data, beside the cases: cases/<folder>/reference.toml of every case
folder of RUNS (hoomans96, chang08, deen07). This script keeps the logic only: the runs (RUNS),
how each compared value is read from their outputs (VALUES, keyed by the quantity's id; its
order is the order of the report's rows) and the criterion kinds (CRITERIA). A reference.toml
holds:

  [[quantity]]           one compared quantity, a row of the report
    id         string    its key in VALUES, e.g. "pouring_soft.area_fraction"
    case       string    the report's case column (a run's name)
    source     string    paper and section / figure / table: "[Hoomans96 §5.1]"
    quantity   string    what is compared, as the report shows it
    published  string    the published value as the report shows it: "0.832 ± 0.010"
    value      number    the published number, where there is one (optional; needed by
                         within_abs and within_rel, which compare with it)
    spread     number    its published spread (optional, for the reader)
    unit       string    unit of value and of fluidem's value, shown after it ("" for a ratio,
                         a fraction or a count)
    format     string    Python format spec of fluidem's value: ".3f", ".2e", ".3g"
    note       string    why, where it matters (optional)
    tried      string    expect.status "disagrees": what was tried to find the cause and what
                         that rules out (the report's section on the disagreements)
    [quantity.criterion]
    kind       string    within_abs  |v - value| <= tolerance
                         within_rel  |v / value - 1| <= tolerance
                         above  v > bound;  at_least  v >= bound;  below  v < bound
                         between  lower <= v <= upper
                         none  nothing to compare (no published number)
    tolerance, bound, lower, upper   numbers: the kind's parameters, exactly these
    text       string    the report's criterion column: "within 0.020 (twice the published
                         spread)"
    [quantity.expect]    what the runs are expected to give: the gate (below)
    status     string    "agrees" (the full run meets the criterion), "disagrees" (it does
                         not; `note` says why), "no_criterion" (criterion kind "none") or
                         "not_established" (a full-size case not run at a recorded commit)
    band       [lo, hi]  "disagrees": the range the full run's value is recorded in
    quick      [lo, hi]  the range of the quick variant's value (--quick), recorded from a run
                         of that variant: a regression band, wide enough for the round-off
                         changes a chaotic bed amplifies in its short run (about 20%)
  [[not_run]]            a seed case the report lists but cannot run, with the reason
    case, source, quantity, published, reason   strings
    value, unit          the published number(s) and unit(s) (optional; a list each when the
                         published text quotes several)

Every file is checked before anything runs (also with --list): a key missing, unknown or of the
wrong type, an unknown criterion kind, an id that VALUES does not know, an id of VALUES with no
[[quantity]], or a file that cannot be read stops the script with exit status 2 and a message
naming the file and the key.

The gate: a full run fails the report when a quantity expected to agree does not, when a
disagreement's value leaves its band, or when it starts to agree (update the reference). A
quick run (CI, ctest label regression) fails when a quick value leaves its quick band; the runs
marked gate_full (seconds in full) run in full in quick mode too and are judged as in a full
run, so that CI fails when a published number that agreed stops agreeing.

Exit status: 0 when every run completed, every quantity was extracted and the gate passed
(disagreement is a result, reported with its reason, when it is the expected one); 1 when a
run failed, a quantity could not be computed or the gate failed; 2 for bad arguments or a
malformed reference.toml.
"""

import argparse
import csv
import datetime
import math
import os
import platform
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)
CASES = os.path.join(SOURCE, "cases")


class Run:
    """One `fluidem run` of a shipped case: full and quick overrides (--set key=value)."""

    def __init__(self, name, case, full=(), quick=(), analyse=(), plot=True, post=(),
                 long=False, gate_full=False):
        self.name = name
        # seconds in full: --quick runs it in full, judged against the paper (the gate)
        self.gate_full = gate_full
        self.long = long  # hours of wall time: run only with --long, never in --quick
        self.post = list(post)  # a script of the case folder run on OUT: [script, args...]
        self.case = case
        self.full = list(full)
        self.quick = list(quick)
        self.analyse = list(analyse)
        self.plot = plot


class Quantity:
    """A compared quantity: its reference (a [[quantity]] of cases/<folder>/reference.toml:
    source, published value, unit, criterion, note) and how fluidem's value is read from the
    runs' outputs (VALUES[id]: the runs it needs and value(outputs) -> float)."""

    def __init__(self, ref, runs, value):
        self.id = ref["id"]
        self.case = ref["case"]
        self.paper = ref["source"]
        self.quantity = ref["quantity"]
        self.published = ref["published"]
        self.reference = ref.get("value")  # the published number, where there is one
        self.unit = ref["unit"]
        self.format = ref["format"]
        self.kind = ref["criterion"]["kind"]
        self.params = ref["criterion"]
        self.criterion = ref["criterion"]["text"]
        self.note = ref.get("note", "")
        e = ref["expect"]
        self.status = e["status"]
        self.band = e.get("band")
        self.quick_band = e.get("quick")
        self.labels = ref.get("labels")
        self.tried = ref.get("tried", "")
        self.runs = list(runs)
        self.value = value

    def agrees(self, v):
        """True or False by the criterion; None when there is nothing to compare."""
        return CRITERIA[self.kind][1](v, self.reference, self.params)

    def gate(self, v, quick_value):
        """None when `v` is what the reference expects, else why not. quick_value: v comes
        from a quick variant (judged by the quick band)."""
        if quick_value:
            if self.quick_band is None:
                return "no quick band recorded ([quantity.expect] quick)"
            lo, hi = self.quick_band
            if not lo <= v <= hi:
                return f"quick value {self.show(v)} outside its recorded band [{lo:g}, {hi:g}]"
            return None
        ok = self.agrees(v)
        if self.status == "agrees" and ok is not True:
            return f"{self.show(v)} no longer agrees ({self.criterion})"
        if self.status == "disagrees":
            if ok is True:
                return (f"{self.show(v)} now agrees ({self.criterion}): update the reference's "
                        "expect.status and note")
            lo, hi = self.band
            if not lo <= v <= hi:
                return f"{self.show(v)} outside its recorded band [{lo:g}, {hi:g}]"
        return None

    def show(self, v):
        """fluidem's value as the report shows it: the reference's format, then the unit (a
        category: its label)."""
        if self.labels is not None and float(v).is_integer() and 0 <= v < len(self.labels):
            return self.labels[int(v)]
        return format(v, self.format) + (" " + self.unit if self.unit else "")


class NotRun:
    """A seed case the report lists but cannot run (yet), with the reason: a [[not_run]] of
    cases/<folder>/reference.toml."""

    def __init__(self, ref):
        self.case = ref["case"]
        self.paper = ref["source"]
        self.quantity = ref["quantity"]
        self.published = ref["published"]
        self.reason = ref["reason"]


class Outputs:
    """The output directories of the runs, and readers of their files."""

    def __init__(self, work):
        self.work = work
        self.elsewhere = {}  # run: its folder outside WORK (a run taken from the archive)

    def dir(self, run):
        return self.elsewhere.get(run, os.path.join(self.work, run))

    def summary(self, run, name):
        path = os.path.join(self.dir(run), "analysis", "summary.csv")
        with open(path) as f:
            for row in csv.DictReader(f):
                if row["name"] == name:
                    return float(row["value"])
        raise KeyError(f"{path} has no row '{name}'")

    def series(self, run, name="series.csv"):
        """The columns of a CSV of the run (header line, then numbers); rows of another length
        (the last line of a run cut short) are left out."""
        path = os.path.join(self.dir(run), name)
        with open(path) as f:
            rows = list(csv.reader(f))
        cols = {h: [] for h in rows[0]}
        for r in rows[1:]:
            if len(r) != len(rows[0]):
                continue
            for h, v in zip(rows[0], r):
                cols[h].append(float(v))
        return cols

    def window_mean(self, run, column, t0, t1, name="series.csv"):
        """Mean of a column of series.csv (or another CSV of the run) over [t0, t1]."""
        s = self.series(run, name)
        v = [x for t, x in zip(s["time"], s[column]) if t0 - 1e-12 <= t <= t1 + 1e-12]
        if not v:
            raise ValueError(f"{run}: no row of {name} in [{t0}, {t1}] s")
        return sum(v) / len(v)

    def csv_at(self, run, name, key, at, column):
        """`column` of the row of OUT/name whose `key` is nearest to `at`."""
        s = self.series(run, name)
        k = min(range(len(s[key])), key=lambda i: abs(s[key][i] - at))
        return s[column][k]

    def bubble_fraction(self, run):
        """Mean over the frames of the analysis window of the bubbles' share of the bed
        (`fluidem analyse`, docs/analysis.md "Bubbles": connected regions of porosity > 0.8
        enclosed by the bed; the freeboard and the dilute surface of an expanded bed are not
        bubbles): 0 for a bed without bubbles."""
        return self.summary(run, "bubble_fraction_mean")

    def orifice_bubble_frames(self, run, x_orifice, reach):
        """Share of the frames of the analysis window holding a bubble that stands on the
        orifice: its lowest cell on the distributor (z_bottom 0) and its centroid within `reach`
        (m) of the orifice's centre x_orifice (analysis/bubbles.csv)."""
        t0 = self.summary(run, "window_start")
        t1 = self.summary(run, "window_end")
        s = self.series(run, os.path.join("analysis", "bubble_frames.csv"))
        frames = [t for t in s["time"] if t0 - 1e-12 <= t <= t1 + 1e-12]
        if not frames:
            raise ValueError(f"{run}: no frame of bubble_frames.csv in [{t0}, {t1}] s")
        b = self.series(run, os.path.join("analysis", "bubbles.csv"))
        on = {t for t, zb, x in zip(b["time"], b["z_bottom"], b["x"])
              if t0 - 1e-12 <= t <= t1 + 1e-12 and zb <= 1e-12 and abs(x - x_orifice) <= reach}
        return len(on) / len(frames)

    def collisions_between(self, run, t0, t1):
        """Hard-sphere collisions in [t0, t1] s: the growth of series.csv n_collisions (the
        row nearest each end). A run that ends before t1 (a quick variant) counts its whole
        length."""
        s = self.series(run)
        at = lambda t: s["n_collisions"][min(range(len(s["time"])),
                                              key=lambda i: abs(s["time"][i] - t))]
        if s["time"][-1] < t1 - 1e-9:
            t0, t1 = s["time"][0], s["time"][-1]
        return at(t1) - at(t0)

    def spout_regime(self, run, t0, x_axis, half_width=0.01, dz=0.02):
        """The regime of a spouted bed from its particles (particles.h5) over [t0, end] [Chang08
        §3.3]: 0 fixed, when the mean particle speed is below 0.01 m/s (no circulation); 2
        through-spout, when the particles within half_width of the nozzle's axis x_axis move up
        on average in every dz-high layer below the bed surface (bed height: twice the solids'
        centre-of-mass height); 1 internal circulation otherwise (particles move, but the axis
        does not carry them up through the whole bed: a cavity, a raceway). A run that ends
        before t0 (a quick variant) is judged over its last half."""
        import h5py
        import numpy as np

        with h5py.File(os.path.join(self.dir(run), "particles.h5"), "r") as f:
            times = f["/particles/all/position/time"][:]
            pos = f["/particles/all/position/value"]
            vel = f["/particles/all/velocity/value"]
            if times[-1] < t0:
                t0 = 0.5 * (times[0] + times[-1])
            frames = [k for k in range(len(times)) if times[k] >= t0 - 1e-12]
            speed, height = [], []
            layers = {}  # layer -> [sum vz, count]
            for k in frames:
                x, v = pos[k], vel[k]
                speed.append(float(np.linalg.norm(v, axis=1).mean()))
                height.append(2.0 * float(x[:, 2].mean()))
                on_axis = np.abs(x[:, 0] - x_axis) < half_width
                for layer, vz in zip((x[on_axis, 2] // dz).astype(int), v[on_axis, 2]):
                    e = layers.setdefault(int(layer), [0.0, 0])
                    e[0] += float(vz)
                    e[1] += 1
        if not frames:
            raise ValueError(f"{run}: no particle frame after {t0} s")
        if sum(speed) / len(speed) < 0.01:
            return 0
        h = sum(height) / len(height)
        below = [e[0] / e[1] for layer, e in layers.items() if (layer + 1) * dz <= h and e[1]]
        return 2 if below and min(below) > 0.0 else 1

    def jet_start(self, run):
        """Start of the pulsed inflow region of the run's gas bottom boundary, s."""
        import tomllib

        with open(os.path.join(self.dir(run), "case.resolved.toml"), "rb") as f:
            case = tomllib.load(f)
        regions = case["gas"]["boundary"]["bottom"].get("region", [])
        starts = [r["start"] for r in regions if r.get("mode") == "pulse"]
        if not starts:
            raise ValueError(f"{run}: no pulsed inflow region at the bottom boundary")
        return starts[0]

    def bubble_diameter_after(self, run, after):
        """Equivalent diameter of the largest bubble (analysis/bubble_frames.csv) in the frame
        nearest to `after` seconds after the jet starts, m."""
        return self.csv_at(run, os.path.join("analysis", "bubble_frames.csv"), "time",
                           self.jet_start(run) + after, "largest_diameter")


def ratio_text(a, b):
    return a / b if b != 0 else math.inf


# ---------------------------------------------------------------------------------------------
# The runs: the cases of the seeds (../shared/seeds) and their overrides. The published values
# they are compared with live beside the cases, in cases/<folder>/reference.toml.
# ---------------------------------------------------------------------------------------------

IDEAL = ["species[0].restitution=1.0", "species[0].friction=0.0", "walls.restitution=1.0",
         "walls.friction=0.0"]

RUNS = [
    Run("pouring_soft", "hoomans96/pouring_soft.toml",
        quick=["simulation.end_time=0.3"], analyse=["--from", "0"], gate_full=True),
    Run("pouring_hard", "hoomans96/pouring_hard.toml",
        full=["simulation.end_time=1.0"], quick=["simulation.end_time=0.3"],
        analyse=["--from", "0"]),
    Run("tsuji_setup", "hoomans96/tsuji_setup_umf.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "1.2"]),
    Run("bubble_orifice", "hoomans96/bubble_orifice_umf.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "1.2"]),
    Run("bubble_orifice_ideal", "hoomans96/bubble_orifice_umf.toml", full=IDEAL,
        quick=IDEAL + ["simulation.end_time=0.05"], analyse=["--from", "1.2"]),
    Run("slug_homogeneous", "hoomans96/slug_homogeneous_umf.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "1.5"]),
    Run("slug_homogeneous_ideal", "hoomans96/slug_homogeneous_umf.toml", full=IDEAL,
        quick=IDEAL + ["simulation.end_time=0.05"], analyse=["--from", "1.5"]),
    Run("binary_collision_d10", "chang08/binary_collision_d10.toml",
        quick=["simulation.end_time=0.5"], analyse=["--from", "10"]),
    Run("binary_collision_d7_5", "chang08/binary_collision_d7_5.toml",
        quick=["simulation.end_time=0.5"], analyse=["--from", "10"]),
    Run("binary_collision_d5", "chang08/binary_collision_d5.toml",
        quick=["simulation.end_time=0.5"], analyse=["--from", "10"]),
    # The binary-collision question asked of the soft-sphere DEM (E = 1e10 Pa, 15 s; the quick
    # variants at E = 1e8 Pa, 5x longer contacts and 6x fewer steps: CI's time).
    *[Run(f"binary_soft_d{d}", f"chang08/binary_collision_soft_d{d}.toml",
          quick=["simulation.end_time=0.3", "species[0].youngs_modulus=1e8"],
          analyse=["--from", "3"], plot=False) for d in ["5", "7_5", "10", "12"]],
    Run("spouted_1.6", "chang08/spouted_1.6.toml", quick=["simulation.end_time=0.05"],
        analyse=["--from", "1.0"]),
    Run("spouted_2.6", "chang08/spouted_2.6.toml", quick=["simulation.end_time=0.05"],
        analyse=["--from", "0.2", "--segment", "0.4"]),
    Run("spouted_4.0", "chang08/spouted_4.0.toml", quick=["simulation.end_time=0.05"],
        analyse=["--from", "1.0"]),
    Run("single_bubble_quick", "deen07/single_bubble_quick.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "0.02"], gate_full=True),
    Run("velocity_ideal_quick", "deen07/velocity_ideal_quick.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "0.5"]),
    Run("velocity_nonideal_quick", "deen07/velocity_nonideal_quick.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "0.5"]),
]

# --quick draws the pictures of these runs only (the plotting of every run was two thirds of the
# quick report's time in CI): that `fluidem plot` works on a hard-sphere and a soft-sphere coupled
# run is what CI needs to know.
QUICK_PLOTS = {"bubble_orifice", "spouted_2.6"}

# The full-size cases: hours each today (issue 7). `fluidem validate --long` runs them too.
RUNS += [
    Run("validation_40k", "hoomans96/validation_40k.toml", analyse=["--from", "0.5", "--to", "0.7"],
        long=True),
    Run("spouted_loop", "chang08/spouted_loop.toml", post=["chang08/loop_umf.py"], long=True),
    Run("single_bubble", "deen07/single_bubble.toml", analyse=["--from", "0.6"], long=True),
    Run("velocity_ideal", "deen07/velocity_ideal.toml", analyse=["--from", "1.0"], long=True),
    Run("velocity_nonideal", "deen07/velocity_nonideal.toml", analyse=["--from", "1.0"],
        long=True),
    # [Deen07 §6.2, Fig. 11]: 45,000 particles for 60 s, about a day each (cases/deen07/README.md)
    Run("segregation_beetstra", "deen07/segregation_beetstra.toml", long=True),
    Run("segregation_standard", "deen07/segregation_standard.toml", long=True),
]



# ---------------------------------------------------------------------------------------------
# How each compared quantity is read from the runs' outputs, keyed by the `id` of its entry in
# cases/<folder>/reference.toml (which holds the published value, unit, source, criterion and
# note). The order here is the order of the report's rows.
# ---------------------------------------------------------------------------------------------

def summary_of(run, name):
    return lambda o: o.summary(run, name)


def loop_summary(o, run, name):
    """A row of OUT/loop_summary.csv (name,value,unit) of cases/chang08/loop_umf.py."""
    with open(os.path.join(o.dir(run), "loop_summary.csv")) as f:
        for row in csv.DictReader(f):
            if row["name"] == name:
                return float(row["value"])
    raise KeyError(f"{run}: loop_summary.csv has no row '{name}'")


def kurtosis_farther(o, run):
    """3 plus the larger distance of the x and z velocity kurtoses from the Gaussian's 3."""
    return max(abs(o.summary(run, "velocity_kurtosis_x") - 3),
               abs(o.summary(run, "velocity_kurtosis_z") - 3)) + 3


def kurtosis_farthest(o, run):
    """The kurtosis of the x, y, z velocity fluctuations farthest from the Gaussian's 3."""
    k = [o.summary(run, f"velocity_kurtosis_{a}") for a in "xz"]
    return max(k, key=lambda v: abs(v - 3.0))


def kurtosis_local_farthest(o, run):
    """The kurtosis of the locally normalised x and z velocity fluctuations (each over its cell's
    rms) farther from the Gaussian's 3."""
    k = [o.summary(run, f"velocity_kurtosis_local_{a}") for a in "xz"]
    return max(k, key=lambda v: abs(v - 3.0))


def pressure_drop_before_jet(o, run, t0, t1):
    """Mean pressure drop over [t0, t1] s / the bed's weight per area."""
    return o.window_mean(run, "pressure_drop", t0, t1) / o.summary(run, "bed_weight_per_area")


def segregation_at_minute(o, run):
    """The degree of segregation s [Deen07 eq. 49] of analysis/segregation.csv (one row per
    frame) averaged over the frames of 59-60 s: "after 1 min" [Deen07 §6.2], over the last
    second (5 frames at 0.25 s) against the frame-to-frame scatter of a bubbling bed."""
    return o.window_mean(run, "s", 59.0, 60.0, os.path.join("analysis", "segregation.csv"))


def cube_cc(o, run, what):
    """The mean of the two collision centres CC1 and CC2."""
    return 0.5 * (o.summary(run, "CC1_" + what) + o.summary(run, "CC2_" + what))


VALUES = {  # id: (the runs it needs, value(outputs) -> float)
    # [Hoomans96]
    "pouring_soft.area_fraction": (["pouring_soft"],
                                   summary_of("pouring_soft", "area_fraction_last_frame")),
    "pouring_soft.energy_error": (["pouring_soft"],
                                  summary_of("pouring_soft", "energy_balance_error")),
    "pouring_hard.area_fraction": (["pouring_hard"],
                                   summary_of("pouring_hard", "area_fraction_last_frame")),
    "pouring_hard.energy_error": (["pouring_hard"],
                                  summary_of("pouring_hard", "energy_balance_error")),
    "tsuji_setup.bubble_fraction": (["tsuji_setup"],
                                    lambda o: o.bubble_fraction("tsuji_setup")),
    "bubble_orifice.bubble_fraction": (["bubble_orifice"],
                                       lambda o: o.bubble_fraction("bubble_orifice")),
    "bubble_orifice_ideal.bubble_fraction": (["bubble_orifice_ideal"],
                                             lambda o: o.bubble_fraction("bubble_orifice_ideal")),
    # The orifice of the Tsuji bed: x = 70-80 mm; within two cells (20 mm) of its centre.
    "tsuji_setup.orifice_bubble": (["tsuji_setup"],
                                   lambda o: o.orifice_bubble_frames("tsuji_setup", 0.075, 0.02)),
    "bubble_orifice.orifice_bubble": (
        ["bubble_orifice"], lambda o: o.orifice_bubble_frames("bubble_orifice", 0.075, 0.02)),
    "bubble_orifice.pressure_std_ratio": (
        ["bubble_orifice", "bubble_orifice_ideal"],
        lambda o: ratio_text(math.sqrt(o.summary("bubble_orifice", "pressure_variance_p_20cm")),
                             math.sqrt(o.summary("bubble_orifice_ideal",
                                                 "pressure_variance_p_20cm")))),
    "slug_homogeneous.pressure_drop_std_ratio": (
        ["slug_homogeneous", "slug_homogeneous_ideal"],
        lambda o: ratio_text(o.summary("slug_homogeneous", "pressure_drop_std_over_weight"),
                             o.summary("slug_homogeneous_ideal",
                                       "pressure_drop_std_over_weight"))),
    "slug_homogeneous.pressure_drop": (["slug_homogeneous"],
                                       summary_of("slug_homogeneous",
                                                  "pressure_drop_over_weight")),
    # [Hoomans96 §5.3.2]: "during the transient", the 2 s of uniform inflow here
    # (switched on at 1.0 s in slug_homogeneous_umf.toml)
    "slug_homogeneous.collisions": (
        ["slug_homogeneous"], lambda o: o.collisions_between("slug_homogeneous", 1.0, 3.0)),
    "slug_homogeneous_ideal.collisions": (
        ["slug_homogeneous_ideal"],
        lambda o: o.collisions_between("slug_homogeneous_ideal", 1.0, 3.0)),
    # [Chang08]
    # The regimes at 1.6, 2.6 and 4.0 m/s [Chang08 §3.3]: the nozzle's axis is x = 75 mm; the
    # particles over the second half of the 2 s runs.
    "spouted_1.6.regime": (["spouted_1.6"], lambda o: o.spout_regime("spouted_1.6", 1.0, 0.075)),
    "spouted_1.6.pressure_steady": (
        ["spouted_1.6"],
        lambda o: o.summary("spouted_1.6", "pressure_drop_std")
        / o.summary("spouted_1.6", "pressure_drop_mean")),
    "spouted_2.6.regime": (["spouted_2.6"], lambda o: o.spout_regime("spouted_2.6", 1.0, 0.075)),
    "spouted_2.6.pressure_drop": (["spouted_2.6"],
                                  summary_of("spouted_2.6", "pressure_drop_over_weight")),
    "spouted_4.0.regime": (["spouted_4.0"], lambda o: o.spout_regime("spouted_4.0", 1.0, 0.075)),
    "spouted_4.0.pressure_drop": (["spouted_4.0"],
                                  summary_of("spouted_4.0", "pressure_drop_over_weight")),
    "spouted_2.6.dominant_frequency": (["spouted_2.6"],
                                       summary_of("spouted_2.6", "dominant_frequency_p_200mm")),
    # [Deen07], reduced cases
    "single_bubble_quick.bed_height": (
        ["single_bubble_quick"],
        lambda o: o.window_mean("single_bubble_quick", "bed_height", 0.005, 0.02)),
    "single_bubble_quick.pressure_drop": (
        ["single_bubble_quick"],
        lambda o: pressure_drop_before_jet(o, "single_bubble_quick", 0.005, 0.02)),
    "single_bubble_quick.bubble_diameter": (
        ["single_bubble_quick"],
        lambda o: o.bubble_diameter_after("single_bubble_quick", 0.1)),
    "velocity_ideal_quick.kurtosis": (["velocity_ideal_quick"],
                                      lambda o: kurtosis_farther(o, "velocity_ideal_quick")),
    "velocity_nonideal_quick.kurtosis": (["velocity_nonideal_quick"],
                                         lambda o: kurtosis_farther(o,
                                                                    "velocity_nonideal_quick")),
    "velocity_ideal_quick.kurtosis_local": (
        ["velocity_ideal_quick"], lambda o: kurtosis_local_farthest(o, "velocity_ideal_quick")),
    "velocity_nonideal_quick.kurtosis_local": (
        ["velocity_nonideal_quick"],
        lambda o: kurtosis_local_farthest(o, "velocity_nonideal_quick")),
    "velocity_ideal_quick.anisotropy": (["velocity_ideal_quick"],
                                        summary_of("velocity_ideal_quick", "anisotropy")),
    "velocity_nonideal_quick.anisotropy": (["velocity_nonideal_quick"],
                                           summary_of("velocity_nonideal_quick", "anisotropy")),
    # The full-size cases (`--long`)
    "validation_40k.bubble_fraction": (["validation_40k"],
                                       lambda o: o.bubble_fraction("validation_40k")),
    "spouted_loop.u_mf_crossing": (["spouted_loop"],
                                   lambda o: loop_summary(o, "spouted_loop", "u_mf_C")),
    "spouted_loop.u_mf_ergun": (["spouted_loop"],
                                lambda o: loop_summary(o, "spouted_loop", "u_mf_ergun")),
    "single_bubble.bed_height": (
        ["single_bubble"], lambda o: o.window_mean("single_bubble", "bed_height", 0.5, 0.6)),
    "single_bubble.pressure_drop": (
        ["single_bubble"], lambda o: pressure_drop_before_jet(o, "single_bubble", 0.5, 0.6)),
    "single_bubble.bubble_diameter": (
        ["single_bubble"],
        lambda o: o.bubble_diameter_after("single_bubble", 0.1)),
    "velocity_ideal.kurtosis": (["velocity_ideal"],
                                lambda o: kurtosis_farthest(o, "velocity_ideal")),
    "velocity_nonideal.kurtosis": (["velocity_nonideal"],
                                   lambda o: kurtosis_farthest(o, "velocity_nonideal")),
    "velocity_ideal.kurtosis_local": (["velocity_ideal"],
                                      lambda o: kurtosis_local_farthest(o, "velocity_ideal")),
    "velocity_nonideal.kurtosis_local": (
        ["velocity_nonideal"], lambda o: kurtosis_local_farthest(o, "velocity_nonideal")),
    "velocity_nonideal.anisotropy_ratio": (
        ["velocity_ideal", "velocity_nonideal"],
        lambda o: o.summary("velocity_nonideal", "anisotropy")
        / o.summary("velocity_ideal", "anisotropy")),
    "segregation_beetstra.s_minute": (["segregation_beetstra"],
                                      lambda o: segregation_at_minute(o, "segregation_beetstra")),
    "segregation_beetstra.s_minute_experiment": (
        ["segregation_beetstra"], lambda o: segregation_at_minute(o, "segregation_beetstra")),
    "segregation_standard.s_minute": (["segregation_standard"],
                                      lambda o: segregation_at_minute(o, "segregation_standard")),
}

# [Chang08 binary-collision paper, Table 1]: the whole cube, the granular centre GC (a sphere of
# radius 0.1 L) and the collision centres CC1, CC2 (their mean), for each particle size.
for _d in ["10", "7_5", "5"]:
    _run = f"binary_collision_d{_d}"
    VALUES.update({
        f"{_run}.collision_frequency": ([_run], summary_of(_run, "collision_frequency")),
        f"{_run}.collision_frequency_gc": ([_run], summary_of(_run, "GC_collision_frequency")),
        f"{_run}.collision_frequency_cc": (
            [_run], lambda o, run=_run: cube_cc(o, run, "collision_frequency")),
        f"{_run}.void_fraction_gc": ([_run], summary_of(_run, "GC_void_fraction")),
        f"{_run}.void_fraction_cc": ([_run], lambda o, run=_run: cube_cc(o, run, "void_fraction")),
    })


# The binary-collision question with soft spheres: the runs' points (void fraction, share of
# multiple collisions) for the whole cube and the regions GC, CC1, CC2; the cube's own void
# fraction follows from the diameter (512 spheres in 1 litre).
BINARY_SOFT = {"5": 0.005, "7_5": 0.0075, "10": 0.010, "12": 0.012}
BINARY_SHARE = 0.05  # "negligible": fewer than 5 % of the collisions multiple
BINARY_MIN_ENDED = 30  # a region's share from fewer collisions is left out


def binary_points(o):
    pts = []
    for d, dia in BINARY_SOFT.items():
        run = f"binary_soft_d{d}"
        for p in ["", "GC_", "CC1_", "CC2_"]:
            ended = o.summary(run, p + "ended_collisions")
            if ended < BINARY_MIN_ENDED:
                continue
            eps = (o.summary(run, p + "void_fraction") if p
                   else 1.0 - 512 * math.pi / 6 * dia ** 3 / 1e-3)
            pts.append((eps, o.summary(run, p + "multiple_collision_fraction")))
    return pts


def binary_void_fraction(o):
    """The void fraction above which fewer than BINARY_SHARE of the collisions are multiple:
    the largest void fraction of a point at or above that share; when no point reaches it, the
    lowest void fraction the runs reached (the assumption holds at least down to there)."""
    pts = binary_points(o)
    failing = [eps for eps, share in pts if share >= BINARY_SHARE]
    return max(failing) if failing else min(eps for eps, _ in pts)


# Pictures drawn from several runs: (file name, title, runs, script of the source tree, its
# arguments); the report draws them when all the runs are there.
STUDY_PICTURES = [
    ("binary_soft_study", "binary_soft: the share of multiple collisions against the void "
     "fraction and against f t_c",
     [f"binary_soft_d{d}" for d in BINARY_SOFT], "tools/chang08_binary_study.py",
     ["--from", "3"]),
]

VALUES["binary_soft.void_fraction_binary"] = (
    [f"binary_soft_d{d}" for d in BINARY_SOFT], binary_void_fraction)
VALUES["binary_soft.multiple_share_densest"] = (
    [f"binary_soft_d{d}" for d in BINARY_SOFT],
    lambda o: min(binary_points(o))[1])


# ---------------------------------------------------------------------------------------------
# The criterion kinds; their parameters come from the reference files. kind: (parameters,
# agrees(v, published value, criterion) -> True, False or None).
# ---------------------------------------------------------------------------------------------

CRITERIA = {
    "within_abs": (["tolerance"], lambda v, ref, c: abs(v - ref) <= c["tolerance"]),
    "within_rel": (["tolerance"], lambda v, ref, c: abs(v / ref - 1) <= c["tolerance"]),
    "above": (["bound"], lambda v, ref, c: v > c["bound"]),
    "at_least": (["bound"], lambda v, ref, c: v >= c["bound"]),
    "below": (["bound"], lambda v, ref, c: v < c["bound"]),
    "between": (["lower", "upper"], lambda v, ref, c: c["lower"] <= v <= c["upper"]),
    "none": ([], lambda v, ref, c: None),
}
NEEDS_VALUE = {"within_abs", "within_rel"}  # compared with the entry's published `value`


class ReferenceError(Exception):
    """A reference.toml that cannot be read or does not match VALUES / CRITERIA."""


def _is_number(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _is_text(x):
    return isinstance(x, str)


def _numbers(x):
    return _is_number(x) or (isinstance(x, list) and x != [] and all(map(_is_number, x)))


def _texts(x):
    return _is_text(x) or (isinstance(x, list) and x != [] and all(map(_is_text, x)))


def _format_spec(x):
    if not _is_text(x):
        return False
    try:
        format(1.0, x)
    except ValueError:
        return False
    return True


# key: (required, check, what it must be)
QUANTITY_KEYS = {
    "id": (True, _is_text, "a string"),
    "case": (True, _is_text, "a string"),
    "source": (True, _is_text, "a string"),
    "quantity": (True, _is_text, "a string"),
    "published": (True, _is_text, "a string"),
    "value": (False, _is_number, "a number"),
    "spread": (False, _is_number, "a number"),
    "unit": (True, _is_text, "a string (\"\" for none)"),
    "format": (True, _format_spec, "a Python format spec such as \".3f\""),
    "note": (False, _is_text, "a string"),
    # expect.status "disagrees": what was tried to find the cause, and what that rules out
    "tried": (False, _is_text, "a string"),
    "criterion": (True, lambda x: isinstance(x, dict), "a table"),
    "expect": (True, lambda x: isinstance(x, dict), "a table ([quantity.expect])"),
    # a category, not a number: fluidem's value is an index into labels, shown as the label
    "labels": (False, lambda x: _texts(x) and isinstance(x, list), "a list of strings"),
    # where `fluidem plot OUT1 OUT2 ...` draws the published value: on the curve of
    # analysis/<curve>.csv at the simulated time at_time (fluidem_analysis_plot.py --compare)
    "curve": (False, _is_text, "a string (an analysis CSV without .csv, e.g. \"segregation\")"),
    "at_time": (False, _is_number, "a number (s)"),
}
NOT_RUN_KEYS = {
    "case": (True, _is_text, "a string"),
    "source": (True, _is_text, "a string"),
    "quantity": (True, _is_text, "a string"),
    "published": (True, _is_text, "a string"),
    "value": (False, _numbers, "a number or a list of numbers"),
    "unit": (False, _texts, "a string or a list of strings"),
    "reason": (True, _is_text, "a string"),
}


def _check_keys(entry, keys, where):
    for k in entry:
        if k not in keys:
            raise ReferenceError(f"{where}: unknown key '{k}' (known: {', '.join(keys)})")
    for k, (required, ok, what) in keys.items():
        if k not in entry:
            if required:
                raise ReferenceError(f"{where}: missing key '{k}'")
        elif not ok(entry[k]):
            raise ReferenceError(f"{where}: key '{k}' must be {what}, not {entry[k]!r}")


STATUSES = ("agrees", "disagrees", "no_criterion", "not_established")


def _band(x):
    return isinstance(x, list) and len(x) == 2 and all(map(_is_number, x)) and x[0] <= x[1]


def _check_expect(entry, where):
    e = entry["expect"]
    where = f"{where}, expect"
    _check_keys(e, {"status": (True, lambda x: x in STATUSES, "one of " + ", ".join(STATUSES)),
                    "band": (False, _band, "[lo, hi] with lo <= hi"),
                    "quick": (False, _band, "[lo, hi] with lo <= hi")}, where)
    if e["status"] == "disagrees" and "band" not in e:
        raise ReferenceError(f"{where}: status 'disagrees' needs key 'band' (the range the "
                             "full run's value is recorded in)")
    if e["status"] == "disagrees" and not entry.get("note"):
        raise ReferenceError(f"{where}: status 'disagrees' needs the quantity's 'note' (why)")
    if e["status"] == "disagrees" and not entry.get("tried"):
        raise ReferenceError(f"{where}: status 'disagrees' needs the quantity's 'tried' (what was "
                             "tried to find the cause, and what it rules out)")
    if (e["status"] == "no_criterion") != (entry["criterion"]["kind"] == "none"):
        raise ReferenceError(f"{where}: status 'no_criterion' goes with criterion kind 'none'")


def _check_criterion(entry, where):
    c = entry["criterion"]
    where = f"{where}, criterion"
    kind = c.get("kind")
    if kind is None:
        raise ReferenceError(f"{where}: missing key 'kind'")
    if kind not in CRITERIA:
        raise ReferenceError(f"{where}: key 'kind' is {kind!r}: must be one of "
                             + ", ".join(CRITERIA))
    params = CRITERIA[kind][0]
    keys = {"kind": (True, _is_text, "a string"),
            "text": (True, _is_text, "a string (the report's criterion column)")}
    keys.update({p: (True, _is_number, "a number") for p in params})
    _check_keys(c, keys, f"{where} '{kind}'")
    if kind in NEEDS_VALUE and "value" not in entry:
        raise ReferenceError(f"{where} '{kind}': missing key 'value' of the quantity (the "
                             "published number it compares with)")
    if kind == "within_rel" and entry["value"] == 0:
        raise ReferenceError(f"{where} 'within_rel': key 'value' is 0")


def load_toml(path):
    try:
        import tomllib  # Python 3.11+
    except ImportError:
        import tomli as tomllib  # the same reader for older Pythons (pip/Debian python3-tomli)
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except OSError as e:
        raise ReferenceError(f"{path}: cannot be read ({e.strerror})") from e
    except tomllib.TOMLDecodeError as e:
        raise ReferenceError(f"{path}: not valid TOML: {e}") from e


def load_references(runs, values, cases=None):
    """The Quantity rows (in the order of `values`) and NotRun rows (in the order of the case
    folders in `runs`) from cases/<folder>/reference.toml of every case folder of `runs`.
    Raises ReferenceError, naming the file and the key, for a malformed file, an id without an
    entry of `values` or an entry of `values` without a reference."""
    cases = cases or CASES
    folders = []
    for r in runs:
        folder = r.case.split("/")[0]
        if folder not in folders:
            folders.append(folder)
    refs = {}  # id -> (entry, path)
    not_run = []
    for folder in folders:
        path = os.path.join(cases, folder, "reference.toml")
        data = load_toml(path)
        for k in data:
            if k not in ("quantity", "not_run"):
                raise ReferenceError(f"{path}: unknown key '{k}' (known: [[quantity]], "
                                     "[[not_run]])")
        for key in ("quantity", "not_run"):
            if key in data and not (isinstance(data[key], list)
                                    and all(isinstance(e, dict) for e in data[key])):
                raise ReferenceError(f"{path}: '{key}' must be an array of tables ([[{key}]])")
        for i, e in enumerate(data.get("quantity", [])):
            where = f"{path}: [[quantity]] {i + 1}" + (f" (id '{e['id']}')" if _is_text(
                e.get("id")) else "")
            _check_keys(e, QUANTITY_KEYS, where)
            _check_criterion(e, where)
            _check_expect(e, where)
            if e["id"] in refs:
                raise ReferenceError(f"{where}: key 'id': '{e['id']}' also in {refs[e['id']][1]}")
            if e["id"] not in values:
                raise ReferenceError(f"{where}: key 'id': '{e['id']}' is not a quantity "
                                     "python/fluidem_validate.py knows how to read (VALUES)")
            refs[e["id"]] = (e, path)
        for i, e in enumerate(data.get("not_run", [])):
            _check_keys(e, NOT_RUN_KEYS, f"{path}: [[not_run]] {i + 1}")
            not_run.append(NotRun(e))
    missing = [q for q in values if q not in refs]
    if missing:
        raise ReferenceError("no [[quantity]] with id " + ", ".join(f"'{q}'" for q in missing)
                             + " in " + ", ".join(os.path.join(cases, f, "reference.toml")
                                                  for f in folders))
    return [Quantity(refs[q][0], *values[q]) for q in values], not_run


# ---------------------------------------------------------------------------------------------

def run_cmd(cmd, log, cwd=None):
    with open(log, "a") as f:
        f.write("$ " + " ".join(cmd) + "\n")
        f.flush()
        return subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, cwd=cwd).returncode


def done_command(path):
    """The command line of a run's record (WORK/<run>.done)."""
    with open(path) as f:
        return f.read().split("\n")[0]


def portable_command(words, cases, work):
    """A run's command line with the case folder and the work folder written as cases/ and
    WORK/ and without its --threads (the results do not depend on them; the record keeps
    them): the same run made in another checkout, work folder or thread count compares equal."""
    out = []
    words = list(words)
    if "--threads" in words:
        k = words.index("--threads")
        del words[k:k + 2]
    for w in words:
        for root, name in ((cases, "cases"), (work, "WORK")):
            if w == root or w.startswith(root + os.sep):
                w = name + w[len(root):]
        out.append(w)
    return " ".join(out)


# The files of a finished run kept in the archive: what the quantities and the report read,
# without the particle and field files (hundreds of MB) and the checkpoints.
ARCHIVED = (".csv", ".toml")
ARCHIVED_ANALYSIS = (".csv", ".png")


def copy_small_outputs(out, dst):
    """Copy a run's small outputs (ARCHIVED at the top, ARCHIVED_ANALYSIS of analysis/) from
    `out` into the new folder `dst`."""
    os.makedirs(os.path.join(dst, "analysis"))
    for f in sorted(os.listdir(out)):
        if f.endswith(ARCHIVED) and os.path.isfile(os.path.join(out, f)):
            shutil.copyfile(os.path.join(out, f), os.path.join(dst, f))
    adir = os.path.join(out, "analysis")
    for f in sorted(os.listdir(adir)) if os.path.isdir(adir) else []:
        if f.endswith(ARCHIVED_ANALYSIS):
            shutil.copyfile(os.path.join(adir, f), os.path.join(dst, "analysis", f))


def replace_folder(tmp, dst):
    """Put the complete folder `tmp` in the place of `dst` (renames; no half folder is left)."""
    old = dst + ".old"
    if os.path.exists(old):
        shutil.rmtree(old)
    if os.path.exists(dst):
        os.replace(dst, old)
    os.replace(tmp, dst)
    if os.path.exists(old):
        shutil.rmtree(old)


def time_rows(path):
    """A CSV file as (header line, [(time, line), ...]) when its first column is `time`, else
    None."""
    with open(path) as f:
        lines = f.read().splitlines()
    if not lines or lines[0].split(",")[0] != "time":
        return None
    rows = []
    for line in lines[1:]:
        try:
            rows.append((float(line.split(",")[0]), line))
        except ValueError:
            return None
    return lines[0], rows


def join_pieces(pieces, final):
    """Prepend to every time-series CSV of the folder `final` (at its top and in analysis/)
    the rows of the same file in each earlier piece's folder (in order), each piece's rows up
    to the first time of the piece after it: one file over the whole run, as if it had run in
    one piece. A file whose header differs from the final one's is left as the final piece
    wrote it."""
    for sub in ("", "analysis"):
        folder = os.path.join(final, sub)
        for f in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
            path = os.path.join(folder, f)
            if not f.endswith(".csv") or not os.path.isfile(path):
                continue
            last = time_rows(path)
            if last is None:
                continue
            header, rows = last
            parts = []
            for p in pieces:
                q = os.path.join(p, sub, f)
                got = time_rows(q) if os.path.isfile(q) else None
                if got is not None and got[0] == header:
                    parts.append(got[1])
            parts.append(rows)
            joined = []
            for k, part in enumerate(parts):
                nxt = next((pp[0][0] for pp in parts[k + 1:] if pp), None)
                joined += [line for t, line in part if nxt is None or t < nxt]
            with open(path, "w") as fh:
                fh.write("\n".join([header] + joined) + "\n")


# A long run stopped part-way and kept in the archive (park_run), to be continued elsewhere.
PARKED = ".parked"


def parked_pieces(parked):
    """The piece folders of a parked run, in order."""
    root = os.path.join(parked, "pieces")
    return [os.path.join(root, p) for p in sorted(os.listdir(root))] if os.path.isdir(root) else []


def archive_run(out, done, archive, name, cases, work):
    """Copy a finished long run's small outputs and record to ARCHIVE/<name> and
    ARCHIVE/<name>.done (the command line written with cases/ and WORK/), replacing an earlier
    copy only once the new one is complete (a temporary folder, then renames). The snapshot
    is drawn at the report's resolution (report_snapshot.png): particles.h5 stays behind.
    A run made in pieces on several machines (park_run) holds its last piece in `out` (the
    piece's number is the record's fifth line): the time series of the pieces before it are
    joined in front of its own (join_pieces), from ARCHIVE/<name>.parked, or when that is gone
    (the run archived before, then re-analysed) from the earlier archived copy. A parked copy
    of the same run is removed once the archive is complete."""
    os.makedirs(archive, exist_ok=True)
    dst = os.path.join(archive, name)
    tmp = dst + ".tmp"
    if os.path.exists(tmp):
        shutil.rmtree(tmp)
    with open(done) as f:
        lines = f.read().split("\n")
    lines[0] = portable_command(lines[0].split(" "), cases, work)
    piece = int(lines[4]) if len(lines) > 4 and lines[4].strip() else 1
    copy_small_outputs(out, tmp)
    parked = os.path.join(archive, name + PARKED)
    rec = read_started(os.path.join(parked, "record.started"))
    same_run = rec is not None and rec["cmd"] == lines[0]
    if piece > 1:
        if same_run:
            earlier = [p for p in parked_pieces(parked) if int(os.path.basename(p)) < piece]
        else:
            earlier = [dst] if os.path.isdir(dst) else []
        join_pieces(earlier, tmp)
    if os.path.exists(os.path.join(out, "particles.h5")):
        subprocess.run([sys.executable, os.path.join(HERE, "fluidem_plot.py"), out, "--out",
                        os.path.join(tmp, "report_snapshot.png"), "--dpi", "60"],
                       capture_output=True)
    with open(os.path.join(tmp, "record.done"), "w") as f:
        f.write("\n".join(lines))
    replace_folder(tmp, dst)
    os.replace(os.path.join(dst, "record.done"), dst + ".done")
    if same_run:
        shutil.rmtree(parked)


def park_run(out, started, archive, name, cases, work):
    """Keep a stopped long run in ARCHIVE/<name>.parked so that a fresh checkout on another
    machine continues it (`--resume`): its last checkpoint (checkpoint.h5), its record
    (record.started: the command line written with cases/ and WORK/, the wall time and commits
    of its pieces so far, threads, the piece's number) and the small outputs of each piece so
    far (pieces/001, 002, ...: the work folder of one machine holds one piece; parking the same
    piece again replaces its copy). Raises OSError when there is nothing to park."""
    rec = read_started(started)
    checkpoint = os.path.join(out, "checkpoint.h5")
    if rec is None or not os.path.isfile(checkpoint):
        raise OSError(f"no stopped run to park: {started} and {checkpoint} are needed")
    dst = os.path.join(archive, name + PARKED)
    tmp = dst + ".tmp"
    if os.path.exists(tmp):
        shutil.rmtree(tmp)
    os.makedirs(os.path.join(tmp, "pieces"))
    for p in parked_pieces(dst):
        if os.path.basename(p) != f"{rec['piece']:03d}":
            shutil.copytree(p, os.path.join(tmp, "pieces", os.path.basename(p)))
    copy_small_outputs(out, os.path.join(tmp, "pieces", f"{rec['piece']:03d}"))
    shutil.copyfile(checkpoint, os.path.join(tmp, "checkpoint.h5"))
    write_started(os.path.join(tmp, "record.started"),
                  portable_command(rec["cmd"].split(" "), cases, work), rec["wall"],
                  rec["commits"], rec["threads"], rec["piece"])
    os.makedirs(archive, exist_ok=True)
    replace_folder(tmp, dst)


def archived_run(archive, name, words, cases, work):
    """Whether ARCHIVE holds run `name` made with this command line (as portable_command)."""
    done = os.path.join(archive, name + ".done")
    return (os.path.exists(done) and os.path.isdir(os.path.join(archive, name))
            and done_command(done) == portable_command(words, cases, work))


def resumable_parked(archive, r, cmd, work):
    """ARCHIVE/<run>.parked when it holds a parked piece of this run (the same command line,
    as portable_command) and WORK has no checkpoint of it to continue, else None."""
    if not (r.long and archive):
        return None
    parked = os.path.join(archive, r.name + PARKED)
    rec = read_started(os.path.join(parked, "record.started"))
    if rec is None or not os.path.isfile(os.path.join(parked, "checkpoint.h5")):
        return None
    return parked if rec["cmd"] == portable_command(cmd[1:], CASES, work) else None


def run_pieces_cmd(cmd, log, record, every=60.0):
    """Run one piece of a run: `cmd` in its own session (a signal to validate's process group
    does not reach it twice), its output appended to `log`. SIGINT and SIGTERM to validate are
    passed on once (fluidem stops after its step and writes a checkpoint). record(seconds) is
    called every `every` s of wall time and at the end, so that a lost machine still leaves the
    wall time of the piece in WORK/<run>.started. Returns (exit code, wall time in s)."""
    with open(log, "a") as f:
        f.write("$ " + " ".join(cmd) + "\n")
        f.flush()
        t0 = time.time()
        record(0.0)
        p = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT, start_new_session=True)

        def forward(sig, _frame):
            p.send_signal(sig)

        old = {s: signal.signal(s, forward) for s in (signal.SIGINT, signal.SIGTERM)}
        try:
            while True:
                try:
                    code = p.wait(timeout=every)
                    break
                except subprocess.TimeoutExpired:
                    record(time.time() - t0)
        finally:
            for s, h in old.items():
                signal.signal(s, h)
        seconds = time.time() - t0
        record(seconds)
        return code, seconds


def write_started(path, cmd, wall, commits, threads, piece=1):
    """The record of a run that is not finished, WORK/<run>.started (written with a temporary
    file and a rename): its command line, the wall time of its pieces so far (s), the commits
    its pieces ran from (comma-separated), its threads and the number of the piece the work
    folder holds (1, or the next after the parked pieces it continued: park_run)."""
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(f"{cmd}\n{wall}\n{','.join(commits)}\n{threads}\n{piece}\n")
    os.replace(tmp, path)


def read_started(path):
    """WORK/<run>.started (write_started), or None when there is none or it is unreadable."""
    try:
        with open(path) as f:
            lines = f.read().split("\n")
        return {"cmd": lines[0], "wall": float(lines[1]), "commits": lines[2].split(","),
                "threads": lines[3],
                "piece": int(lines[4]) if len(lines) > 4 and lines[4] else 1}
    except (OSError, IndexError, ValueError):
        return None


def git_commit():
    """The source tree's commit, "+changes" when tracked files differ from it (the report's
    own folder, which writing the report changes, aside)."""
    try:
        out = subprocess.run(["git", "-C", SOURCE, "rev-parse", "--short", "HEAD"],
                             capture_output=True, text=True, check=True)
        changed = subprocess.run(["git", "-C", SOURCE, "status", "--porcelain",
                                  "--untracked-files=no", "--", ".", ":!docs/validation"],
                                 capture_output=True, text=True, check=True)
        return out.stdout.strip() + ("+changes" if changed.stdout.strip() else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def restart_cmd(a, checkpoint, out, piece, extra=()):
    """The command of a run's next piece (from `checkpoint` into `out`) and the commits of its
    pieces with the present one added."""
    run = [a.fluidem, "run", "--restart", checkpoint, "--out", out] + list(extra)
    if a.threads > 0:
        run += ["--threads", str(a.threads)]
    commits = piece["commits"]
    now = git_commit()
    if now not in commits:
        commits.append(now)
    return run, commits


def park_stopped(a, runs, work, archive):
    """--park: each long run of `runs` stopped in WORK (its .started record and checkpoint)
    analysed (`fluidem analyse`, so that the piece's per-frame tables are kept) and parked in
    the archive (park_run). Exit status 0, or 1 when there was nothing to park."""
    parked = 0
    for r in runs:
        out = os.path.join(work, r.name)
        started = os.path.join(work, r.name + ".started")
        if not (r.long and archive and os.path.isfile(started)):
            continue
        run_cmd([a.fluidem, "analyse", out] + list(r.analyse), os.path.join(work, r.name + ".log"))
        try:
            park_run(out, started, archive, r.name, CASES, work)
        except OSError as e:
            print(f"[{r.name}] not parked: {e}", file=sys.stderr, flush=True)
            continue
        rec = read_started(started)
        print(f"[{r.name}] parked in {os.path.join(archive, r.name + PARKED)} (piece "
              f"{rec['piece']}, {rec['wall']:.0f} s of wall time so far)", flush=True)
        parked += 1
    if parked == 0:
        print("error: no stopped full-size run to park in " + work, file=sys.stderr)
        return 1
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--fluidem", required=True, help="the fluidem binary")
    ap.add_argument("--quick", action="store_true", help="short runs (CI); numbers not comparable")
    ap.add_argument("--work", help="directory of the runs (default out/validation[-quick])")
    ap.add_argument("--report", help="report file (default docs/validation/README.md of the "
                    "source tree; WORK/README.md with --quick)")
    ap.add_argument("--cases", help="the case folders (default: cases/ of the source tree; a "
                    "copy with edited reference.toml files tests the gate)")
    ap.add_argument("--only", action="append", default=[],
                    help="only the runs whose name contains this text (repeatable)")
    ap.add_argument("--threads", type=int, default=0, help="threads per run (default: all)")
    ap.add_argument("--list", action="store_true", help="list the runs and quantities, run none")
    ap.add_argument("--long", action="store_true",
                    help="also the full-size cases (hours of wall time each today)")
    ap.add_argument("--report-only", action="store_true",
                    help="run nothing: write the report from the finished runs of WORK (those "
                    "not finished are listed as not run)")
    ap.add_argument("--reuse", action="store_true",
                    help="keep the runs of WORK that completed with the same command line "
                    "(WORK/<run>.done) instead of running them again")
    ap.add_argument("--resume", action="store_true",
                    help="continue the runs of WORK that were stopped (Ctrl-C, SIGTERM, a lost "
                    "machine) from their last checkpoint, when their record WORK/<run>.started "
                    "has the same command line; the wall times of the pieces add up. Implies "
                    "--reuse")
    ap.add_argument("--archive",
                    help="folder of the finished full-size (--long) runs' small outputs: "
                    "their CSV files, analysis tables and pictures and their record, without "
                    "the HDF5 files (default docs/validation/runs of the source tree; not "
                    "with --quick). A long run that finishes is copied there; with --reuse or "
                    "--report-only, a long run not finished in WORK is taken from there, so "
                    "that the report can be made at a later commit, on another machine, from "
                    "runs of days")
    ap.add_argument("--park", action="store_true",
                    help="run nothing: keep each stopped full-size run of WORK (Ctrl-C, "
                    "SIGTERM) in the archive, its checkpoint and its small outputs so far "
                    "(ARCHIVE/<run>.parked), so that --resume continues it in a fresh checkout "
                    "on another machine (the pieces' series are joined when it finishes)")
    a = ap.parse_args()
    a.reuse = a.reuse or a.resume
    global CASES
    if a.cases:
        CASES = os.path.abspath(a.cases)

    try:
        all_quantities, not_run = load_references(RUNS, VALUES)
    except ReferenceError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    chosen = [r for r in RUNS if not a.only or any(t in r.name for t in a.only)]
    # The hours-long cases run only with --long (never in --quick); their rows say so.
    runs = [r for r in chosen if not r.long or (a.long and not a.quick)]
    long_left = {r.name for r in chosen if r not in runs}
    names = {r.name for r in chosen}
    quantities = [q for q in all_quantities if all(r in names for r in q.runs)]
    if a.list:
        for r in chosen:
            kind = "long-run" if r.name in long_left else "run"
            print(f"{kind} {r.name:<24} {r.case} {' '.join(r.quick if a.quick else r.full)}")
        for q in quantities:
            kind = "long-quantity" if any(n in long_left for n in q.runs) else "quantity"
            print(f"{kind} {q.paper} {q.quantity}: published {q.published}")
        return 0
    if not runs:
        print(f"error: no run matches --only {a.only}; runs: "
              + ", ".join(r.name for r in RUNS), file=sys.stderr)
        return 2
    if not os.access(a.fluidem, os.X_OK):
        print(f"error: --fluidem {a.fluidem} is not an executable", file=sys.stderr)
        return 2

    work = os.path.abspath(a.work or os.path.join("out", "validation-quick" if a.quick
                                                 else "validation"))
    report = os.path.abspath(a.report or (os.path.join(work, "README.md") if a.quick else
                                          os.path.join(SOURCE, "docs", "validation",
                                                       "README.md")))
    os.makedirs(work, exist_ok=True)
    os.makedirs(os.path.dirname(report), exist_ok=True)
    archive = None if a.quick else os.path.abspath(
        a.archive or os.path.join(SOURCE, "docs", "validation", "runs"))
    if a.park:
        return park_stopped(a, runs, work, archive)
    outputs = Outputs(work)
    failed = []
    skipped = []  # --report-only: runs not finished in WORK
    wall = {}
    made = {}  # run: (the commit of the source tree it ran from, threads)
    for r in runs:
        out = outputs.dir(r.name)
        log = os.path.join(work, r.name + ".log")
        cmd = [a.fluidem, "run", os.path.join(CASES, r.case), "--out", out, "--force"]
        in_full = not a.quick or r.gate_full
        for s in (r.full if in_full else r.quick):
            cmd += ["--set", s]
        if a.threads > 0:
            cmd += ["--threads", str(a.threads)]
        done = os.path.join(work, r.name + ".done")
        finished = os.path.exists(done) and (
            a.report_only or done_command(done) == " ".join(cmd[1:]))
        archived = (r.long and archive and not finished and (a.reuse or a.report_only)
                    and archived_run(archive, r.name, cmd[1:], CASES, work))
        if archived:
            # A full-size run made earlier (another commit, another machine): its record and
            # small outputs, kept in the archive.
            outputs.elsewhere[r.name] = os.path.join(archive, r.name)
            wall[r.name], made[r.name] = read_done(os.path.join(archive, r.name + ".done"))
            print(f"[{r.name}] taken from the archive ({archive})", flush=True)
            continue
        if a.report_only:
            if finished:
                wall[r.name], made[r.name] = read_done(done)
            else:
                skipped.append(r.name)
            continue
        reused = False
        if a.reuse and finished:
            wall[r.name], made[r.name] = read_done(done)
            reused = True
            print(f"[{r.name}] run reused ({done})", flush=True)
        if not reused:
            started = os.path.join(work, r.name + ".started")
            checkpoint = os.path.join(out, "checkpoint.h5")
            piece = read_started(started) if a.resume and os.path.exists(checkpoint) else None
            if piece and piece["cmd"] == " ".join(cmd[1:]):
                # The next piece: the run continues from its checkpoint, appending to its
                # outputs (a restart is bitwise: the same result as one piece).
                print(f"[{r.name}] continuing {r.case} from {checkpoint} ({piece['wall']:.0f} s "
                      "of wall time before) ...", flush=True)
                run, commits = restart_cmd(a, checkpoint, out, piece)
            elif a.resume and (parked := resumable_parked(archive, r, cmd, work)):
                # A run parked by another machine (park_run): the next piece starts from its
                # checkpoint in new output files here; the archive joins the pieces at the end.
                for old in (done, started):
                    if os.path.exists(old):
                        os.remove(old)
                piece = read_started(os.path.join(parked, "record.started"))
                piece["piece"] += 1
                print(f"[{r.name}] continuing {r.case} from the parked {parked} (piece "
                      f"{piece['piece']}, {piece['wall']:.0f} s of wall time before) ...",
                      flush=True)
                run, commits = restart_cmd(a, os.path.join(parked, "checkpoint.h5"), out, piece,
                                           ["--force"])
            else:
                for old in (done, log, started):
                    if os.path.exists(old):
                        os.remove(old)
                print(f"[{r.name}] running {r.case} ...", flush=True)
                run, piece, commits = cmd, {"wall": 0.0, "piece": 1}, [git_commit()]
            threads = str(a.threads) if a.threads > 0 else "all"

            def record(seconds, started=started, piece=piece, commits=commits, threads=threads):
                write_started(started, " ".join(cmd[1:]), piece["wall"] + seconds, commits,
                              threads, piece["piece"])

            code, seconds = run_pieces_cmd(run, log, record)
            wall[r.name] = piece["wall"] + seconds
            if code in (128 + signal.SIGINT, 128 + signal.SIGTERM):
                # Stopped: no report (it would list the runs not made as failed); the run
                # continues from its checkpoint with --resume.
                print(f"[{r.name}] stopped by a signal after {wall[r.name]:.0f} s of wall time "
                      f"in all: continue it with --resume (log {log})", file=sys.stderr,
                      flush=True)
                return code
            if code != 0:
                failed.append(f"{r.name}: fluidem run exited {code} (log {log})")
                print(f"[{r.name}] FAILED (exit {code}), log {log}", flush=True)
                continue
            os.remove(started)
            made[r.name] = (",".join(commits), threads)
        analyse = [a.fluidem, "analyse", out] + (r.analyse if in_full else ["--from", "0"])
        code = run_cmd(analyse, log)
        if code != 0:
            failed.append(f"{r.name}: fluidem analyse exited {code} (log {log})")
            continue
        if r.post:
            code = run_cmd([sys.executable, os.path.join(CASES, r.post[0])] + r.post[1:] + [out],
                           log)
            if code != 0:
                failed.append(f"{r.name}: {r.post[0]} exited {code} (log {log})")
        if r.plot and (not a.quick or r.name in QUICK_PLOTS):
            code = run_cmd([a.fluidem, "plot", out], log)
            if code != 0:
                failed.append(f"{r.name}: fluidem plot exited {code} (log {log})")
        if not reused:
            with open(done, "w") as f:
                f.write(" ".join(cmd[1:]) + "\n" + str(wall[r.name]) + "\n"
                        + "\n".join(made[r.name]) + f"\n{piece['piece']}\n")
        if r.long and archive:
            archive_run(out, done, archive, r.name, CASES, work)
            # The report reads what was archived (its snapshot drawn once, there).
            outputs.elsewhere[r.name] = os.path.join(archive, r.name)
            print(f"[{r.name}] archived in {outputs.dir(r.name)}", flush=True)
        print(f"[{r.name}] done ({wall[r.name]:.0f} s of wall time)", flush=True)

    rows = []
    gate_failed = []
    gate_full = {r.name: r.gate_full for r in runs}
    for q in quantities:
        if any(n in long_left for n in q.runs):
            rows.append((q, None, "not run: a full-size case (hours), run by `fluidem validate "
                         "--long`"))
            continue
        if any(n in skipped for n in q.runs):
            rows.append((q, None, "not run for this report"))
            continue
        if any(n in [f.split(":")[0] for f in failed] for n in q.runs):
            rows.append((q, None, "run failed"))
            continue
        try:
            v = q.value(outputs)
        except (OSError, KeyError, ValueError, ZeroDivisionError) as e:
            failed.append(f"{q.case}: {q.quantity}: {e}")
            rows.append((q, None, f"not computed: {e}"))
            continue
        if not math.isfinite(v):
            failed.append(f"{q.case}: {q.quantity}: not finite ({v})")
        rows.append((q, v, None))
        in_full = not a.quick or all(gate_full.get(n, False) for n in q.runs)
        why = q.gate(v, quick_value=not in_full)
        if why:
            gate_failed.append(f"{q.case}: {q.quantity}: {why}")
    failed += [f"gate: {g}" for g in gate_failed]

    write_report(report, a.quick, runs, rows, not_run, wall, failed, outputs, made)
    print(f"report: {report}")
    if failed:
        print("failures:\n  " + "\n  ".join(failed), file=sys.stderr)
        return 1
    return 0


def read_done(path):
    """A finished run's record WORK/<run>.done: its command line, wall time (s), the commit of
    the source tree it ran from and its threads (those two missing in older records: "-"),
    and the number of the piece its work folder holds (park_run; 1 when missing)."""
    with open(path) as f:
        lines = f.read().split("\n")
    made = tuple(lines[2:4]) if len(lines) > 3 and lines[3] else ("-", "-")
    return float(lines[1]), made


def write_report(path, quick, runs, rows, not_run, wall, failed, outputs, made=None):
    made = made or {}
    pics = os.path.join(os.path.dirname(path), "pictures")
    os.makedirs(pics, exist_ok=True)
    for old in os.listdir(pics):  # the pictures of an earlier report
        if old.endswith(".png"):
            os.remove(os.path.join(pics, old))
    lines = []
    w = lines.append
    w("# fluidem against the seeds' published results" + (" (QUICK RUNS)" if quick else ""))
    w("")
    w(f"Generated by `fluidem validate{' --quick' if quick else ''}` "
      f"(python/fluidem_validate.py) on {datetime.date.today().isoformat()}, commit "
      f"{git_commit()}, {cpu_model()}, {os.cpu_count()} cores.")
    w("")
    if quick:
        w("**Quick mode**: the runs are cut short (a few hundredths of a second of bed, analysed "
          "from t = 0), so their values are NOT comparable with the papers (n/a (quick)): they "
          "are checked against the bands recorded for them (a regression gate). The runs that "
          "take seconds in full (" + ", ".join(r.name for r in runs if r.gate_full) + ") run "
          "in full and are judged against the papers. The full report is "
          "docs/validation/README.md.")
        w("")
    w("Agreement: **yes** when fluidem's value meets the criterion, **no** when it does not "
      "(the note says why, as far as we know), n/a when the quantity could not be computed.")
    w("")
    w("The gate: every quantity's reference.toml entry records what is expected of it "
      "([quantity.expect]): that it agrees, or that it disagrees, for the reason in its note, "
      "with its value in a recorded band. The report fails (exit status 1, the failures listed "
      "at its end) when a value leaves what is expected. CI (`fluidem validate --quick`, ctest "
      "label regression) runs the same gate: the runs that take seconds in full, judged against "
      "the papers, and the short variants of the others against the bands recorded for them.")
    w("")
    if not quick:
        agree = sum(1 for q, v, _ in rows if v is not None and q.agrees(v) is True)
        disagree = sum(1 for q, v, _ in rows if v is not None and q.agrees(v) is False)
        other = len(rows) - agree - disagree
        w(f"**{len(rows)} quantities: {agree} agree, {disagree} do not, {other} without a "
          f"criterion, not computed or not run (the full-size cases need `--long`: hours each); "
          f"{len(not_run)} seed case cannot be set up (last row, with the reason).** Where a seed lost the data a case needs, the case file says what was "
          "chosen; the notes say where that matters. The runs' table gives each run's wall time, "
          "its OpenMP threads and the commit it ran from; the wall times are of a shared "
          "two-core machine (not benchmarks).")
        w("")
    w("| case | paper | quantity | published | fluidem | criterion | agreement | note |")
    w("|---|---|---|---|---|---|---|---|")
    for q, v, err in rows:
        if v is None:
            val, agree = err, "n/a"
        else:
            val = q.show(v)
            ok = q.agrees(v)
            if quick and not all(r.gate_full for r in runs if r.name in q.runs):
                agree = "n/a (quick)"
            elif ok is None:
                agree = "n/a (nothing to compare)"
            else:
                agree = "**yes**" if ok else "**no**"
        w(f"| {q.case} | {q.paper} | {q.quantity} | {q.published} | {val} | {q.criterion} | "
          f"{agree} | {q.note} |")
    for n in not_run:
        w(f"| {n.case} | {n.paper} | {n.quantity} | {n.published} | not run | - | n/a | "
          f"{n.reason} |")
    w("")
    disagreeing = [(q, v) for q, v, _ in rows if v is not None and q.agrees(v) is False]
    if disagreeing and not quick:
        w("## Disagreements: why, what was tried, what it rules out")
        w("")
        for q, v in disagreeing:
            w(f"- **{q.case}, {q.quantity}**: {q.show(v)} against {q.published} ({q.paper}).")
            w(f"  - Why, as far as we know: {q.note}")
            w(f"  - Tried: {q.tried}")
        w("")
    w("## Runs")
    w("")
    w("| run | case file | overrides | commit | threads | wall time |")
    w("|---|---|---|---|---|---|")
    for r in runs:
        sets = " ".join(f"`{s}`" for s in (r.quick if quick and not r.gate_full else r.full))
        sets = sets or "-"
        wt = f"{wall[r.name]:.0f} s" if r.name in wall else "-"
        commit, threads = made.get(r.name, ("-", "-"))
        w(f"| {r.name} | cases/{r.case} | {sets} | {commit} | {threads} | {wt} |")
    w("")
    w("## Pictures")
    w("")
    for r in runs:
        if (quick and r.name not in QUICK_PLOTS) or not r.plot or r.name not in wall:
            continue  # (not drawn: a run that did not finish, or --report-only without it)
        out = outputs.dir(r.name)
        shown = []
        # The snapshot drawn again at a lower resolution (the repository keeps the report), then
        # the analysis pictures: velocity distribution, pressure-drop curve, s(t), first spectrum.
        dst = f"{r.name}_snapshot.png"
        if os.path.exists(os.path.join(out, "particles.h5")):
            code = subprocess.run([sys.executable, os.path.join(HERE, "fluidem_plot.py"), out,
                                   "--out", os.path.join(pics, dst), "--dpi", "60"],
                                  capture_output=True).returncode
            if code == 0:
                shown.append(f"![{r.name} snapshot](pictures/{dst})")
        elif os.path.exists(os.path.join(out, "report_snapshot.png")):  # an archived run
            shutil.copyfile(os.path.join(out, "report_snapshot.png"), os.path.join(pics, dst))
            shown.append(f"![{r.name} snapshot](pictures/{dst})")
        adir = os.path.join(out, "analysis")
        spectra = sorted(f for f in os.listdir(adir) if f.startswith("spectrum_")
                         and f.endswith(".png")) if os.path.isdir(adir) else []
        for f in (["velocity_distribution.png", "pressure_drop_velocity.png", "segregation.png"]
                  + spectra[:1]):
            p = os.path.join(adir, f)
            if os.path.exists(p):
                dst = f"{r.name}_{f}"
                shutil.copyfile(p, os.path.join(pics, dst))
                shown.append(f"![{r.name} {f[:-4]}](pictures/{dst})")
        if shown:
            w(f"### {r.name}")
            w("")
            w(" ".join(shown))
            w("")
    done = {r.name for r in runs if r.name in wall}
    for name, title, names, script, args in STUDY_PICTURES:
        if quick or not all(n in done for n in names):
            continue
        dst = f"{name}.png"
        code = subprocess.run([sys.executable, os.path.join(SOURCE, script)]
                              + [outputs.dir(n) for n in names] + args
                              + ["--png", os.path.join(pics, dst)], capture_output=True).returncode
        w(f"### {title}")
        w("")
        w(f"![{title}](pictures/{dst})" if code == 0 else f"({script} exited {code})")
        w("")
    if failed:
        w("## Failures (runs, quantities not computed, the gate)")
        w("")
        for f in failed:
            w(f"- {f}")
        w("")
    with open(path, "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
