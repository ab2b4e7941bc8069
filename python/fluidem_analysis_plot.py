#!/usr/bin/python3
"""Pictures of `fluidem analyse OUTDIR` (docs/analysis.md).

Usage: /usr/bin/python3 python/fluidem_analysis_plot.py OUTDIR
       /usr/bin/python3 python/fluidem_analysis_plot.py --compare OUTDIR1 OUTDIR2 [...]

Reads OUTDIR/analysis/*.csv (written by `fluidem analyse`) and OUTDIR/probes.csv, and writes into
OUTDIR/analysis/:
  spectrum_<probe>.png      the probe's pressure fluctuation over the analysis window (top) and
                            its power spectral density with the dominant frequency marked
                            (bottom), as [Chang08 Fig. 10];
  velocity_distribution.png the density of each velocity fluctuation component C/s against the
                            standard normal density, and of the speed |C|/sqrt(theta) against the
                            Maxwell (3-D) or Rayleigh (2-D) density, as [Deen07 Fig. 10];
  segregation.png           the degree of segregation s against time [Deen07 eq. 49], when
                            segregation.csv exists;
  pressure_drop_velocity.png the bed pressure drop against the superficial velocity, rising and
                            falling branches (over the bed weight W), as [Chang08 Fig. 3.17],
                            when pressure_drop_velocity.csv exists (the inflow varied).
With --compare (`fluidem plot OUT1 OUT2 ...`), the curves the runs share on one figure in
OUTDIR1/analysis/:
  segregation_compare.png   s(t) of every run that has segregation.csv, each labelled with its
                            directory and drag closure, with the published values of each run's
                            case: the [[quantity]] rows of the reference.toml next to the case file
                            (recorded in OUTDIR/case.resolved.toml) whose `case` is the case file's
                            name and whose `curve` is "segregation", drawn at their `at_time` (a
                            point for a value, an arrow for a bound such as "above 0.9").
Exit codes: 0 done; 2 bad input (no OUTDIR/analysis: run `fluidem analyse OUTDIR` first; an
unreadable CSV); 3 matplotlib or numpy is missing.
"""
import csv
import glob
import os
import sys
import tomllib


def fail(message, code=2):
    print(f"fluidem_analysis_plot: {message}", file=sys.stderr)
    sys.exit(code)


try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: E402
    import numpy as np  # noqa: E402
except ImportError as e:
    fail(f"{sys.executable} cannot import {e.name} ({e}); install python3-matplotlib and "
         "python3-numpy (Debian) or run with an interpreter that has them", 3)


def read_columns(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        fail(f"cannot read {path}: {e.strerror}")
    if not rows:
        fail(f"{path} is empty")
    header, body = rows[0], [r for r in rows[1:] if r]
    try:
        data = np.array([[float(v) for v in r] for r in body], dtype=float)
    except ValueError:
        fail(f"{path}: a row is not all numbers")
    if data.size == 0:
        data = np.zeros((0, len(header)))
    if data.shape[1] != len(header):
        fail(f"{path}: rows do not have {len(header)} columns")
    return {name: data[:, i] for i, name in enumerate(header)}


def read_summary(path):
    out = {}
    try:
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                out[row["name"]] = float(row["value"])
    except (OSError, KeyError, ValueError) as e:
        fail(f"cannot read {path}: {e}")
    return out


def plot_spectrum(outdir, adir, summary, probes, path):
    name = os.path.basename(path)[len("spectrum_"):-len(".csv")]
    spec = read_columns(path)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 7))
    t0, t1 = summary.get("window_start"), summary.get("window_end")
    if probes is not None and name in probes and t0 is not None:
        t = probes["time"]
        sel = (t >= t0) & (t <= t1)
        p = probes[name][sel]
        ax1.plot(t[sel], (p - p.mean()) / 1e3, lw=0.8)
        ax1.set_title(f"probe {name}: pressure fluctuation (mean {p.mean() / 1e3:.4g} kPa)")
    ax1.set_xlabel("time (s)")
    ax1.set_ylabel("p - <p> (kPa)")
    f, psd = spec["frequency"], spec["psd"]
    ax2.semilogy(f[1:], psd[1:], lw=1.0)
    fd = summary.get("dominant_frequency_" + name)
    if fd is not None:
        ax2.axvline(fd, color="r", ls="--", lw=1.0, label=f"dominant {fd:.3g} Hz")
        ax2.legend()
    ax2.set_xlim(0, min(f[-1], max(10 * (fd or 1.0), 20.0)))
    ax2.set_xlabel("frequency (Hz)")
    ax2.set_ylabel("PSD (Pa$^2$/Hz)")
    ax2.set_title("Welch power spectral density [Chang08 §4.2]")
    fig.tight_layout()
    fig.savefig(os.path.join(adir, f"spectrum_{name}.png"), dpi=100)
    plt.close(fig)


