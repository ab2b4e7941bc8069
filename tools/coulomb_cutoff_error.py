#!/usr/bin/python3
"""The error of the shifted-force Coulomb cut-off (src/noncontact/kernels/coulomb.hpp) against the
full pairwise sum, for a random bed of charged spheres in a closed cube (no periodic images, so
the full sum over all pairs is the exact Coulomb force). Independent of the C++ (numpy).

Run:  /usr/bin/python3 tools/coulomb_cutoff_error.py     (prints the table of docs/noncontact.md)

Bed: N = 2000 spheres of diameter d at solids fraction 0.3 (random sequential addition), each
charge +-q: "bipolar" (random signs, net charge ~0, as triboelectric charging of like particles
gives) and "unipolar" (all +q, the net-charged bed). Error: rms over the particles of
|F_cut - F_full| / rms |F_full|.
"""
import numpy as np

rng = np.random.default_rng(1)
d, n, phi = 1.0, 2000, 0.3
side = (n * np.pi / 6 * d**3 / phi) ** (1 / 3)
pos = np.empty((n, 3))
k = 0
while k < n:
    x = rng.uniform(0.5 * d, side - 0.5 * d, 3)
    if k == 0 or np.min(np.sum((pos[:k] - x) ** 2, axis=1)) >= d * d:
        pos[k] = x
        k += 1
diff = pos[None, :, :] - pos[:, None, :]  # j - i
r = np.sqrt(np.sum(diff**2, axis=2))
np.fill_diagonal(r, np.inf)


def forces(q, rc):
    qq = q[:, None] * q[None, :]
    mag = qq * (1.0 / r**2 - (0.0 if rc is None else 1.0 / rc**2))
    if rc is not None:
        mag = np.where(r < rc, mag, 0.0)
    return -np.sum((mag / r)[:, :, None] * diff, axis=1)  # on i, repelling along i - j


print(f"cube side {side:.1f} d, {n} spheres, solids fraction {phi}")
print("charges    r_c/d   rms error")
for name, q in (("bipolar", rng.choice([-1.0, 1.0], n)), ("unipolar", np.ones(n))):
    full = forces(q, None)
    scale = np.sqrt(np.mean(np.sum(full**2, axis=1)))
    for rc in (2.0, 4.0, 8.0):
        err = np.sqrt(np.mean(np.sum((forces(q, rc * d) - full) ** 2, axis=1))) / scale
        print(f"{name:9s}  {rc:5.0f}   {err:.3f}")
