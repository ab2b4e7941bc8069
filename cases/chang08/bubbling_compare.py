#!/usr/bin/python3
"""Side by side: the Chang08 bubbling bed with real particles and with virtual particles
[Chang08 §4.2, Figs. 4.5-4.6]: cases/chang08/bubbling_{A,B,C,D}.toml, each run and analysed
(output.analyse = true) into its own directory.

    /usr/bin/python3 cases/chang08/bubbling_compare.py OUT_A OUT_B OUT_C OUT_D [--png FILE]

Prints a Markdown table (per case: W, parcels, simulated time, wall time per simulated second
from the run's log if `OUT.log` or `OUT/run.log` exists, mean pressure at 150 mm above the
outlet's, mean bed pressure drop / bed weight, dominant frequency at 150 mm, bed expansion) and
draws the pressure at 150 mm and its spectra (PNG). Published [Chang08 §4.2]: mean pressure
drops 826.1, 837.6, 847.4, 838.4 Pa and characteristic frequencies 1.82, 2.08, 2.34, 1.82 Hz for
Cases A-D over 0-3.825 s (Table 4.2 lost: the set-up is chosen, README.md).
"""
import csv
import os
import re
import sys

PUBLISHED = {"A": (826.1, 1.82), "B": (837.6, 2.08), "C": (847.4, 2.34), "D": (838.4, 1.82)}


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def summary(out):
    _, rows = read_csv(os.path.join(out, "analysis", "summary.csv"))
    return {r[0]: float(r[1]) for r in rows if len(r) >= 2 and r[1] not in ("", "nan")}


def ratio_of(out):
    with open(os.path.join(out, "case.resolved.toml")) as f:
        text = f.read()
    m = re.search(r"^\s*ratio\s*=\s*([0-9.eE+-]+)", text, re.M)
    return float(m.group(1)) if m else 1.0


def wall_rate(out):
    for log in (out.rstrip("/") + ".log", os.path.join(out, "run.log")):
        if os.path.exists(log):
            with open(log) as f:
                done = [l for l in f if l.startswith("done:")]
            if done:
                m = re.search(r"done: (\d+) steps in ([0-9.]+) s wall", done[-1])
                if m:
                    return float(m.group(2))
    return None


def probe_stats(out, t0, t1):
    head, rows = read_csv(os.path.join(out, "probes.csv"))
    i150, itop = head.index("p_150mm"), head.index("p_top")
    t = [float(r[0]) for r in rows]
    dp = [float(r[i150]) - float(r[itop]) for r in rows]
    kept = [v for tt, v in zip(t, dp) if t0 <= tt <= t1]
    return t, dp, (sum(kept) / len(kept) if kept else float("nan"))


def main(argv):
    png = None
    if "--png" in argv:
        k = argv.index("--png")
        png = argv[k + 1]
        del argv[k : k + 2]
    outs = argv[1:]
    if not outs:
        sys.exit(__doc__)
    rows, traces = [], []
    for out in outs:
        name = {1.0: "A", 8.0: "B", 27.0: "C", 64.0: "D"}.get(ratio_of(out), "?")
        s = summary(out)
        t, dp, mean150 = probe_stats(out, s.get("window_start", 0.0), s.get("window_end", 1e300))
        wall = wall_rate(out)
        end = t[-1] if t else float("nan")
        rows.append(
            {
                "case": name,
                "W": ratio_of(out),
                "end": end,
                "wall_per_s": wall / end if wall and end > 0 else None,
                "p150": mean150,
                "drop_over_weight": s.get("pressure_drop_over_weight", float("nan")),
                "f150": s.get("dominant_frequency_p_150mm", float("nan")),
                "res": s.get("spectrum_resolution_p_150mm", float("nan")),
                "expansion": s.get("bed_expansion", float("nan")),
            }
        )
        traces.append((name, out, t, dp))
    print(f"window {s.get('window_start', 0):g}-{s.get('window_end', 0):g} s (analysis/summary.csv)")
    print("| case | W | simulated s | wall s per simulated s | mean p(150 mm) - p(outlet), Pa "
          "(published) | bed drop / weight | dominant f at 150 mm, Hz (published) | bed expansion |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        pub = PUBLISHED.get(r["case"], (float("nan"), float("nan")))
        wall = f"{r['wall_per_s']:.0f}" if r["wall_per_s"] else "-"
        print(f"| {r['case']} | {r['W']:g} | {r['end']:.3f} | {wall} | {r['p150']:.1f} ({pub[0]}) | "
              f"{r['drop_over_weight']:.3f} | {r['f150']:.2f} +- {r['res'] / 2:.2f} ({pub[1]}) | "
              f"{r['expansion']:.3f} |")
    if png:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.5))
        for name, out, t, dp in traces:
            a.plot(t, dp, lw=0.7, label=f"Case {name}")
            head, spec = read_csv(os.path.join(out, "analysis", "spectrum_p_150mm.csv"))
            b.plot([float(r[0]) for r in spec], [float(r[1]) for r in spec], label=f"Case {name}")
        a.set_xlabel("t, s")
        a.set_ylabel("p(150 mm) - p(outlet), Pa")
        a.legend()
        b.set_xlim(0, 10)
        b.set_xlabel("frequency, Hz")
        b.set_ylabel("PSD, Pa^2/Hz")
        b.axvline(1.82, color="k", ls=":", lw=0.8, label="Chang08 Case A, 1.82 Hz")
        b.legend()
        fig.suptitle("Chang08 §4 bubbling bed: real particles (A) and virtual particles W = 8, 27, 64")
        fig.tight_layout()
        fig.savefig(png, dpi=110)
        print(png)


if __name__ == "__main__":
    main(sys.argv)
