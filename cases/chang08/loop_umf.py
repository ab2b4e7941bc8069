#!/usr/bin/python3
"""Pressure drop - superficial velocity loop of a spouted_loop.toml run [Chang08 §3.4, Fig. 3.17].

usage: /usr/bin/python3 cases/chang08/loop_umf.py OUT [--ratio 15] [--bin 0.1]

Reads OUT/case.resolved.toml (the bottom face's velocity table: the nozzle's superficial velocity,
ratio x U0) and OUT/series.csv (pressure_drop). Writes OUT/loop.csv (U0 bin centre, mean pressure
drop on the rising branch, on the falling branch, in Pa and over the bed weight per area W) and
prints, also as OUT/loop_summary.csv (name,value,unit):
  u_mf_C          the point C of Chang, "the interception of the loop as increasing the gas
                  velocity and the loop as decreasing": the first crossing of the two branches above
                  the rising branch's peak (point B);
  u_mf_ergun      the usual construction on the falling branch: the fixed-bed points (below 70% of
                  the fluidised plateau) fitted by dP = a U + b U^2, intersected with the plateau;
  plateau_over_W  mean pressure drop over both branches at U0 >= 0.75 of the highest U0 (3.0 m/s), over W;
  peak_over_W     highest bin of the rising branch (point B), over W.
"""
import csv
import math
import sys
import tomllib


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    out = argv[1]
    ratio = float(argv[argv.index("--ratio") + 1]) if "--ratio" in argv else 15.0
    width = float(argv[argv.index("--bin") + 1]) if "--bin" in argv else 0.1
    with open(f"{out}/case.resolved.toml", "rb") as f:
        case = tomllib.load(f)
    bottom = case["gas"]["boundary"]["bottom"]
    times, vels = bottom["times"], bottom["velocities"]
    sp = case["species"][0]
    lo, hi = case["domain"]["lo"], case["domain"]["hi"]
    area = (hi[0] - lo[0]) * (hi[1] - lo[1])

    def u0(t):
        if t <= times[0]:
            return vels[0] / ratio
        for k in range(1, len(times)):
            if t <= times[k]:
                w = (t - times[k - 1]) / (times[k] - times[k - 1])
                return ((1 - w) * vels[k - 1] + w * vels[k]) / ratio
        return vels[-1] / ratio

    t_peak = times[max(range(len(vels)), key=lambda k: vels[k])]
    rows = list(csv.DictReader(open(f"{out}/series.csv")))
    # the bed mass from the first row: e_pot = m g z_cm with z_cm = bed_height / 2
    e_pot0 = float(rows[0]["e_pot"])
    h0 = float(rows[0]["bed_height"])
    g = abs(case["simulation"]["gravity"][2])
    mass = e_pot0 / (g * h0 / 2.0)
    rho_g = case["gas"].get("density", 1.2)
    W = mass * g * (1.0 - rho_g / sp["density"]) / area
    nb = int(math.ceil(max(vels) / ratio / width)) + 1
    up = [[0.0, 0] for _ in range(nb)]
    down = [[0.0, 0] for _ in range(nb)]
    for r in rows:
        t = float(r["time"])
        u = u0(t)
        b = min(nb - 1, int(u / width))
        acc = up if t <= t_peak else down
        acc[b][0] += float(r["pressure_drop"])
        acc[b][1] += 1
    mean = lambda a: a[0] / a[1] if a[1] else float("nan")
    with open(f"{out}/loop.csv", "w") as f:
        f.write("superficial_velocity,dp_up,dp_down,dp_up_over_W,dp_down_over_W\n")
        for b in range(nb):
            u, du, dd = (b + 0.5) * width, mean(up[b]), mean(down[b])
            f.write(f"{u:.3f},{du:.6g},{dd:.6g},{du / W:.4f},{dd / W:.4f}\n")
    ub = [(b + 0.5) * width for b in range(nb)]
    plateau_vals = [mean(a) for b in range(nb) for a in (up[b], down[b]) if ub[b] >= 0.75 * max(vels) / ratio and a[1]]
    plateau = sum(plateau_vals) / len(plateau_vals)
    # point C: the first crossing, above the rising branch's peak (point B), of the rising and
    # falling branches (rising - falling changes sign), linear between bin centres
    umf_c = float("nan")
    both = [b for b in range(nb) if up[b][1] and down[b][1]]
    b_peak = max((b for b in both), key=lambda b: mean(up[b]))
    for k in range(len(both) - 1):
        b0, b1 = both[k], both[k + 1]
        if b0 < b_peak:
            continue
        d0, d1 = mean(up[b0]) - mean(down[b0]), mean(up[b1]) - mean(down[b1])
        if d0 > 0 >= d1:
            umf_c = ub[b0] + (ub[b1] - ub[b0]) * d0 / (d0 - d1)
            break
    # Ergun-form fit on the falling branch's fixed-bed points
    s11 = s12 = s22 = r1 = r2 = 0.0
    for b in range(nb):
        if down[b][1] and mean(down[b]) < 0.7 * plateau and ub[b] >= 0.3:
            u, dp = ub[b], mean(down[b])
            s11 += u * u; s12 += u ** 3; s22 += u ** 4; r1 += u * dp; r2 += u * u * dp
    det = s11 * s22 - s12 * s12
    umf_e = float("nan")
    if det > 0:
        a = (r1 * s22 - r2 * s12) / det
        bq = (s11 * r2 - s12 * r1) / det
        disc = a * a + 4 * bq * plateau
        if bq and disc >= 0:
            umf_e = (-a + math.sqrt(disc)) / (2 * bq)
        elif a > 0:
            umf_e = plateau / a
    peak = max(mean(up[b]) for b in range(nb) if up[b][1])
    summary = [("bed_weight_per_area", W, "Pa"), ("u_mf_C", umf_c, "m/s"),
               ("u_mf_ergun", umf_e, "m/s"), ("plateau_over_W", plateau / W, "-"),
               ("peak_over_W", peak / W, "-")]
    with open(f"{out}/loop_summary.csv", "w") as f:
        f.write("name,value,unit\n")
        for n, v, unit in summary:
            f.write(f"{n},{v:.6g},{unit}\n")
            print(f"{n:22s} {v:.4g} {unit}")


if __name__ == "__main__":
    main(sys.argv)
