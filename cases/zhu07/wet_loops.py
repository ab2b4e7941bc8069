#!/usr/bin/python3
"""The loops of the dry and wet beds of wet_bed_umf.toml side by side (README.md).

usage: /usr/bin/python3 cases/zhu07/wet_loops.py OUT_DRY OUT_WATER OUT_STRONG [PNG]

Runs ../chang08/loop_umf.py on each run folder (its loop.csv and loop_summary.csv: the pressure
drop binned by 0.1 m/s of U0 on the rising and falling branches, u_mf by the Ergun construction
on the falling branch, the rising branch's peak over W), prints one row per bed and draws the
three loops (pressure drop over W against U0) into PNG (default docs/wet_bed_loops.png).
"""
import csv
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = os.path.dirname(os.path.abspath(__file__))


def main(argv):
    if len(argv) < 4:
        sys.exit(__doc__)
    runs = {"dry": argv[1], "water, Bo = 1.0": argv[2], "model liquid, Bo = 4.2": argv[3]}
    png = argv[4] if len(argv) > 4 else os.path.join(HERE, "..", "..", "docs", "wet_bed_loops.png")
    fig, ax = plt.subplots(figsize=(7, 4.5))
    print(f"{'bed':24s} {'u_mf (Ergun) m/s':>17s} {'peak / W':>9s} {'plateau / W':>12s}")
    for (label, out), colour in zip(runs.items(), ("C0", "C1", "C3")):
        subprocess.run([sys.executable, os.path.join(HERE, "..", "chang08", "loop_umf.py"), out,
                        "--ratio", "1"], check=True, stdout=subprocess.DEVNULL)
        summary = {r["name"]: float(r["value"]) for r in csv.DictReader(open(f"{out}/loop_summary.csv"))}
        rows = list(csv.DictReader(open(f"{out}/loop.csv")))
        u = [float(r["superficial_velocity"]) for r in rows]
        ax.plot(u, [float(r["dp_up_over_W"]) for r in rows], "-", color=colour,
                label=f"{label}: rising")
        ax.plot(u, [float(r["dp_down_over_W"]) for r in rows], "--", color=colour,
                label=f"{label}: falling")
        print(f"{label:24s} {summary['u_mf_ergun']:17.2f} {summary['peak_over_W']:9.2f} "
              f"{summary['plateau_over_W']:12.2f}")
    ax.set_xlabel("superficial gas velocity U0 (m/s)")
    ax.set_ylabel("pressure drop / bed weight per area")
    ax.set_title("700 spheres of 4 mm, dry and wet (cases/zhu07/wet_bed_umf.toml)")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


if __name__ == "__main__":
    main(sys.argv)
