#!/usr/bin/python3
"""fluidem's validation report: run the seeds' cases, compare with the published numbers.

Called by `fluidem validate [--quick]` (docs/validation/README.md says how to read the report):

    fluidem_validate.py --fluidem BIN [--quick] [--work DIR] [--report FILE] [--only TEXT]
                        [--threads N] [--list]

Each run is `fluidem run CASE --set ...` into WORK/<run>, then `fluidem analyse` (and `fluidem
plot` for the pictures); each compared quantity is read from the run's outputs (the
summary.csv rows of `fluidem analyse`, series.csv, fields.h5) and set beside the published
value with the criterion it is judged by. The report is a Markdown file with one table and the
pictures copied beside it. Full runs (the default) write docs/validation/README.md of the source
tree; `--quick` runs short versions (ctest label `regression`): their numbers are not comparable
with the papers and the report says so; the quick mode checks that every run completes and every
quantity is extracted.

Exit status: 0 when every run completed and every quantity was extracted (whether or not it
agrees: disagreement is a result, reported with its reason); 1 when a run failed or a quantity
could not be computed; 2 for bad arguments.
"""

import argparse
import csv
import datetime
import math
import os
import platform
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)
CASES = os.path.join(SOURCE, "cases")


class Run:
    """One `fluidem run` of a shipped case: full and quick overrides (--set key=value)."""

    def __init__(self, name, case, full=(), quick=(), analyse=(), plot=True, post=(),
                 long=False):
        self.name = name
        self.long = long  # hours of wall time: run only with --long, never in --quick
        self.post = list(post)  # a script of the case folder run on OUT: [script, args...]
        self.case = case
        self.full = list(full)
        self.quick = list(quick)
        self.analyse = list(analyse)
        self.plot = plot


class Quantity:
    """A compared quantity: value(outputs) -> float; agrees(value) -> bool or None."""

    def __init__(self, case, paper, quantity, published, value, agrees, criterion, note="",
                 runs=(), fmt="{:.4g}"):
        self.case = case
        self.paper = paper
        self.quantity = quantity
        self.published = published
        self.value = value
        self.agrees = agrees
        self.criterion = criterion
        self.note = note
        self.runs = list(runs)
        self.fmt = fmt


class NotRun:
    """A seed case the report lists but cannot run (yet), with the reason."""

    def __init__(self, case, paper, quantity, published, reason):
        self.case = case
        self.paper = paper
        self.quantity = quantity
        self.published = published
        self.reason = reason


class Outputs:
    """The output directories of the runs, and readers of their files."""

    def __init__(self, work):
        self.work = work

    def dir(self, run):
        return os.path.join(self.work, run)

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

    def bubble_fraction(self, run, threshold=0.8):
        """Mean over the frames of the analysis window of the fraction of the gas cells below
        the bed height (series.csv `bed_height`, interpolated to the frame) whose porosity
        exceeds `threshold`: 0 for a bed without bubbles. The porosity is the one the gas
        solver uses (in 2-D the 3-D porosity of [Hoomans96 eq. 49])."""
        import h5py
        import numpy as np

        t0 = self.summary(run, "window_start")
        t1 = self.summary(run, "window_end")
        s = self.series(run)
        with h5py.File(os.path.join(self.dir(run), "fields.h5"), "r") as f:
            times = f["/fields/time"][:]
            por = f["/fields/porosity"]
            lo = f["/grid/lo"][:]
            dz = f["/grid/spacing"][:][2]
            nz = por.shape[1]
            zc = lo[2] + (np.arange(nz) + 0.5) * dz
            fractions = []
            for k, t in enumerate(times):
                if t < t0 - 1e-12 or t > t1 + 1e-12:
                    continue
                h = np.interp(t, s["time"], s["bed_height"])
                below = zc < lo[2] + h
                if not below.any():
                    continue
                eps = por[k][below]
                fractions.append(float(np.mean(eps > threshold)))
        if not fractions:
            raise ValueError(f"{run}: no fields.h5 frame in the window [{t0}, {t1}] s")
        return sum(fractions) / len(fractions)


def ratio_text(a, b):
    return a / b if b != 0 else math.inf


# ---------------------------------------------------------------------------------------------
# The cases. Published values from the seeds (../shared/seeds); criteria as stated per row.
# ---------------------------------------------------------------------------------------------

