#!/usr/bin/python3
"""Snapshot picture of a fluidem run.

Usage: /usr/bin/python3 python/fluidem_plot.py OUTDIR [--frame -1]
                                   [--color-by|--color species|speed|id|layer] [--out PNG]

Reads OUTDIR/particles.h5 (H5MD, written by fluidem's H5mdWriter) and draws one frame's particles
as circles of their true radius in the x-z plane (axes in mm). For 3-D data (a spread in y) only
the particles of the slab |y - y_mid| < 2 r_max are drawn (y_mid: middle of the box, or of the
particles when the file has no box), and the title says so. If OUTDIR/series.csv exists, a second
panel shows the energies over time (the columns e_kin, e_rot, e_pot, e_el, e_dsp that are present,
and their sum, "total"). Writes OUTDIR/snapshot.png unless --out is given.

Colours (--color-by, or its synonym --color): "species" (one colour per species), "speed" or "id"
(a colour bar), "layer": the horizontal layer of the initial bed each particle started in
(/particles/all/layer, written when the case sets output.layers > 0), drawn as alternating black
and white bands like the coloured layers of [Hoomans96 Figs. 10, 12], to show mixing. The default
is "layer" when the file holds layers, else "species"; "layer" on a file without them exits 2.

Coupled runs (with a gas phase) add:
  * OUTDIR/fields.h5 (FieldsWriter): a panel next to the particles with the porosity (gas volume
    fraction) of the same frame, the x-z slice through the middle cell row in y (the only one in
    2-D), cells drawn at their true size on the particle panel's axes (mm), with sparse arrows of
    the gas velocity (x and z components, interstitial) when /fields/gas_velocity is present;
    arrows faster than the 95th percentile of the slice's speeds are drawn at that length, in red.
  * series.csv columns pressure_drop / OUTDIR/probes.csv: the time-series column becomes a stack
    of panels: the pressure drop over the bed (kPa), the probe pressures (kPa, relative to each
    probe's time mean over the whole file, the mean given in the legend), then the particle
    energies, titled as such: the gas does work on the particles, so their total is not conserved.
A run without fields.h5, probes.csv and pressure_drop is drawn exactly as before.

Exit codes: 0 done, 2 bad input in particles.h5 (missing file, frame out of range, malformed file).
A bad fields.h5 (unreadable, a missing or misshapen dataset among /grid/cells, /grid/lo,
/grid/spacing, /fields/time, /fields/porosity, a frame count different from particles.h5's, or a
different time for the frame drawn) does not stop the picture: the porosity panel is left out,
with "fluidem_plot: warning: ..." on stderr, and the exit code stays 0 (the particles alone can
still be drawn; a live run may have written one file's frame and not yet the other's). A bad
/fields/gas_velocity only drops the arrows (same warning); an unreadable series.csv or
probes.csv only drops its curves (a message on stderr).
"""
import argparse
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: E402
    import numpy as np  # noqa: E402
    from matplotlib.collections import PatchCollection  # noqa: E402
    from matplotlib.patches import Circle, Patch, Rectangle  # noqa: E402
except ImportError as e:
    sys.exit(
        f"fluidem_plot: {e.name or 'a module'} is missing: install python3-matplotlib and "
        "python3-numpy (apt-get) and run with /usr/bin/python3"
    )

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


def warn(message):
    print(f"fluidem_plot: warning: {message}", file=sys.stderr)


def parse_args(argv):
    p = argparse.ArgumentParser(description="Snapshot picture of a fluidem run.")
    p.add_argument("outdir",
                   help="run output directory (holds particles.h5, series.csv; fields.h5, "
                        "probes.csv for coupled runs)")
    p.add_argument("--frame", type=int, default=-1, help="frame index, negative from the end")
    p.add_argument("--color-by", "--color", dest="color_by",
                   choices=["species", "speed", "id", "layer"], default=None,
                   help="particle colours (default: layer when the file holds layers, else "
                        "species)")
    p.add_argument("--out", default=None, help="PNG to write (default OUTDIR/snapshot.png)")
    p.add_argument("--dpi", type=float, default=150.0, help="resolution of the PNG (dots per inch)")
    p.add_argument("--movie", action="store_true",
                   help="draw every frame (or every --every-th) to OUTDIR/movie_frames/ and "
                        "join them into OUTDIR/movie.mp4 with ffmpeg")
    p.add_argument("--every", type=int, default=1, help="with --movie: every N-th frame")
    p.add_argument("--fps", type=float, default=20.0, help="with --movie: frames per second")
    a = p.parse_args(argv)
    if a.every < 1:
        p.error(f"--every {a.every}: must be at least 1")
    if not a.fps > 0:
        p.error(f"--fps {a.fps}: must be positive")
    return a


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
                "layer": (np.asarray(all_["layer/value"][k]) if "layer/value" in all_ else None),
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


