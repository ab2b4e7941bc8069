#!/usr/bin/env python3
"""Pressure drop against superficial velocity of a velocity sweep (the fluidisation loop of
[Chang08 §3.4, Fig. 6]) from the CSV the minimum-fluidisation validation test writes
(columns superficial_velocity, pressure_drop, branch = down | up), as a PNG.

Usage: plot_fluidisation_loop.py minimum_fluidisation.csv out.png [--umf U] [--weight W]
  --umf: the u_mf found (drawn as a vertical line), --weight: bed weight per area, Pa.
Use the Debian interpreter (/usr/bin/python3), which has matplotlib.
"""
import argparse
import csv
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit("plot_fluidisation_loop.py: matplotlib is missing (apt-get install python3-matplotlib; "
             "run with /usr/bin/python3)")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("csv")
    p.add_argument("png")
    p.add_argument("--umf", type=float, help="u_mf found, m/s")
    p.add_argument("--wen-yu", type=float, default=1.77, help="Wen & Yu u_mf, m/s")
    p.add_argument("--weight", type=float, help="bed weight per area, Pa")
    a = p.parse_args(argv)
    branches = {"down": ([], []), "up": ([], [])}
    try:
        with open(a.csv, newline="") as f:
            for row in csv.DictReader(f):
                u, dp = float(row["superficial_velocity"]), float(row["pressure_drop"])
                branches[row["branch"]][0].append(u)
                branches[row["branch"]][1].append(dp)
    except (OSError, KeyError, ValueError) as e:
        sys.exit(f"plot_fluidisation_loop.py: cannot read {a.csv}: {e}")
    fig, ax = plt.subplots(figsize=(6, 4.2), dpi=120)
    ax.plot(*branches["down"], "o-", ms=3, label="velocity decreasing")
    ax.plot(*branches["up"], "s--", ms=3, label="velocity increasing")
    if a.weight:
        ax.axhline(a.weight, color="grey", lw=0.8, label="bed weight / area")
    if a.umf:
        ax.axvline(a.umf, color="C3", lw=1, label=f"u_mf found {a.umf:.2f} m/s")
    ax.axvline(a.wen_yu, color="k", ls=":", lw=1, label=f"Wen & Yu {a.wen_yu:.2f} m/s")
    ax.set_xlabel("superficial gas velocity, m/s")
    ax.set_ylabel("pressure drop, Pa")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
