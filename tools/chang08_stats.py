#!/usr/bin/env python3
"""Table 1 of [Chang08] from a fluidem run of cases/chang08/*.toml.

usage: chang08_stats.py OUT_DIR [--from T0] [--length L]

Averages over the particle frames with t >= T0 (default 10 s) and over the series.csv rows:
  whole domain: global void fraction, mean and rms fluctuating x velocity of all particles,
                collision frequency f = 2 (pair collisions in [T0, t_end]) / (N (t_end - T0))
                (each collision involves two particles: f is collisions per particle per second);
  GC, CC:       spheres of radius 0.1 L around (L/2, L/2, L/2) and around both (L/4, L/4, L/4)
                and (3L/4, 3L/4, 3L/4) (periodic images), the particles whose centre lies inside
                [Chang08]: local void fraction 1 - sum V_p / V_cell, mean u_x, rms u'_x (about the
                region's mean over all samples).
With `output.collisions = true` (OUT/collisions.csv, regions named GC, CC1, CC2) it also gives
f per region: f = sum_rows(f_row N_row) / sum_rows(N_row) over the rows with t > T0 (= 2 C / (<N> T)
over the whole averaging time; CC: CC1 and CC2 together), and the regions' void fraction as the
statistics count it at every step (column eps_steps).
"""
import argparse
import csv
import math
import sys

import h5py
import numpy as np


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--from", dest="t0", type=float, default=10.0)
    ap.add_argument("--length", type=float, default=0.1)
    a = ap.parse_args()
    L = a.length
    with h5py.File(f"{a.out}/particles.h5", "r") as f:
        g = f["particles/all"]
        t = np.asarray(g["position/time"])
        pos = np.asarray(g["position/value"])
        vel = np.asarray(g["velocity/value"])
        rad = np.asarray(g["radius/value"])
    if rad.ndim > 1:
        rad = rad[0]
    sel = t >= a.t0 - 1e-9
    if not sel.any():
        sys.exit(f"no frames at t >= {a.t0}")
    pos, vel = pos[sel], vel[sel]
    n = pos.shape[1]
    vp = 4.0 / 3.0 * math.pi * rad**3
    rc = 0.1 * L
    vcell = 4.0 / 3.0 * math.pi * rc**3
    out = {}
    u_all = vel[:, :, 0]
    out["whole domain"] = dict(
        eps=1.0 - vp.sum() / L**3, u=u_all.mean(), urms=u_all.std(), nframes=len(pos))
    centres = {"GC": [[L / 2] * 3], "CC": [[L / 4] * 3, [3 * L / 4] * 3]}
    for name, cs in centres.items():
        fr, us = [], []
        for c in cs:
            d = pos - np.asarray(c)
            d -= L * np.round(d / L)
            inside = (d**2).sum(axis=2) < rc**2
            fr += list((inside * vp).sum(axis=1) / vcell)
            us += list(vel[:, :, 0][inside])
        us = np.asarray(us)
        out[name] = dict(eps=1.0 - np.mean(fr), u=us.mean() if us.size else float("nan"),
                         urms=us.std() if us.size else float("nan"),
                         count=np.mean(fr) * vcell / vp.mean())
    with open(f"{a.out}/series.csv") as f:
        rows = [r for r in csv.DictReader(f)]
    tt = np.array([float(r["time"]) for r in rows])
    nc = np.array([float(r["n_collisions"]) for r in rows])
    k0 = np.searchsorted(tt, a.t0 - 1e-9)
    freq = 2.0 * (nc[-1] - nc[k0]) / (n * (tt[-1] - tt[k0]))
    out["whole domain"]["f"] = freq
    try:
        with open(f"{a.out}/collisions.csv") as f:
            crow = [r for r in csv.DictReader(f) if float(r["time"]) > a.t0 + 1e-9]
    except FileNotFoundError:
        crow = []
    if crow:
        out["whole domain"]["f_csv"] = np.mean([float(r["collision_frequency"]) for r in crow])
        for name, cols in {"GC": ["GC"], "CC": ["CC1", "CC2"]}.items():
            fn = sum(float(r[c + "_collision_frequency"]) * float(r[c + "_particles"])
                     for r in crow for c in cols
                     if math.isfinite(float(r[c + "_collision_frequency"])))
            nn = sum(float(r[c + "_particles"]) for r in crow for c in cols)
            out[name]["f"] = fn / nn if nn > 0 else float("nan")
            out[name]["eps_steps"] = np.mean([float(r[c + "_void_fraction"])
                                              for r in crow for c in cols])
    print(f"frames {out['whole domain']['nframes']} from t = {a.t0} s to {tt[-1]:.3g} s, "
          f"N = {n}")
    print(f"{'region':14s} {'u_x (m/s)':>11s} {'u_x rms':>10s} {'eps':>7s} {'eps_steps':>9s} "
          f"{'f (1/s)':>9s} {'particles':>9s}")
    for name, r in out.items():
        print(f"{name:14s} {r['u']:11.3e} {r['urms']:10.3e} {r['eps']:7.3f} "
              f"{r.get('eps_steps', float('nan')):9.3f} {r.get('f', float('nan')):9.3f} "
              f"{r.get('count', n):9.2f}")
    if "f_csv" in out["whole domain"]:
        print(f"whole-domain f from collisions.csv: {out['whole domain']['f_csv']:.3f} 1/s")


if __name__ == "__main__":
    main()