IDEAL = ["species[0].restitution=1.0", "species[0].friction=0.0", "walls.restitution=1.0",
         "walls.friction=0.0"]

RUNS = [
    Run("pouring_soft", "hoomans96/pouring_soft.toml",
        quick=["simulation.end_time=0.3"], analyse=["--from", "0"]),
    Run("pouring_hard", "hoomans96/pouring_hard.toml",
        full=["simulation.end_time=1.0"], quick=["simulation.end_time=0.3"],
        analyse=["--from", "0"]),
    Run("tsuji_setup", "hoomans96/tsuji_setup.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "0.3"]),
    Run("bubble_orifice", "hoomans96/bubble_orifice.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "0.3"]),
    Run("bubble_orifice_ideal", "hoomans96/bubble_orifice.toml", full=IDEAL,
        quick=IDEAL + ["simulation.end_time=0.05"], analyse=["--from", "0.3"]),
    Run("slug_homogeneous", "hoomans96/slug_homogeneous.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "0.5"]),
    Run("slug_homogeneous_ideal", "hoomans96/slug_homogeneous.toml", full=IDEAL,
        quick=IDEAL + ["simulation.end_time=0.05"], analyse=["--from", "0.5"]),
    Run("binary_collision_d10", "chang08/binary_collision_d10.toml",
        quick=["simulation.end_time=0.5"], analyse=["--from", "10"]),
    Run("binary_collision_d7_5", "chang08/binary_collision_d7_5.toml",
        quick=["simulation.end_time=0.5"], analyse=["--from", "10"]),
    Run("binary_collision_d5", "chang08/binary_collision_d5.toml",
        quick=["simulation.end_time=0.5"], analyse=["--from", "10"]),
    Run("spouted_2.6", "chang08/spouted_2.6.toml", quick=["simulation.end_time=0.05"],
        analyse=["--from", "0.2", "--segment", "0.4"]),
    Run("single_bubble_quick", "deen07/single_bubble_quick.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "0.02"],
        post=["deen07/bubble_size.py"]),
    Run("velocity_ideal_quick", "deen07/velocity_ideal_quick.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "0.5"]),
    Run("velocity_nonideal_quick", "deen07/velocity_nonideal_quick.toml",
        quick=["simulation.end_time=0.05"], analyse=["--from", "0.5"]),
]

H96 = "Hoomans96"
QUANTITIES = [
    Quantity("pouring_soft", "[Hoomans96 §5.1]", "settled area fraction",
             "0.832 ± 0.010",
             lambda o: o.summary("pouring_soft", "area_fraction_last_frame"),
             lambda v: abs(v - 0.832) <= 0.020, "within 0.020 (twice the published spread)",
             "soft spheres, k_n = 1e4 N/m", runs=["pouring_soft"], fmt="{:.3f}"),
    Quantity("pouring_soft", "[Hoomans96 §5.1]", "energy balance error (largest, relative)",
             "< 5e-5 (0.005 %)",
             lambda o: o.summary("pouring_soft", "energy_balance_error"),
             lambda v: v < 5e-5, "below 5e-5",
             "the paper's is the hard-sphere error; a soft-sphere run's is its integration "
             "error (velocity Verlet)", runs=["pouring_soft"], fmt="{:.2e}"),
    Quantity("pouring_hard", "[Hoomans96 §5.1]", "settled area fraction", "0.832 ± 0.010",
             lambda o: o.summary("pouring_hard", "area_fraction_last_frame"),
             lambda v: abs(v - 0.832) <= 0.020, "within 0.020 (twice the published spread)",
             "event-driven hard spheres", runs=["pouring_hard"], fmt="{:.3f}"),
    Quantity("pouring_hard", "[Hoomans96 §5.1]", "energy balance error (largest, relative)",
             "< 5e-5 (0.005 %)",
             lambda o: o.summary("pouring_hard", "energy_balance_error"),
             lambda v: v < 5e-5, "below 5e-5",
             "series.csv holds 10 significant digits: 0 means below 1e-10 (the run's log: "
             "round-off, exact parabolic flights, every collision's loss booked)",
             runs=["pouring_hard"], fmt="{:.2e}"),
    Quantity("tsuji_setup", "[Hoomans96 §5.2]", "bubble fraction (cells of the bed with "
             "porosity > 0.8)", "no bubbles",
             lambda o: o.bubble_fraction("tsuji_setup"), lambda v: v < 0.01, "below 0.01",
             "the 2-D bed is above its own u_mf at 1.8 m/s (cases/hoomans96/README.md)",
             runs=["tsuji_setup"], fmt="{:.3f}"),
    Quantity("bubble_orifice", "[Hoomans96 §5.3.1]", "bubble fraction, non-ideal (e = 0.9, "
             "mu = 0.3)", "bubbles (a bubble turning into a slug)",
             lambda o: o.bubble_fraction("bubble_orifice"), lambda v: v >= 0.01, "at least 0.01",
             runs=["bubble_orifice"], fmt="{:.3f}"),
    Quantity("bubble_orifice", "[Hoomans96 §5.3.1]", "bubble fraction, ideal (e = 1, mu = 0)",
             "no bubbles", lambda o: o.bubble_fraction("bubble_orifice_ideal"),
             lambda v: v < 0.01, "below 0.01",
             "as in tsuji_setup: the 2-D packing converted to 3-D porosity (eq. 49) is dense "
             "(eps = 0.33), where Ergun carries the bed at about 1.1 m/s, so at 1.8 m/s the "
             "model bed is fluidised even without the jet, and the full inflow from rest lifts "
             "it as a plug (cases/hoomans96/README.md); the non-ideal/ideal contrast is there",
             runs=["bubble_orifice_ideal"], fmt="{:.3f}"),
    Quantity("bubble_orifice", "[Hoomans96 §5.3.1, Fig. 11]", "pressure std 20 cm above the "
             "jet, non-ideal / ideal", "> 1 (the non-ideal line has the strongest peaks)",
             lambda o: ratio_text(math.sqrt(o.summary("bubble_orifice", "pressure_variance_p_20cm")),
                                  math.sqrt(o.summary("bubble_orifice_ideal",
                                                      "pressure_variance_p_20cm"))),
             lambda v: v > 1.0, "above 1", runs=["bubble_orifice", "bubble_orifice_ideal"],
             fmt="{:.2f}"),
    Quantity("bubble_orifice", "[Hoomans96 §5.3]", "collisions in the run, non-ideal",
             "over 3 million", lambda o: o.summary("bubble_orifice", "collisions_total"),
             lambda v: v > 3e6, "above 3e6", runs=["bubble_orifice"], fmt="{:.3g}"),
    Quantity("slug_homogeneous", "[Hoomans96 §5.3.2, Fig. 13]", "pressure-drop std / bed "
             "weight, non-ideal / ideal", "> 1 (slugs with pressure peaks vs homogeneous "
             "expansion)",
             lambda o: ratio_text(o.summary("slug_homogeneous", "pressure_drop_std_over_weight"),
                                  o.summary("slug_homogeneous_ideal",
                                            "pressure_drop_std_over_weight")),
             lambda v: v > 1.0, "above 1", runs=["slug_homogeneous", "slug_homogeneous_ideal"],
             fmt="{:.2f}"),
    Quantity("slug_homogeneous", "[Hoomans96 §5.3.2]", "mean pressure drop / bed weight, "
             "non-ideal", "1 (a fluidised bed carries its weight)",
             lambda o: o.summary("slug_homogeneous", "pressure_drop_over_weight"),
             lambda v: abs(v - 1.0) <= 0.1, "within 10 %", runs=["slug_homogeneous"],
             fmt="{:.3f}"),
    Quantity("slug_homogeneous", "[Hoomans96 §5.3.2]", "collisions in the run, ideal",
             "slightly over 1 million", lambda o: o.summary("slug_homogeneous_ideal",
                                                            "collisions_total"),
             lambda v: 1e6 <= v <= 2e6, "1e6 to 2e6",
             "the paper's run length is not stated", runs=["slug_homogeneous_ideal"],
             fmt="{:.3g}"),
]

QUANTITIES += [
    Quantity("spouted_2.6", "[Chang08 §3.3, Fig. 3.10]", "regime at U0 = 2.6 m/s: mean pressure "
             "drop / bed weight", "spouting (the pressure drop falls below the bed weight in "
             "the fluidised region)",
             lambda o: o.summary("spouted_2.6", "pressure_drop_over_weight"),
             lambda v: v < 1.0, "below 1",
             "inlet width, grid and start lost in the seed: chosen (cases/chang08/README.md); "
             "within 1 s a cavity forms, no through-spout", runs=["spouted_2.6"], fmt="{:.3f}"),
    Quantity("spouted_2.6", "[Chang08 §3.4]", "dominant pressure frequency 200 mm above the "
             "nozzle", "not given in the text (Fig. 3.16 lost)",
             lambda o: o.summary("spouted_2.6", "dominant_frequency_p_200mm"),
             lambda v: None, "none (no published number)", runs=["spouted_2.6"],
             fmt="{:.2f} Hz"),
    Quantity("single_bubble_quick", "[Deen07 §6.1]", "bed height before the jet (0.005-0.02 s; "
             "reduced case: one particle deep, 0.15 m wide)", "0.22 m",
             lambda o: o.window_mean("single_bubble_quick", "bed_height", 0.005, 0.02),
             lambda v: abs(v - 0.22) <= 0.022, "within 10 %", runs=["single_bubble_quick"],
             fmt="{:.3f} m"),
    Quantity("single_bubble_quick", "[Deen07 §6.1]", "pressure drop / bed weight before the "
             "jet (incipient fluidisation)", "1",
             lambda o: o.window_mean("single_bubble_quick", "pressure_drop", 0.005, 0.02)
             / o.summary("single_bubble_quick", "bed_weight_per_area"),
             lambda v: abs(v - 1.0) <= 0.15, "within 15 %",
             "a one-particle-deep bed packs looser: not quite fluidised at 1.25 m/s",
             runs=["single_bubble_quick"], fmt="{:.2f}"),
    Quantity("single_bubble_quick", "[Deen07 §6.1, Fig. 8]", "bubble equivalent diameter 0.1 s "
             "after injection (cells with porosity > 0.8)",
             "a bubble (sizes in the lost Fig. 8; DPM slightly larger than experiment)",
             lambda o: o.csv_at("single_bubble_quick", "bubble.csv", "after_injection", 0.1,
                                "equivalent_diameter"),
             lambda v: v > 0.03, "a bubble: above 0.03 m", "reduced case (5,620 particles)",
             runs=["single_bubble_quick"], fmt="{:.3f} m"),
    Quantity("velocity_ideal_quick", "[Deen07 §6.2, Fig. 10]", "velocity kurtosis x / z, ideal "
             "particles", "near Gaussian (3)",
             lambda o: max(abs(o.summary("velocity_ideal_quick", "velocity_kurtosis_x") - 3),
                           abs(o.summary("velocity_ideal_quick", "velocity_kurtosis_z") - 3)) + 3,
             lambda v: abs(v - 3.0) <= 1.0, "both within 3 ± 1 (the value shown: the farther)",
             "reduced case: 5,000 particles, 1 s", runs=["velocity_ideal_quick"], fmt="{:.2f}"),
    Quantity("velocity_nonideal_quick", "[Deen07 §6.2, Fig. 10]", "velocity kurtosis x / z, "
             "non-ideal particles", "near Gaussian (3)",
             lambda o: max(abs(o.summary("velocity_nonideal_quick", "velocity_kurtosis_x") - 3),
                           abs(o.summary("velocity_nonideal_quick",
                                         "velocity_kurtosis_z") - 3)) + 3,
             lambda v: abs(v - 3.0) <= 1.0, "both within 3 ± 1 (the value shown: the farther)",
             "sharply peaked with long tails: the fluctuations pooled over a mostly packed small "
             "bed and a few fast bubbles; whether the full case (25,000 particles) and "
             "Goldschmidt's sampling change this is open", runs=["velocity_nonideal_quick"],
             fmt="{:.2f}"),
    Quantity("velocity_ideal_quick", "[Deen07 §6.2]", "anisotropy s_z^2 / s_horizontal^2, ideal",
             "isotropic",
             lambda o: o.summary("velocity_ideal_quick", "anisotropy"),
             lambda v: abs(v - 1.0) <= 0.3, "1 ± 0.3", runs=["velocity_ideal_quick"],
             fmt="{:.2f}"),
    Quantity("velocity_nonideal_quick", "[Deen07 §6.2]", "anisotropy s_z^2 / s_horizontal^2, "
             "non-ideal", "clear anisotropy",
             lambda o: o.summary("velocity_nonideal_quick", "anisotropy"),
             lambda v: v > 1.3, "above 1.3", runs=["velocity_nonideal_quick"], fmt="{:.2f}"),
]

# The full-size cases: hours each today (issue 7). `fluidem validate --long` runs them too.
RUNS += [
    Run("validation_40k", "hoomans96/validation_40k.toml", analyse=["--from", "0.5", "--to", "0.7"],
        long=True),
    Run("spouted_loop", "chang08/spouted_loop.toml", post=["chang08/loop_umf.py"], long=True),
    Run("single_bubble", "deen07/single_bubble.toml", analyse=["--from", "0.6"],
        post=["deen07/bubble_size.py"], long=True),
    Run("velocity_ideal", "deen07/velocity_ideal.toml", analyse=["--from", "1.0"], long=True),
    Run("velocity_nonideal", "deen07/velocity_nonideal.toml", analyse=["--from", "1.0"],
        long=True),
]


def loop_summary(o, run, name):
    """A row of OUT/loop_summary.csv (name,value,unit) of cases/chang08/loop_umf.py."""
    with open(os.path.join(o.dir(run), "loop_summary.csv")) as f:
        for row in csv.DictReader(f):
            if row["name"] == name:
                return float(row["value"])
    raise KeyError(f"{run}: loop_summary.csv has no row '{name}'")


def kurtosis_farthest(o, run):
    """The kurtosis of the x, y, z velocity fluctuations farthest from the Gaussian's 3."""
    k = [o.summary(run, f"velocity_kurtosis_{a}") for a in "xz"]
    return max(k, key=lambda v: abs(v - 3.0))


QUANTITIES += [
    Quantity("validation_40k", "[Hoomans96 §5.4, Fig. 15]", "bubble fraction during the jet "
             "(0.5-0.7 s; cells of the bed with porosity > 0.8)",
             "a bubble comparing reasonably with the photographs (figures lost)",
             lambda o: o.bubble_fraction("validation_40k"), lambda v: v >= 0.01,
             "a bubble: at least 0.01", "40,000 particles", runs=["validation_40k"],
             fmt="{:.3f}"),
    Quantity("spouted_loop", "[Chang08 §3.4, Fig. 3.17]", "u_mf: crossing of the rising and "
             "falling branches (point C)", "1.9 m/s",
             lambda o: loop_summary(o, "spouted_loop", "u_mf_C"),
             lambda v: abs(v / 1.9 - 1) <= 0.2, "within 20 %",
             "17 s of bed, about 2.6 h. A loop ramped 4x faster (4.4 s of bed, 1969 s of wall "
             "time, cases/chang08/README.md) gave 2.21 m/s here and 1.58 m/s for the Ergun fit "
             "below; the periodic 3-D loop of tests/validation/integrate/"
             "minimum_fluidisation_test.cpp gave 1.594 m/s (-9.9 % from Wen & Yu)",
             runs=["spouted_loop"], fmt="{:.2f} m/s"),
    Quantity("spouted_loop", "[Chang08 §3.2, eq. 3.8]", "u_mf: Ergun fit of the fixed-bed "
             "branch meeting the plateau", "1.77 m/s (Wen & Yu)",
             lambda o: loop_summary(o, "spouted_loop", "u_mf_ergun"),
             lambda v: abs(v / 1.77 - 1) <= 0.15, "within 15 %", runs=["spouted_loop"],
             fmt="{:.2f} m/s"),
    Quantity("single_bubble", "[Deen07 §6.1]", "bed height before the jet (0.5-0.6 s)", "0.22 m",
             lambda o: o.window_mean("single_bubble", "bed_height", 0.5, 0.6),
             lambda v: abs(v - 0.22) <= 0.022, "within 10 %", runs=["single_bubble"],
             fmt="{:.3f} m"),
    Quantity("single_bubble", "[Deen07 §6.1]", "pressure drop / bed weight before the jet", "1",
             lambda o: o.window_mean("single_bubble", "pressure_drop", 0.5, 0.6)
             / o.summary("single_bubble", "bed_weight_per_area"),
             lambda v: abs(v - 1.0) <= 0.15, "within 15 %", runs=["single_bubble"],
             fmt="{:.2f}"),
    Quantity("single_bubble", "[Deen07 §6.1, Fig. 8]", "bubble equivalent diameter 0.1 s after "
             "injection", "a bubble (sizes in the lost Fig. 8)",
             lambda o: o.csv_at("single_bubble", "bubble.csv", "after_injection", 0.1,
                                "equivalent_diameter"),
             lambda v: v > 0.03, "a bubble: above 0.03 m", runs=["single_bubble"],
             fmt="{:.3f} m"),
    Quantity("velocity_ideal", "[Deen07 §6.2, Fig. 10]", "velocity kurtosis (x or z, the "
             "farther from 3), ideal, 25,000 particles", "near Gaussian (3)",
             lambda o: kurtosis_farthest(o, "velocity_ideal"),
             lambda v: abs(v - 3.0) <= 1.0, "within 3 ± 1", runs=["velocity_ideal"],
             fmt="{:.2f}"),
    Quantity("velocity_nonideal", "[Deen07 §6.2, Fig. 10]", "velocity kurtosis (x or z, the "
             "farther from 3), non-ideal, 25,000 particles", "near Gaussian (3)",
             lambda o: kurtosis_farthest(o, "velocity_nonideal"),
             lambda v: abs(v - 3.0) <= 1.0, "within 3 ± 1", runs=["velocity_nonideal"],
             fmt="{:.2f}"),
    Quantity("velocity_nonideal", "[Deen07 §6.2]", "anisotropy, non-ideal / ideal, 25,000 "
             "particles", "> 1 (ideal isotropic, non-ideal clearly anisotropic)",
             lambda o: o.summary("velocity_nonideal", "anisotropy")
             / o.summary("velocity_ideal", "anisotropy"),
             lambda v: v > 1.3, "above 1.3", runs=["velocity_ideal", "velocity_nonideal"],
             fmt="{:.2f}"),
]

# [Chang08 conference paper, Table 1]: 512 spheres in a periodic cube of water driven by a
# sinusoidal field (eq. 1, garbled: reconstructed, cases/chang08/README_binary_collision.md).
CUBE_NOTE = ("eq. (1) reconstructed (the seed garbles it), restitution 0.9 and no friction "
             "chosen, water held at rest on average (coupling.hold_gas_at_rest)")
TABLE1 = {  # d: (void fraction whole, GC, CC; collision frequency whole, GC, CC)
    "10": (0.732, 0.546, 0.440, 11.86, 10.83, 27.87),
    "7_5": (0.887, 0.619, 0.564, 8.852, 4.761, 22.63),
    "5": (0.966, 0.840, 0.619, 7.690, 8.991, 12.90),
}


def cube_cc(o, run, what):
    """The mean of the two collision centres CC1 and CC2."""
    return 0.5 * (o.summary(run, "CC1_" + what) + o.summary(run, "CC2_" + what))


for d, (vw, vg, vc, fw, fg, fc) in TABLE1.items():
    run = f"binary_collision_d{d}"
    size = d.replace("_", ".") + " mm"
    QUANTITIES += [
        Quantity(run, "[Chang08 binary-collision paper, Table 1]",
                 f"collision frequency, whole cube, d = {size}", f"{fw} 1/s",
                 lambda o, run=run: o.summary(run, "collision_frequency"),
                 lambda v, fw=fw: abs(v / fw - 1) <= 0.25, "within 25 %",
                 CUBE_NOTE + ("" if d == "10" else "; not steady after 30 s: f falls during the "
                              "run as the particles form streams along the field lines that "
                              "carry their water (cases/chang08/README_binary_collision.md)"),
                 runs=[run], fmt="{:.3g} 1/s"),
        Quantity(run, "[Chang08 binary-collision paper, Table 1]",
                 f"collision frequency at GC (sphere of radius 0.1 L), d = {size}", f"{fg} 1/s",
                 lambda o, run=run: o.summary(run, "GC_collision_frequency"),
                 lambda v, fg=fg: abs(v / fg - 1) <= 0.25, "within 25 %",
                 runs=[run], fmt="{:.3g} 1/s"),
        Quantity(run, "[Chang08 binary-collision paper, Table 1]",
                 f"collision frequency at CC (mean of the two), d = {size}", f"{fc} 1/s",
                 lambda o, run=run: cube_cc(o, run, "collision_frequency"),
                 lambda v, fc=fc: abs(v / fc - 1) <= 0.25, "within 25 %", runs=[run],
                 fmt="{:.3g} 1/s"),
        Quantity(run, "[Chang08 binary-collision paper, Table 1]",
                 f"local void fraction at GC, d = {size}", f"{vg}",
                 lambda o, run=run: o.summary(run, "GC_void_fraction"),
                 lambda v, vg=vg: abs(v - vg) <= 0.05, "within 0.05",
                 "the global void fraction is "
                 f"{vw} by construction (512 spheres in 1 litre)", runs=[run],
                 fmt="{:.3f}"),
        Quantity(run, "[Chang08 binary-collision paper, Table 1]",
                 f"local void fraction at CC (mean of the two), d = {size}", f"{vc}",
                 lambda o, run=run: cube_cc(o, run, "void_fraction"),
                 lambda v, vc=vc: abs(v - vc) <= 0.05, "within 0.05",
                 "our particles gather less at GC and CC than the paper's" if d != "10" else
                 "", runs=[run], fmt="{:.3f}"),
    ]

NOT_RUN = [
    NotRun("chang08 bubbling bed", "[Chang08 §4]", "mean pressure drop; PSD peak at 150 mm",
           "826.1 Pa; 1.82 Hz",
           "the particle size and velocity of the cases (Table 4.2) are lost in the seed's "
           "extraction: the case cannot be set up without inventing them"),
]


# ---------------------------------------------------------------------------------------------

def run_cmd(cmd, log, cwd=None):
    with open(log, "a") as f:
        f.write("$ " + " ".join(cmd) + "\n")
        f.flush()
        return subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, cwd=cwd).returncode


def git_commit():
    try:
        out = subprocess.run(["git", "-C", SOURCE, "rev-parse", "--short", "HEAD"],
                             capture_output=True, text=True, check=True)
        return out.stdout.strip()
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


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--fluidem", required=True, help="the fluidem binary")
    ap.add_argument("--quick", action="store_true", help="short runs (CI); numbers not comparable")
    ap.add_argument("--work", help="directory of the runs (default out/validation[-quick])")
    ap.add_argument("--report", help="report file (default docs/validation/README.md of the "
                    "source tree; WORK/README.md with --quick)")
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
    a = ap.parse_args()

    chosen = [r for r in RUNS if not a.only or any(t in r.name for t in a.only)]
    # The hours-long cases run only with --long (never in --quick); their rows say so.
    runs = [r for r in chosen if not r.long or (a.long and not a.quick)]
    long_left = {r.name for r in chosen if r not in runs}
    names = {r.name for r in chosen}
    quantities = [q for q in QUANTITIES if all(r in names for r in q.runs)]
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
    outputs = Outputs(work)
    failed = []
    skipped = []  # --report-only: runs not finished in WORK
    wall = {}
    for r in runs:
        out = outputs.dir(r.name)
        log = os.path.join(work, r.name + ".log")
        cmd = [a.fluidem, "run", os.path.join(CASES, r.case), "--out", out, "--force"]
        for s in (r.quick if a.quick else r.full):
            cmd += ["--set", s]
        if a.threads > 0:
            cmd += ["--threads", str(a.threads)]
        done = os.path.join(work, r.name + ".done")
        if a.report_only:
            if os.path.exists(done):
                with open(done) as f:
                    wall[r.name] = float(f.read().split("\n")[1])
            else:
                skipped.append(r.name)
            continue
        reused = False
        if a.reuse and os.path.exists(done):
            with open(done) as f:
                prev_cmd, prev_wall = f.read().split("\n")[:2]
            if prev_cmd == " ".join(cmd[1:]):
                wall[r.name] = float(prev_wall)
                reused = True
                print(f"[{r.name}] run reused ({done})", flush=True)
        if not reused:
            for old in (done, log):
                if os.path.exists(old):
                    os.remove(old)
            print(f"[{r.name}] running {r.case} ...", flush=True)
            t = time.time()
            code = run_cmd(cmd, log)
            wall[r.name] = time.time() - t
            if code != 0:
                failed.append(f"{r.name}: fluidem run exited {code} (log {log})")
                print(f"[{r.name}] FAILED (exit {code}), log {log}", flush=True)
                continue
        analyse = [a.fluidem, "analyse", out] + (["--from", "0"] if a.quick else r.analyse)
        code = run_cmd(analyse, log)
        if code != 0:
            failed.append(f"{r.name}: fluidem analyse exited {code} (log {log})")
            continue
        if r.post:
            code = run_cmd([sys.executable, os.path.join(CASES, r.post[0])] + r.post[1:] + [out],
                           log)
            if code != 0:
                failed.append(f"{r.name}: {r.post[0]} exited {code} (log {log})")
        if r.plot:
            code = run_cmd([a.fluidem, "plot", out], log)
            if code != 0:
                failed.append(f"{r.name}: fluidem plot exited {code} (log {log})")
        if not reused:
            with open(done, "w") as f:
                f.write(" ".join(cmd[1:]) + "\n" + str(wall[r.name]) + "\n")
        print(f"[{r.name}] done ({wall[r.name]:.0f} s of wall time)", flush=True)

    rows = []
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

    write_report(report, a.quick, runs, rows, wall, failed, outputs)
    print(f"report: {report}")
    if failed:
        print("failures:\n  " + "\n  ".join(failed), file=sys.stderr)
        return 1
    return 0


def write_report(path, quick, runs, rows, wall, failed, outputs):
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
        w("**Quick mode**: every run is cut short (a few hundredths of a second of bed, analysed from t = 0), so the "
          "values below are NOT comparable with the papers; this report only shows that every "
          "case runs and every quantity is extracted. The full report is "
          "docs/validation/README.md.")
        w("")
    w("Agreement: **yes** when fluidem's value meets the criterion, **no** when it does not "
      "(the note says why, as far as we know), n/a when the quantity could not be computed.")
    w("")
    if not quick:
        agree = sum(1 for q, v, _ in rows if v is not None and q.agrees(v) is True)
        disagree = sum(1 for q, v, _ in rows if v is not None and q.agrees(v) is False)
        other = len(rows) - agree - disagree
        w(f"**{len(rows)} quantities: {agree} agree, {disagree} do not, {other} without a "
          f"criterion, not computed or not run (the full-size cases need `--long`: hours each); "
          f"{len(NOT_RUN)} seed case cannot be set up (last row, with the reason).** Where a seed lost the data a case needs, the case file says what was "
          "chosen; the notes say where that matters. Wall times below are of one thread on a "
          "shared two-core machine (not benchmarks).")
        w("")
    w("| case | paper | quantity | published | fluidem | criterion | agreement | note |")
    w("|---|---|---|---|---|---|---|---|")
    for q, v, err in rows:
        if v is None:
            val, agree = err, "n/a"
        else:
            val = q.fmt.format(v)
            ok = q.agrees(v)
            if quick:
                agree = "n/a (quick)"
            elif ok is None:
                agree = "n/a (nothing to compare)"
            else:
                agree = "**yes**" if ok else "**no**"
        w(f"| {q.case} | {q.paper} | {q.quantity} | {q.published} | {val} | {q.criterion} | "
          f"{agree} | {q.note} |")
    for n in NOT_RUN:
        w(f"| {n.case} | {n.paper} | {n.quantity} | {n.published} | not run | - | n/a | "
          f"{n.reason} |")
    w("")
    w("## Runs")
    w("")
    w("| run | case file | overrides | wall time |")
    w("|---|---|---|---|")
    for r in runs:
        sets = " ".join(f"`{s}`" for s in (r.quick if quick else r.full)) or "-"
        wt = f"{wall[r.name]:.0f} s" if r.name in wall else "-"
        w(f"| {r.name} | cases/{r.case} | {sets} | {wt} |")
    w("")
    w("## Pictures")
    w("")
    for r in runs:
        out = outputs.dir(r.name)
        shown = []
        # The snapshot drawn again at a lower resolution (the repository keeps the report), then
        # the analysis pictures: velocity distribution, pressure-drop curve, first spectrum.
        if os.path.exists(os.path.join(out, "particles.h5")):
            dst = f"{r.name}_snapshot.png"
            code = subprocess.run([sys.executable, os.path.join(HERE, "fluidem_plot.py"), out,
                                   "--out", os.path.join(pics, dst), "--dpi", "60"],
                                  capture_output=True).returncode
            if code == 0:
                shown.append(f"![{r.name} snapshot](pictures/{dst})")
        adir = os.path.join(out, "analysis")
        spectra = sorted(f for f in os.listdir(adir) if f.startswith("spectrum_")
                         and f.endswith(".png")) if os.path.isdir(adir) else []
        for f in ["velocity_distribution.png", "pressure_drop_velocity.png"] + spectra[:1]:
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
    if failed:
        w("## Failures")
        w("")
        for f in failed:
            w(f"- {f}")
        w("")
    with open(path, "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
