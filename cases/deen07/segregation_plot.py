#!/usr/bin/python3
"""Degree of segregation s(t) of the bidisperse bed with two drag closures, as [Deen07 Fig. 11].

usage: /usr/bin/python3 cases/deen07/segregation_plot.py OUT_BEETSTRA [OUT_STANDARD]
                                                          [--out PNG]

Reads OUT/analysis/segregation.csv (time,s; written by `fluidem analyse OUT`, or at the end of a
run with output.analyse = true) of the run of segregation_beetstra.toml and, if given, of
segregation_standard.toml, and draws s against time for both with the published values of
[Deen07 §6.2] (Fig. 11 itself is lost from the seed; its text gives): the experiment 0.64 and
the DPM with the Beetstra polydisperse drag 0.65 after 1 min (points at t = 60 s), and, for the
standard drag, the paper's words "almost completely segregated after 1 min" (an arrow at s = 1,
t = 60 s: no number is published). Each run's label is its coupling.drag from
OUT/case.resolved.toml. Prints s at the frame nearest 60 s (or the last frame of a shorter run)
for each run. Writes PNG (default: OUT_BEETSTRA/analysis/segregation_deen07.png).
Exit codes: 0 done; 2 bad input (a missing or malformed segregation.csv).
"""
import csv
import os
import sys
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

T_PUBLISHED = 60.0  # s: "after 1 min" [Deen07 §6.2]
EXPERIMENT = 0.64  # Goldschmidt et al. 2003, [Deen07 §6.2]
BEETSTRA_DPM = 0.65  # DPM with the Beetstra et al. 2006b drag, [Deen07 §6.2]


def fail(message):
    print(f"segregation_plot: {message}", file=sys.stderr)
    sys.exit(2)


def read_run(out):
    path = os.path.join(out, "analysis", "segregation.csv")
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        fail(f"cannot read {path} ({e.strerror}): run `fluidem analyse {out}` first")
    try:
        t = [float(r["time"]) for r in rows]
        s = [float(r["s"]) for r in rows]
    except (KeyError, TypeError, ValueError):
        fail(f"{path}: not a time,s table")
    if not t:
        fail(f"{path} has no rows")
    label = os.path.basename(os.path.normpath(out))
    try:
        with open(os.path.join(out, "case.resolved.toml"), "rb") as f:
            label = f"{label} (drag {tomllib.load(f)['coupling']['drag']})"
    except (OSError, KeyError, tomllib.TOMLDecodeError):
        pass
    return t, s, label


def main(argv):
    args = list(argv[1:])
    png = None
    if "--out" in args:
        k = args.index("--out")
        if k + 1 >= len(args):
            fail("--out needs a file name")
        png = args[k + 1]
        del args[k:k + 2]
    if not 1 <= len(args) <= 2 or any(a.startswith("-") for a in args):
        print(__doc__, file=sys.stderr)
        return 2
    runs = [read_run(out) for out in args]
    png = png or os.path.join(args[0], "analysis", "segregation_deen07.png")

    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    for (t, s, label), style in zip(runs, ["-", "--"]):  # Fig. 11: solid Beetstra, dashed standard
        ax.plot(t, s, style, lw=1.2, label=f"fluidem: {label}")
        k = min(range(len(t)), key=lambda i: abs(t[i] - T_PUBLISHED))
        print(f"{label}: s = {s[k]:.3f} at t = {t[k]:.2f} s")
    ax.plot([T_PUBLISHED], [EXPERIMENT], "ko", ms=7, label="experiment (Goldschmidt et al. 2003)")
    ax.plot([T_PUBLISHED], [BEETSTRA_DPM], "s", mfc="none", mec="C0", ms=8, mew=1.5,
            label="DPM, Beetstra drag (Beetstra et al. 2006b)")
    ax.annotate("standard drag [Deen07 §6.2]: \"almost completely segregated after 1 min\"",
                xy=(T_PUBLISHED, 1.0), xytext=(2.0, 1.06),
                arrowprops={"arrowstyle": "->", "color": "C1"}, color="C1", fontsize=9)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.axhline(1.0, color="k", lw=0.5, ls=":")
    ax.set_xlim(0.0, max(T_PUBLISHED + 2.0, max(max(r[0]) for r in runs)))
    ax.set_ylim(min(-0.1, min(min(r[1]) for r in runs) - 0.05), 1.15)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("degree of segregation s [Deen07 eq. 49]")
    ax.set_title("bidisperse bed, 1.5 / 2.5 mm glass, 1.30 m/s [Deen07 §6.2, Fig. 11]")
    ax.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    print(f"written {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
