#!/usr/bin/env python3
"""The binary-collision question of [Chang08] asked of the soft-sphere DEM: the share of the
collisions that are multiple (a particle of the pair in another contact during the collision)
against the local void fraction.

usage: chang08_binary_study.py OUT_DIR... [--from T0] [--csv FILE] [--png FILE]
                               [--threshold S]

Reads OUT/collisions.csv of soft-sphere runs of cases/chang08/binary_collision_soft_*.toml
(docs/analysis.md, "Collision statistics") over the rows whose interval ends after T0, and gives
one point per region (the whole cube, GC, CC1, CC2: spheres of radius 0.1 L): the mean void
fraction, the collisions ended, the multiple ones, their share, the collision frequency and the
mean contact duration (whole cube). Regions with fewer than 30 collisions ended are listed but
left out of the threshold.

The threshold: the void fraction above which fewer than S (default 0.05) of the collisions are
multiple, read as the largest void fraction of a point whose share is at least S (NaN when no
point reaches S: the binary assumption then holds at every void fraction the runs reached, and
the smallest of them is the bound the runs support). Printed, and written to the CSV.
The picture: the share against the void fraction, and against f t_c (the region's collision
frequency times the run's mean contact duration) with the estimate for independent collisions,
1 - exp(-4 f t_c) (tests/unit/integrate/collision_statistics_test.cpp).
"""
import argparse
import csv
import math
import os
import sys

MIN_ENDED = 30
REGIONS = ["", "GC_", "CC1_", "CC2_"]  # "" = the whole cube


def points(out, t0):
    with open(os.path.join(out, "collisions.csv")) as f:
        rows = [r for r in csv.DictReader(f) if float(r["time"]) > t0 + 1e-12]
    if not rows:
        raise SystemExit(f"{out}/collisions.csv: no rows after t = {t0} s")
    if "multiple_collisions" not in rows[0]:
        raise SystemExit(f"{out}/collisions.csv has no multiple_collisions column (soft spheres "
                         "only)")

    def total(k):
        return sum(float(r[k]) for r in rows)

    def mean(k):
        v = [float(r[k]) for r in rows if math.isfinite(float(r[k]))]
        return sum(v) / len(v) if v else math.nan

    duration = mean("mean_contact_duration")
    res = []
    for p in REGIONS:
        ended, multiple = total(p + "ended_collisions"), total(p + "multiple_collisions")
        eps = mean(p + "void_fraction") if p else math.nan
        res.append({"run": os.path.basename(os.path.normpath(out)), "region": p[:-1] or "whole",
                    "void_fraction": eps, "ended": int(ended), "multiple": int(multiple),
                    "share": multiple / ended if ended > 0 else math.nan,
                    "frequency": mean(p + "collision_frequency"), "contact_duration": duration})
    return res


def whole_void_fraction(out):
    """The cube's void fraction from the resolved case (512 spheres of one diameter)."""
    import tomllib
    with open(os.path.join(out, "case.resolved.toml"), "rb") as f:
        case = tomllib.load(f)
    d = case["species"][0]["diameter"]
    n = sum(i["count"] for i in case["insert"])
    box = [h - l for l, h in zip(case["domain"]["lo"], case["domain"]["hi"])]
    return 1.0 - n * math.pi / 6.0 * d ** 3 / (box[0] * box[1] * box[2])


def threshold(pts, s):
    counted = [p for p in pts if p["ended"] >= MIN_ENDED and math.isfinite(p["void_fraction"])]
    failing = [p["void_fraction"] for p in counted if p["share"] >= s]
    return max(failing) if failing else math.nan


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outs", nargs="+")
    ap.add_argument("--from", dest="t0", type=float, default=10.0)
    ap.add_argument("--threshold", type=float, default=0.05)
    ap.add_argument("--csv")
    ap.add_argument("--png")
    a = ap.parse_args()
    pts = []
    for out in a.outs:
        run_pts = points(out, a.t0)
        run_pts[0]["void_fraction"] = whole_void_fraction(out)
        pts += run_pts
    eps_star = threshold(pts, a.threshold)
    counted = [p for p in pts if p["ended"] >= MIN_ENDED]
    lowest = min(p["void_fraction"] for p in counted)
    print(f"{'run':<16} {'region':<6} {'eps':>6} {'ended':>7} {'multiple':>8} {'share':>7} "
          f"{'f (1/s)':>8} {'t_c (s)':>9}")
    for p in pts:
        print(f"{p['run']:<16} {p['region']:<6} {p['void_fraction']:6.3f} {p['ended']:7d} "
              f"{p['multiple']:8d} {p['share']:7.4f} {p['frequency']:8.3g} "
              f"{p['contact_duration']:9.3g}")
    print(f"void fraction above which fewer than {a.threshold:g} of the collisions are multiple: "
          f"{eps_star:.3f}" if math.isfinite(eps_star) else
          f"no point has {a.threshold:g} or more of its collisions multiple: the binary "
          f"assumption holds down to the lowest void fraction reached, {lowest:.3f}")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(pts[0]))
            w.writeheader()
            w.writerows(pts)
            f.write(f"# threshold {a.threshold:g}: void fraction {eps_star:.4f}; lowest void "
                    f"fraction with {MIN_ENDED}+ collisions {lowest:.4f}\n")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (ax, bx) = plt.subplots(1, 2, figsize=(10.5, 4.2))
        runs = sorted({p["run"] for p in pts})
        for run in runs:
            rp = [p for p in counted if p["run"] == run]
            line, = ax.plot([p["void_fraction"] for p in rp], [p["share"] for p in rp], "o",
                            label=run)
            bx.plot([p["frequency"] * p["contact_duration"] for p in rp],
                    [p["share"] for p in rp], "o", color=line.get_color(), label=run)
        ax.axhline(a.threshold, color="grey", lw=0.8, ls="--")
        ax.axvline(0.6, color="tab:red", lw=0.8, ls=":", label="[Chang08]: 0.6")
        ax.set_xlabel("local void fraction (sphere of radius 0.1 L; whole cube)")
        ax.set_ylabel("share of collisions that are multiple")
        ax.set_ylim(0.0, None)
        ax.legend(fontsize=7)
        x = [i * 1e-4 for i in range(1, 801)]
        bx.plot(x, [1 - math.exp(-4 * v) for v in x], "k-", lw=0.8,
                label="1 - exp(-4 f t_c) (independent collisions)")
        bx.axhline(a.threshold, color="grey", lw=0.8, ls="--")
        bx.set_xscale("log")
        bx.set_yscale("log")
        bx.set_xlabel("collision frequency x mean contact duration, f t_c")
        bx.set_ylabel("share of collisions that are multiple")
        bx.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(a.png, dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
