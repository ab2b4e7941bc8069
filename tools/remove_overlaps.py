#!/usr/bin/python3
"""Push apart the overlapping spheres of a LAMMPS data file (the format of [[insert]] placement =
"file": Atoms id type diameter density x y z) until no two touch closer than their contact
distance, so that a bed settled by the soft-sphere engine (static overlaps of a fraction of a
percent) can start the event-driven hard-sphere engine, which allows none.

usage: remove_overlaps.py in.data out.data --lo X Y Z --hi X Y Z [--gap 1e-6] [--digits 10]
                          [--stretch F] [--split]

With --stretch F the heights above the floor are first multiplied by 1 + F (the overlaps of a
settled bed add up over its height; the sweeps then only have the local ones to undo). Each
sweep moves both spheres of every pair closer than (d_i + d_j)/2 (1 + gap) apart along
their line of centres by half the shortfall (Jacobi: all displacements from the same positions,
then summed), then puts the spheres that cut a wall of the box [lo, hi] back against it. It
stops when no pair is closer than (1 + gap) x contact (the result is checked once more from the
written, rounded numbers) and reports the largest displacement, so that one can see that the bed kept
its structure. Positions are written with --digits significant digits. With --split, one file
per atom type, out_typeT.data (an [[insert]] batch has one species: one file each).
"""
import argparse
import os
import sys

import numpy as np
from scipy.spatial import cKDTree


def read_data(path):
    with open(path) as f:
        lines = f.read().splitlines()
    header, atoms, i = [], [], 0
    while i < len(lines) and not lines[i].strip().startswith("Atoms"):
        header.append(lines[i])
        i += 1
    if i == len(lines):
        sys.exit(f"{path}: no Atoms section")
    for line in lines[i + 1:]:
        if line.strip():
            atoms.append(line.split("#")[0].split())
    a = np.array(atoms, dtype=float)
    if a.ndim != 2 or a.shape[1] < 7:
        sys.exit(f"{path}: Atoms lines must be 'id type diameter density x y z'")
    return header, lines[i], a


def contact_pairs(x, r, gap):
    tree = cKDTree(x)
    pairs = tree.query_pairs(2.0 * r.max() * (1.0 + gap), output_type="ndarray")
    if len(pairs) == 0:
        return pairs, np.zeros(0), np.zeros((0, 3)), np.zeros(0)
    d = x[pairs[:, 1]] - x[pairs[:, 0]]
    dist = np.linalg.norm(d, axis=1)
    sigma = (r[pairs[:, 0]] + r[pairs[:, 1]]) * (1.0 + gap)
    close = dist < sigma
    return pairs[close], dist[close], d[close], sigma[close]


def relax(x, r, lo, hi, gap, max_sweeps, start):
    """Sweeps towards every pair at least (1 + gap) x contact apart; done when none is closer
    than (1 + gap/2) x contact (the pushes shrink geometrically near the target)."""
    for sweep in range(max_sweeps):
        pairs, dist, d, sigma = contact_pairs(x, r, gap)
        if len(pairs) == 0 or (dist / sigma).min() >= (1.0 + 0.5 * gap) / (1.0 + gap):
            return sweep, np.linalg.norm(x - start, axis=1).max()
        if sweep % 100 == 0:
            print(f"sweep {sweep}: {len(pairs)} pairs closer than contact, the deepest at "
                  f"{1.0 - (dist / sigma).min():.3g}", file=sys.stderr)
        unit = d / np.maximum(dist, 1e-300)[:, None]
        # 0.5 x the shortfall each, and a little more so that the sweep does not creep
        push = 0.5 * (sigma - dist)[:, None] * unit * 1.01
        dx = np.zeros_like(x)
        np.add.at(dx, pairs[:, 0], -push)
        np.add.at(dx, pairs[:, 1], push)
        x += dx
        inner = r[:, None] * (1.0 + gap)
        np.clip(x, lo + inner, hi - inner, out=x)
    sys.exit(f"overlaps left after {max_sweeps} sweeps: {len(pairs)} pairs, the closest at "
             f"{(dist / sigma).min():.9f} of its contact distance")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("inp")
    ap.add_argument("out")
    ap.add_argument("--lo", type=float, nargs=3, required=True, help="the box's lower corner, m")
    ap.add_argument("--hi", type=float, nargs=3, required=True, help="the box's upper corner, m")
    ap.add_argument("--gap", type=float, default=1e-6,
                    help="the smallest allowed gap as a fraction of the contact distance")
    ap.add_argument("--digits", type=int, default=10)
    ap.add_argument("--sweeps", type=int, default=20000)
    ap.add_argument("--comment", default="", help="the file's first line")
    ap.add_argument("--split", action="store_true", help="one file per atom type")
    ap.add_argument("--stretch", type=float, default=0.0,
                    help="first multiply the heights above lo[2] by 1 + STRETCH")
    a = ap.parse_args()
    header, atoms_line, atoms = read_data(a.inp)
    x = atoms[:, 4:7].copy()
    r = 0.5 * atoms[:, 2]
    lo, hi = np.array(a.lo), np.array(a.hi)
    before, dist, _, sigma = contact_pairs(x, r, 0.0)
    worst = (1.0 - (dist / sigma).min()) if len(before) else 0.0
    # the bed's overlaps add up over its height: stretching it upwards first (heights above the
    # floor times 1 + stretch) leaves the sweeps the local ones
    start = x.copy()
    x[:, 2] = lo[2] + (x[:, 2] - lo[2]) * (1.0 + a.stretch)
    # relax towards three times the gap (done at one and a half): rounding to --digits cannot
    # bring a pair back under the gap
    sweeps, moved = relax(x, r, lo, hi, 3.0 * a.gap + 10.0 ** (1 - a.digits), a.sweeps, start)
    fmt = f"{{:.{a.digits}g}}"
    rows = []
    for k in range(len(atoms)):
        q = [fmt.format(v) for v in x[k]]
        rows.append(f"{int(atoms[k, 0])} {int(atoms[k, 1])} {float(atoms[k, 2])!r} "
                    f"{float(atoms[k, 3])!r} {' '.join(q)}")
    written = np.array([[float(v) for v in row.split()[4:7]] for row in rows])
    left, _, _, _ = contact_pairs(written, r, a.gap)
    if len(left):
        sys.exit(f"{len(left)} pairs still closer than (1 + {a.gap}) x contact after rounding")
    types = sorted(set(int(t) for t in atoms[:, 1])) if a.split else [None]
    stem, ext = os.path.splitext(a.out)
    for t in types:
        keep = [row for k, row in enumerate(rows) if t is None or int(atoms[k, 1]) == t]
        path = a.out if t is None else f"{stem}_type{t}{ext}"
        with open(path, "w") as o:
            first = a.comment or header[0]
            o.write(first.rstrip() + (f" (atom type {t})" if t is not None else "") + "\n\n")
            o.write(f"{len(keep)} atoms\n1 atom types\n\n{atoms_line}\n\n")
            o.write("\n".join(keep) + "\n")
        print(f"wrote {len(keep)} spheres to {path}", file=sys.stderr)
    print(f"{len(atoms)} spheres; {len(before)} pairs overlapped (deepest "
          f"{worst:.3g} of the contact distance); none after {sweeps} sweeps; largest "
          f"displacement {moved:.3g} m ({moved / (2.0 * r.min()):.3g} of the smallest diameter)",
          file=sys.stderr)


if __name__ == "__main__":
    main()