def plot_velocities(adir, summary):
    d = read_columns(os.path.join(adir, "velocity_distribution.csv"))
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    x = d["bin_centre"]
    for comp in ("x", "y", "z"):
        key = "density_" + comp
        if key in d:
            k = summary.get("velocity_kurtosis_" + comp)
            label = f"C$_{comp}$/s$_{comp}$" + (f" (kurtosis {k:.2f})" if k is not None else "")
            ax1.plot(x, d[key], "o-", ms=3, lw=0.8, label=label)
    ax1.plot(x, d["normal"], "k-", lw=1.5, label="normal")
    ax1.set_xlabel("C / s")
    ax1.set_ylabel("probability density")
    ax1.legend(fontsize=8)
    ax1.set_title("velocity fluctuation components [Deen07 §6.2]")
    ref = "maxwell" if "maxwell" in d else "rayleigh"
    ax2.plot(d["speed"], d["speed_density"], "o-", ms=3, lw=0.8, label="|C| / sqrt(theta)")
    ax2.plot(d["speed"], d[ref], "k-", lw=1.5, label=ref.capitalize())
    ax2.set_xlabel("|C| / sqrt(theta)")
    ax2.set_ylabel("probability density")
    theta = summary.get("granular_temperature")
    ax2.set_title("speed" + (f", theta = {theta:.3g} m$^2$/s$^2$" if theta is not None else ""))
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(adir, "velocity_distribution.png"), dpi=100)
    plt.close(fig)


def plot_segregation(adir):
    d = read_columns(os.path.join(adir, "segregation.csv"))
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(d["time"], d["s"], lw=1.0)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("degree of segregation s")
    ax.set_title("segregation [Deen07 eq. 49]: 0 mixed, 1 segregated")
    fig.tight_layout()
    fig.savefig(os.path.join(adir, "segregation.png"), dpi=100)
    plt.close(fig)


def plot_pressure_velocity(adir):
    d = read_columns(os.path.join(adir, "pressure_drop_velocity.csv"))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(d["superficial_velocity"], d["rising_over_weight"], "o-", ms=3, lw=1.0,
            label="velocity rising")
    ax.plot(d["superficial_velocity"], d["falling_over_weight"], "s--", ms=3, lw=1.0,
            label="velocity falling")
    ax.axhline(1.0, color="k", lw=0.5)
    ax.set_xlabel("superficial velocity (m/s)")
    ax.set_ylabel("pressure drop / bed weight per area")
    ax.set_title("pressure drop against superficial velocity [Chang08 §3.4]")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(adir, "pressure_drop_velocity.png"), dpi=100)
    plt.close(fig)


CASE_FILE_MARK = "# case file: "
# analysis CSVs that --compare draws together: column, axis label
COMPARABLE = {"segregation": ("s", "degree of segregation s [Deen07 eq. 49]")}


def run_case(outdir):
    """The case file recorded in OUTDIR/case.resolved.toml's header (or None) and the run's
    coupling.drag (or None)."""
    path = os.path.join(outdir, "case.resolved.toml")
    try:
        with open(path, "rb") as f:
            text = f.read().decode("utf-8", "replace")
    except OSError:
        return None, None
    case_file = next((line[len(CASE_FILE_MARK):].strip() for line in text.splitlines()[:3]
                      if line.startswith(CASE_FILE_MARK)), None)
    try:
        drag = tomllib.loads(text).get("coupling", {}).get("drag")
    except tomllib.TOMLDecodeError:
        drag = None
    return case_file, drag


def published_points(case_file, curve):
    """The [[quantity]] rows of the reference.toml next to `case_file` for this case and curve
    with an at_time (python/fluidem_validate.py checks these files' keys)."""
    if not case_file:
        return []
    ref = os.path.join(os.path.dirname(case_file), "reference.toml")
    try:
        with open(ref, "rb") as f:
            rows = tomllib.load(f).get("quantity", [])
    except (OSError, tomllib.TOMLDecodeError):
        return []
    stem = os.path.splitext(os.path.basename(case_file))[0]
    return [r for r in rows if isinstance(r, dict) and r.get("case") == stem
            and r.get("curve") == curve and isinstance(r.get("at_time"), (int, float))]