class FieldsError(Exception):
    """fields.h5 cannot be drawn with the particles (the panel is skipped)."""


def read_fields(h5_path, d):
    """The porosity (and gas velocity) of the y-middle x-z slice of fields.h5 at particle frame
    d["frame"], checked against particles.h5 (frame count and time). Returns a dict with
    "porosity" [nz][nx], "x_edges", "z_edges" (m), "gas_velocity" [nz][nx][2] (x, z) or None,
    "j", "ny", "y" (centre of the slice, m), "cells". Raises FieldsError."""
    import h5py

    try:
        f = h5py.File(h5_path, "r")
    except OSError as e:
        raise FieldsError(f"cannot open {h5_path}: {e}")
    with f:
        def get(name):
            if name not in f or not isinstance(f[name], h5py.Dataset):
                raise FieldsError(f"{h5_path} has no dataset /{name}")
            return f[name]

        try:
            cells = np.asarray(get("grid/cells")[()])
            lo = np.asarray(get("grid/lo")[()], dtype=float)
            spacing = np.asarray(get("grid/spacing")[()], dtype=float)
            if cells.shape != (3,) or lo.shape != (3,) or spacing.shape != (3,):
                raise FieldsError(f"{h5_path}: /grid/cells, /grid/lo and /grid/spacing must hold "
                                  "3 values each")
            if np.any(cells < 1) or not np.all(np.isfinite(lo)) or not np.all(spacing > 0):
                raise FieldsError(f"{h5_path}: bad grid (cells {cells.tolist()}, spacing "
                                  f"{spacing.tolist()})")
            nx, ny, nz = (int(c) for c in cells)
            times = np.asarray(get("fields/time")[()], dtype=float).reshape(-1)
            por = get("fields/porosity")
            n_frames = len(times)
            if n_frames != d["frames"]:
                raise FieldsError(f"{h5_path} holds {n_frames} frames, particles.h5 holds "
                                  f"{d['frames']} (frames are written at the same times)")
            if por.shape != (n_frames, nz, ny, nx):
                raise FieldsError(f"/fields/porosity in {h5_path} has shape {por.shape}, "
                                  f"expected {(n_frames, nz, ny, nx)} (frames, nz, ny, nx)")
            k = d["frame"]
            t = float(times[k])
            if abs(t - d["time"]) > 1e-9 * max(1.0, abs(d["time"])):
                raise FieldsError(f"frame {k} of {h5_path} is at t = {t:.9g} s, the particles' "
                                  f"at t = {d['time']:.9g} s")
            j = ny // 2
            out = {
                "porosity": np.asarray(por[k, :, j, :], dtype=float),
                "x_edges": lo[0] + spacing[0] * np.arange(nx + 1),
                "z_edges": lo[2] + spacing[2] * np.arange(nz + 1),
                "j": j,
                "ny": ny,
                "y": lo[1] + spacing[1] * (j + 0.5),
                "cells": (nx, ny, nz),
                "gas_velocity": None,
            }
            if "fields/gas_velocity" in f:
                u = f["fields/gas_velocity"]
                if isinstance(u, h5py.Dataset) and u.shape == (n_frames, nz, ny, nx, 3):
                    out["gas_velocity"] = np.asarray(u[k, :, j, :, :], dtype=float)[:, :, [0, 2]]
                else:
                    warn(f"/fields/gas_velocity in {h5_path} has shape "
                         f"{getattr(u, 'shape', None)}, expected {(n_frames, nz, ny, nx, 3)}; "
                         "no gas velocity arrows")
            return out
        except (OSError, KeyError, ValueError, TypeError) as e:
            raise FieldsError(f"cannot read {h5_path}: {e}")


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


# Alternating colours of the initial layers (layer 0 at the bottom is black).
LAYER_COLOURS = ("black", "white")


