#!/usr/bin/python3
"""Snapshot picture of a fluidem run.

Usage: /usr/bin/python3 python/fluidem_plot.py OUTDIR [--frame -1] [--color-by species|speed|id]
                                                      [--out PNG]

Reads OUTDIR/particles.h5 (H5MD, written by fluidem's H5mdWriter) and draws one frame's particles
as circles of their true radius in the x-z plane (axes in mm). For 3-D data (a spread in y) only
the particles of the slab |y - y_mid| < 2 r_max are drawn (y_mid: middle of the box, or of the
particles when the file has no box), and the title says so. If OUTDIR/series.csv exists, a second
panel shows the energies over time (the columns e_kin, e_rot, e_pot, e_el, e_dsp that are present,
and their sum, "total"). Writes OUTDIR/snapshot.png unless --out is given.

Exit codes: 0 done, 2 bad input (missing file, frame out of range, malformed file).
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Circle, Patch, Rectangle  # noqa: E402

ENERGY_COLUMNS = ["e_kin", "e_rot", "e_pot", "e_el", "e_dsp"]
ENERGY_LABELS = {
    "e_kin": "kinetic",
    "e_rot": "rotational",
    "e_pot": "potential",
    "e_el": "elastic",
    "e_dsp": "dissipated",
}


def fail(message):
    print(f"fluidem_plot: {message}", file=sys.stderr)
    sys.exit(2)


def parse_args(argv):
    p = argparse.ArgumentParser(description="Snapshot picture of a fluidem run.")
    p.add_argument("outdir", help="run output directory (holds particles.h5, series.csv)")
    p.add_argument("--frame", type=int, default=-1, help="frame index, negative from the end")
    p.add_argument("--color-by", choices=["species", "speed", "id"], default="species")
    p.add_argument("--out", default=None, help="PNG to write (default OUTDIR/snapshot.png)")
    return p.parse_args(argv)


def read_frame(h5_path, frame):
    import h5py

    try:
        f = h5py.File(h5_path, "r")
    except OSError as e:
        fail(f"cannot open {h5_path}: {e}")
    with f:
        try:
            all_ = f["particles/all"]
            pos = all_["position/value"]
            n_frames = pos.shape[0]
            if n_frames == 0:
                fail(f"{h5_path} holds no frame yet")
            k = frame + n_frames if frame < 0 else frame
            if not 0 <= k < n_frames:
                fail(f"frame {frame} out of range: {h5_path} holds {n_frames} frames")
            d = {
                "frame": k,
                "frames": n_frames,
                "position": np.asarray(pos[k], dtype=float),
                "velocity": np.asarray(all_["velocity/value"][k], dtype=float),
                "radius": np.asarray(all_["radius/value"][k], dtype=float),
                "species": np.asarray(all_["species/value"][k]),
                "id": np.asarray(all_["id/value"][k]),
                "time": float(all_["position/time"][k]),
                "step": int(all_["position/step"][k]),
                "box": None,
            }
            if "box/edges" in all_:
                edges = np.asarray(all_["box/edges"], dtype=float)
                offset = (
                    np.asarray(all_["box/offset"], dtype=float)
                    if "box/offset" in all_
                    else np.zeros(3)
                )
                if edges.shape == (3,) and np.all(edges > 0):
                    d["box"] = (offset, offset + edges)
            return d
        except KeyError as e:
            fail(f"{h5_path} is not a fluidem H5MD particle file (missing {e})")


def read_series(csv_path):
    """Columns of series.csv as a dict of arrays, or None when absent or empty."""
    if not os.path.exists(csv_path):
        return None
    try:
        data = np.genfromtxt(csv_path, delimiter=",", names=True, dtype=float, ndmin=1)
    except (ValueError, OSError) as e:
        print(f"fluidem_plot: ignoring {csv_path}: {e}", file=sys.stderr)
        return None
    if data.dtype.names is None or data.size == 0 or "time" not in data.dtype.names:
        return None
    return {name: np.atleast_1d(data[name]) for name in data.dtype.names}


def draw_particles(ax, fig, d, color_by):
    pos, r = d["position"], d["radius"]
    n_total = len(r)
    title_extra = ""
    keep = np.ones(n_total, dtype=bool)
    if n_total > 0 and np.ptp(pos[:, 1]) > 0.0:
        r_max = float(r.max())
        if d["box"] is not None:
            y_mid = 0.5 * (d["box"][0][1] + d["box"][1][1])
        else:
            y_mid = 0.5 * (pos[:, 1].min() + pos[:, 1].max())
        keep = np.abs(pos[:, 1] - y_mid) < 2.0 * r_max
        title_extra = f"\nslab |y - y_mid| < 2 r_max: {int(keep.sum())} of {n_total} particles"

    x_mm = pos[keep, 0] * 1e3
    z_mm = pos[keep, 2] * 1e3
    r_mm = r[keep] * 1e3
    circles = [Circle((x, z), rr) for x, z, rr in zip(x_mm, z_mm, r_mm)]
    coll = PatchCollection(circles, linewidths=0.2, edgecolors="k")

    if color_by == "species":
        species = d["species"][keep].astype(int)
        kinds = np.unique(d["species"].astype(int))
        cmap = plt.get_cmap("tab10")
        index = {s: i for i, s in enumerate(kinds)}
        coll.set_facecolor([cmap(index[s] % 10) for s in species])
        handles = [Patch(facecolor=cmap(index[s] % 10), edgecolor="k", label=f"species {s}")
                   for s in kinds]
        if 1 < len(kinds) <= 10:
            ax.legend(handles=handles, loc="upper right", fontsize="small")
    else:
        if color_by == "speed":
            values = np.linalg.norm(d["velocity"][keep], axis=1)
            label = "speed (m/s)"
        else:
            values = d["id"][keep].astype(float)
            label = "id"
        coll.set_array(values)
        coll.set_cmap("viridis")
        fig.colorbar(coll, ax=ax, label=label, shrink=0.8)
    ax.add_collection(coll)

    if d["box"] is not None:
        lo, hi = d["box"]
        ax.add_patch(Rectangle((lo[0] * 1e3, lo[2] * 1e3), (hi[0] - lo[0]) * 1e3,
                               (hi[2] - lo[2]) * 1e3, fill=False, edgecolor="0.3", linewidth=0.8))
        ax.set_xlim(lo[0] * 1e3, hi[0] * 1e3)
        ax.set_ylim(lo[2] * 1e3, hi[2] * 1e3)
    elif len(r_mm) > 0:
        pad = float(r_mm.max())
        ax.set_xlim(float((x_mm - r_mm).min()) - pad, float((x_mm + r_mm).max()) + pad)
        ax.set_ylim(float((z_mm - r_mm).min()) - pad, float((z_mm + r_mm).max()) + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("z (mm)")
    ax.set_title(f"t = {d['time']:.6g} s (step {d['step']}, frame {d['frame'] + 1} of "
                 f"{d['frames']}, coloured by {color_by}){title_extra}", fontsize="medium")


def draw_energies(ax, series, t_now):
    t = series["time"]
    present = [c for c in ENERGY_COLUMNS if c in series]
    if not present:
        ax.text(0.5, 0.5, "series.csv has no energy column", ha="center", va="center",
                transform=ax.transAxes)
        return
    total = np.zeros_like(t)
    for c in present:
        ax.plot(t, series[c], label=f"{c} ({ENERGY_LABELS[c]})", linewidth=1.0)
        total = total + series[c]
    ax.plot(t, total, label="total", color="k", linewidth=1.5)
    ax.axvline(t_now, color="0.5", linestyle=":", linewidth=1.0)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("energy (J)")
    ax.set_title("energies")
    ax.legend(fontsize="small")
    ax.grid(True, alpha=0.3)


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    h5_path = os.path.join(args.outdir, "particles.h5")
    if not os.path.isfile(h5_path):
        fail(f"no such file: {h5_path} (is {args.outdir} a fluidem output directory?)")
    d = read_frame(h5_path, args.frame)
    series = read_series(os.path.join(args.outdir, "series.csv"))

    if series is not None:
        fig, (ax_p, ax_e) = plt.subplots(1, 2, figsize=(13, 6.5),
                                         gridspec_kw={"width_ratios": [1.0, 1.1]})
    else:
        fig, ax_p = plt.subplots(figsize=(7, 7))
        ax_e = None
    draw_particles(ax_p, fig, d, args.color_by)
    if ax_e is not None:
        draw_energies(ax_e, series, d["time"])
    fig.tight_layout()
    out = args.out if args.out else os.path.join(args.outdir, "snapshot.png")
    fig.savefig(out, dpi=150)
    plt.close(fig)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