def plot_compare(outdirs):
    written = 0
    markers = ["o", "s", "D", "v", "P"]
    for curve, (column, ylabel) in COMPARABLE.items():
        runs = [o for o in outdirs if os.path.exists(os.path.join(o, "analysis", curve + ".csv"))]
        if len(runs) < 2:
            continue
        fig, ax = plt.subplots(figsize=(8, 4.8))
        t_max, y_min, y_max, m = 0.0, 0.0, 1.0, 0
        for k, o in enumerate(runs):
            d = read_columns(os.path.join(o, "analysis", curve + ".csv"))
            case_file, drag = run_case(o)
            label = os.path.basename(os.path.normpath(o)) + (f" ({drag})" if drag else "")
            colour = f"C{k}"
            ax.plot(d["time"], d[column], "-", color=colour, lw=1.2, label=f"fluidem: {label}")
            if len(d["time"]):
                print(f"{label}: {column} = {d[column][-1]:.4f} at t = {d['time'][-1]:.3f} s "
                      "(last frame)")
                t_max = max(t_max, float(d["time"][-1]))
                y_min = min(y_min, float(np.min(d[column])))
                y_max = max(y_max, float(np.max(d[column])))
            for row in published_points(case_file, curve):
                t = float(row["at_time"])
                t_max = max(t_max, t)
                text = f"{row['published']} {row['source']}"
                crit = row.get("criterion", {})
                print(f"  published for {os.path.basename(case_file)}: {text} at t = {t:g} s")
                if isinstance(row.get("value"), (int, float)):
                    ax.plot([t], [row["value"]], markers[m % len(markers)], mfc="none",
                            mec=colour, mew=1.5, ms=8, label=text)
                    m += 1
                elif crit.get("kind") in ("above", "below") and "bound" in crit:
                    b = float(crit["bound"])
                    up = crit["kind"] == "above"
                    ax.annotate("", xy=(t, b + (0.12 if up else -0.12)), xytext=(t, b),
                                arrowprops={"arrowstyle": "->", "color": colour, "lw": 1.5})
                    ax.plot([t], [b], "_", color=colour, ms=14, mew=2,
                            label=f"{text}: {crit.get('text', crit['kind'])}")
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_xlim(0.0, t_max * 1.04 + 1e-9)
        ax.set_ylim(min(-0.1, y_min - 0.05), max(1.15, y_max + 0.05))
        ax.set_xlabel("time (s)")
        ax.set_ylabel(ylabel)
        ax.legend(loc="best", fontsize=7)
        fig.tight_layout()
        png = os.path.join(outdirs[0], "analysis", f"{curve}_compare.png")
        fig.savefig(png, dpi=100)
        plt.close(fig)
        print(f"written {png}")
        written += 1
    if written == 0:
        fail("the runs share no curve to compare (segregation.csv in two or more of them)")
    return 0


def main(argv):
    if len(argv) >= 1 and argv[0] == "--compare":
        if len(argv) < 3:
            fail("--compare needs two or more output directories")
        return plot_compare(argv[1:])
    if len(argv) != 1 or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv and argv[0] in ("-h", "--help") else 2
    outdir = argv[0]
    adir = os.path.join(outdir, "analysis")
    if not os.path.isdir(adir):
        fail(f"no {adir}: run `fluidem analyse {outdir}` first")
    summary_path = os.path.join(adir, "summary.csv")
    summary = read_summary(summary_path) if os.path.exists(summary_path) else {}
    probes_path = os.path.join(outdir, "probes.csv")
    probes = read_columns(probes_path) if os.path.exists(probes_path) else None
    written = 0
    for path in sorted(glob.glob(os.path.join(adir, "spectrum_*.csv"))):
        plot_spectrum(outdir, adir, summary, probes, path)
        written += 1
    if os.path.exists(os.path.join(adir, "velocity_distribution.csv")):
        plot_velocities(adir, summary)
        written += 1
    if os.path.exists(os.path.join(adir, "segregation.csv")):
        plot_segregation(adir)
        written += 1
    if os.path.exists(os.path.join(adir, "pressure_drop_velocity.csv")):
        plot_pressure_velocity(adir)
        written += 1
    if written == 0:
        fail(f"{adir} holds no analysis CSV: run `fluidem analyse {outdir}`")
    print(f"fluidem_analysis_plot: {written} pictures in {adir}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