def draw_particles(ax, fig, d, color_by, narrow=False):
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

    if color_by == "layer":
        layer = d["layer"][keep].astype(int)
        coll.set_facecolor([LAYER_COLOURS[k % 2] for k in layer])
        n_layers = int(d["layer"].max()) + 1 if len(d["layer"]) > 0 else 0
        handles = [Patch(facecolor=LAYER_COLOURS[k], edgecolor="k",
                         label=f"{'even' if k == 0 else 'odd'} layers") for k in (0, 1)]
        ax.legend(handles=handles, loc="upper right", fontsize="small",
                  title=f"{n_layers} initial layers", title_fontsize="small")
    elif color_by == "species":
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
    sep = ")\n(" if narrow else ", "  # narrow: a tall panel next to the porosity map
    ax.set_title(f"t = {d['time']:.6g} s (step {d['step']}{sep}frame {d['frame'] + 1} of "
                 f"{d['frames']}, coloured by {color_by}){title_extra}", fontsize="medium")


def draw_porosity(ax, fig, fd, ax_particles, has_box):
    """Porosity map of the slice fd (read_fields) on ax, same axes (mm) as ax_particles."""
    xe, ze = fd["x_edges"] * 1e3, fd["z_edges"] * 1e3
    eps = fd["porosity"]
    finite = eps[np.isfinite(eps)]
    vmin = min(0.3, float(finite.min())) if finite.size else 0.3
    mesh = ax.pcolormesh(xe, ze, eps, cmap="viridis", vmin=vmin, vmax=1.0, shading="flat")
    mesh.set_label("porosity")
    fig.colorbar(mesh, ax=ax, label="gas volume fraction", shrink=0.8)

    title, arrows = "porosity", ""
    if fd["gas_velocity"] is not None:
        title += " and gas velocity"
        u = fd["gas_velocity"]
        nz, nx = eps.shape
        dx, dz = xe[1] - xe[0], ze[1] - ze[0]
        # About 20 arrows along the longer side, the same spacing in x and z where possible.
        target = max(nx * dx, nz * dz) / 20.0
        sx = max(1, int(round(target / dx)))
        sz = max(1, int(round(target / dz)))
        xc = 0.5 * (xe[:-1] + xe[1:])
        zc = 0.5 * (ze[:-1] + ze[1:])
        ix, iz = np.arange(sx // 2, nx, sx), np.arange(sz // 2, nz, sz)
        X, Z = np.meshgrid(xc[ix], zc[iz])
        U = u[np.ix_(iz, ix)]
        speed = np.hypot(U[..., 0], U[..., 1])
        ok = np.isfinite(speed) & (speed > 0)
        if np.any(ok):
            # Arrow length: linear up to u_ref (95th percentile of the slice's nonzero speeds),
            # longer ones are drawn at u_ref length, in red. u_ref is one arrow spacing long.
            u_ref = float(np.percentile(speed[ok], 95))
            if u_ref <= 0:
                u_ref = float(speed[ok].max())
            factor = np.where(speed > u_ref, u_ref / np.where(speed > 0, speed, 1.0), 1.0)
            capped = ok & (speed > u_ref * (1 + 1e-12))
            spacing_mm = min(sx * dx, sz * dz)
            scale = u_ref / (0.9 * spacing_mm)  # data units (m/s) per mm of arrow
            for sel, colour in ((ok & ~capped, "white"), (capped, "red")):
                if np.any(sel):
                    ax.quiver(X[sel], Z[sel], (U[..., 0] * factor)[sel],
                                  (U[..., 1] * factor)[sel], color=colour, angles="xy",
                                  scale_units="xy", scale=scale, pivot="mid", width=0.006,
                                  edgecolor="k" if colour == "white" else colour, linewidth=0.3)
            arrows = (f"\narrows: gas velocity, {u_ref:.3g} m/s = {u_ref / scale:.3g} mm"
                      + ("\n(red: faster, shortened)" if np.any(capped) else ""))
    nx, ny, nz = fd["cells"]
    where = "" if ny == 1 else f"\ny slice: cell j = {fd['j']} of {ny} (y = {fd['y'] * 1e3:.4g} mm)"
    ax.set_title(f"{title} ({nx} x {ny} x {nz} cells){where}{arrows}", fontsize="medium")
    if has_box:
        ax.set_xlim(ax_particles.get_xlim())
        ax.set_ylim(ax_particles.get_ylim())
    else:
        # No box in particles.h5: the gas grid is the domain; show it on both panels.
        for a in (ax, ax_particles):
            a.set_xlim(xe[0], xe[-1])
            a.set_ylim(ze[0], ze[-1])
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("z (mm)")


def draw_energies(ax, series, t_now, coupled=False):
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
    if coupled:
        ax.set_title("particle energies (the gas does work on the particles: "
                     "the total is not conserved)", fontsize="medium")
    else:
        ax.set_title("energies")
    ax.legend(fontsize="small")
    ax.grid(True, alpha=0.3)


def draw_pressure_drop(ax, series, t_now):
    ax.plot(series["time"], series["pressure_drop"] * 1e-3, color="C0", linewidth=1.0)
    ax.axvline(t_now, color="0.5", linestyle=":", linewidth=1.0)
    ax.set_ylabel("pressure drop (kPa)")
    ax.set_title("pressure drop over the bed (series.csv pressure_drop)", fontsize="medium")
    ax.grid(True, alpha=0.3)


def draw_probes(ax, probes, t_now):
    t = probes["time"]
    for c in (c for c in probes if c != "time"):
        p = probes[c]
        mean = float(np.nanmean(p)) if np.any(np.isfinite(p)) else float("nan")
        ax.plot(t, (p - mean) * 1e-3, linewidth=1.0, label=f"{c} (mean {mean * 1e-3:.6g} kPa)")
    ax.axvline(t_now, color="0.5", linestyle=":", linewidth=1.0)
    ax.set_ylabel("p - time mean (kPa)")
    ax.set_title("probe pressures relative to their time mean (probes.csv)", fontsize="medium")
    ax.legend(fontsize="small")
    ax.grid(True, alpha=0.3)


def make_figure(args):
    """The figure for parsed arguments `args` (axes labelled "particles", "porosity",
    "pressure_drop", "probes", "energies" for tests), and the frame drawn (read_frame)."""
    h5_path = os.path.join(args.outdir, "particles.h5")
    if not os.path.isfile(h5_path):
        fail(f"no such file: {h5_path} (is {args.outdir} a fluidem output directory?)")
    d = read_frame(h5_path, args.frame)
    if args.color_by is None:
        args.color_by = "layer" if d["layer"] is not None else "species"
    elif args.color_by == "layer" and d["layer"] is None:
        fail(f"{h5_path} holds no layers (/particles/all/layer; set output.layers in the case)")
    series = read_series(os.path.join(args.outdir, "series.csv"))

    fd = None
    fields_path = os.path.join(args.outdir, "fields.h5")
    if os.path.exists(fields_path):
        try:
            fd = read_fields(fields_path, d)
        except FieldsError as e:
            warn(f"{e}; drawing the particles without the porosity panel")
    probes = read_series(os.path.join(args.outdir, "probes.csv"))
    if probes is not None and len(probes) < 2:
        probes = None
    has_dp = series is not None and "pressure_drop" in series
    coupled = has_dp or probes is not None or fd is not None
    rows = []  # time-series panels, top to bottom
    if has_dp:
        rows.append("pressure_drop")
    if probes is not None:
        rows.append("probes")
    if series is not None:
        rows.append("energies")

    if fd is None and not coupled:  # granular run: as before
        if series is not None:
            fig, (ax_p, ax_e) = plt.subplots(1, 2, figsize=(13, 6.5),
                                             gridspec_kw={"width_ratios": [1.0, 1.1]})
        else:
            fig, ax_p = plt.subplots(figsize=(7, 7))
            ax_e = None
        ax_p.set_label("particles")
        draw_particles(ax_p, fig, d, args.color_by)
        if ax_e is not None:
            ax_e.set_label("energies")
            draw_energies(ax_e, series, d["time"])
        return fig, d

    # Panel widths from the width/height of the picture (box, else gas grid, else particles),
    # so that the true-aspect maps do not float in white space.
    if d["box"] is not None:
        extent = d["box"][1] - d["box"][0]
    elif fd is not None:
        extent = np.array([fd["x_edges"][-1] - fd["x_edges"][0], 0.0,
                           fd["z_edges"][-1] - fd["z_edges"][0]])
    elif len(d["radius"]) > 0:
        extent = np.ptp(d["position"], axis=0) + 4.0 * float(d["radius"].max())
    else:
        extent = np.ones(3)
    aspect = float(extent[0] / extent[2]) if extent[2] > 0 and extent[0] > 0 else 1.0
    map_height = 6.3  # inches, of a figure 8 inches high
    map_width = float(np.clip(map_height * aspect, 3.0, 9.0)) + 1.0  # + tick labels
    colour_bar = 1.3
    widths = [map_width + (colour_bar if args.color_by not in ("species", "layer") else 0.0)]
    if fd is not None:
        widths.append(map_width + colour_bar)
    if rows:
        widths.append(7.5)
    fig = plt.figure(figsize=(sum(widths), 8.0), layout="constrained")
    gs = fig.add_gridspec(1, len(widths), width_ratios=widths)
    ax_p = fig.add_subplot(gs[0, 0], label="particles")
    draw_particles(ax_p, fig, d, args.color_by, narrow=True)
    if fd is not None:
        ax_f = fig.add_subplot(gs[0, 1], label="porosity")
        draw_porosity(ax_f, fig, fd, ax_p, d["box"] is not None)
    if rows:
        sub = gs[0, -1].subgridspec(len(rows), 1)
        first = None
        for i, name in enumerate(rows):
            ax = fig.add_subplot(sub[i, 0], label=name, sharex=first)
            first = first or ax
            if name == "pressure_drop":
                draw_pressure_drop(ax, series, d["time"])
            elif name == "probes":
                draw_probes(ax, probes, d["time"])
            else:
                draw_energies(ax, series, d["time"], coupled=True)
            if i + 1 < len(rows):
                ax.tick_params(labelbottom=False)
                ax.set_xlabel("")
            else:
                ax.set_xlabel("time (s)")
    return fig, d


def make_movie(args):
    """Every --every-th frame as OUTDIR/movie_frames/frame_NNNNN.png (the snapshot's layout,
    at 80 dpi), then OUTDIR/movie.mp4 (H.264, even pixel sizes) when ffmpeg is installed. Without
    ffmpeg the frames stay and the exit code is 3, with the command to install it."""
    import shutil
    import subprocess

    frames_dir = os.path.join(args.outdir, "movie_frames")
    os.makedirs(frames_dir, exist_ok=True)
    for old in os.listdir(frames_dir):
        if old.startswith("frame_") and old.endswith(".png"):
            os.remove(os.path.join(frames_dir, old))
    args.frame = 0
    colour = args.color_by
    n_frames = None
    k = 0
    written = 0
    while n_frames is None or k < n_frames:
        args.frame = k
        args.color_by = colour
        fig, d = make_figure(args)
        n_frames = d["frames"]
        if fig.get_layout_engine() is None:
            fig.tight_layout()
        fig.savefig(os.path.join(frames_dir, f"frame_{written:05d}.png"), dpi=80)
        plt.close(fig)
        written += 1
        k += args.every
    print(f"{written} frames in {frames_dir}")
    ffmpeg = shutil.which("ffmpeg")
    if ffmpeg is None:
        print("fluidem_plot: ffmpeg is not installed (Debian: apt-get install ffmpeg); the frames "
              f"are in {frames_dir}, no movie written", file=sys.stderr)
        return 3
    movie = os.path.join(args.outdir, "movie.mp4")
    cmd = [ffmpeg, "-loglevel", "error", "-y", "-framerate", str(args.fps), "-i",
           os.path.join(frames_dir, "frame_%05d.png"), "-vf",
           "scale=trunc(iw/2)*2:trunc(ih/2)*2", "-pix_fmt", "yuv420p", "-c:v", "libx264", movie]
    if subprocess.run(cmd).returncode != 0:
        print(f"fluidem_plot: ffmpeg failed: {' '.join(cmd)}", file=sys.stderr)
        return 1
    print(movie)
    return 0


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    if args.movie:
        return make_movie(args)
    fig, _ = make_figure(args)
    if fig.get_layout_engine() is None:  # the coupled layout is constrained already
        fig.tight_layout()
    out = args.out if args.out else os.path.join(args.outdir, "snapshot.png")
    fig.savefig(out, dpi=args.dpi)
    plt.close(fig)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
