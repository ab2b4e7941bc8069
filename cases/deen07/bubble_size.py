#!/usr/bin/python3
"""Bubble size after the jet of a single_bubble*.toml run [Deen07 §6.1, Fig. 8].

usage: /usr/bin/python3 cases/deen07/bubble_size.py OUT [--start T_JET] [--eps 0.8]

For each frame of OUT/fields.h5: the bubble is the set of gas cells with porosity above --eps
(0.8) below the bed surface (the highest cell row whose mean porosity is below --eps). Prints and
writes OUT/bubble.csv: time, time after injection, bubble area (m^2, x-z plane), equivalent
diameter sqrt(4 A / pi), width and height of the cells' bounding box, bed surface height (m).
--start defaults to the jet region's pulse start in OUT/case.resolved.toml.
"""
import sys
import tomllib

import h5py
import numpy as np

out = sys.argv[1] if len(sys.argv) > 1 else sys.exit(__doc__)
thr = float(sys.argv[sys.argv.index("--eps") + 1]) if "--eps" in sys.argv else 0.8
if "--start" in sys.argv:
    t0 = float(sys.argv[sys.argv.index("--start") + 1])
else:
    with open(f"{out}/case.resolved.toml", "rb") as f:
        case = tomllib.load(f)
    t0 = [r for r in case["gas"]["boundary"]["bottom"]["region"] if r.get("mode") == "pulse"][0]["start"]
with h5py.File(f"{out}/fields.h5", "r") as f:
    eps = f["fields/porosity"][:]
    time = f["fields/time"][:]
    dx, _, dz = f["grid/spacing"][:]
with open(f"{out}/bubble.csv", "w") as o:
    o.write("time,after_injection,area,equivalent_diameter,width,height,bed_surface\n")
    for k in range(len(time)):
        e = eps[k].mean(axis=1)  # (z, x), averaged over the cells across y
        rows = np.where(e.mean(axis=1) < thr)[0]
        top = rows.max() + 1 if len(rows) else 0
        b = e[:top, :] > thr
        area = b.sum() * dx * dz
        w = h = 0.0
        if b.any():
            zz, xx = np.where(b)
            w, h = (xx.max() - xx.min() + 1) * dx, (zz.max() - zz.min() + 1) * dz
        line = f"{time[k]:.4f},{time[k] - t0:.4f},{area:.6g},{np.sqrt(4 * area / np.pi):.4f},{w:.4f},{h:.4f},{top * dz:.4f}"
        o.write(line + "\n")
        if time[k] >= t0 and abs(((time[k] - t0) * 100) - round((time[k] - t0) * 100)) < 1e-6:
            print(line)
