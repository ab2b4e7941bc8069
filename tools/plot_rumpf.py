#!/usr/bin/python3
"""[Zhu07 Fig. 4] (after Rumpf 1962): interparticle forces between two equal touching spheres of
diameter d, against the weight of one, drawn to docs/interparticle_forces.png.

Run:  /usr/bin/python3 tools/plot_rumpf.py

The curves are computed here, in Python, from the formulas (not from the C++ kernels, which
tests/unit/noncontact/rumpf_comparison_test.cpp checks against the same crossings):
  van der Waals   F = A d / (24 h^2)            A = 6.5e-20 J, h = 1.65 A   [Zhu07 Table 2]
  capillary       F = pi d gamma                the small-bridge limit of Willett et al. (2000)
                                                at contact, 2 pi R gamma cos(theta), theta = 0,
                                                water gamma = 72.8e-3 N/m
  electrostatic   F = Q^2 / (4 pi eps0 d^2)     Q = pi d^2 eps0 E_b, E_b = 3e6 V/m: each sphere
                                                carries the largest surface charge air holds,
                                                point charges at the centre distance d, eps_r = 1
                                                (an ASSUMPTION: the seed gives no charge)
  weight          W = rho g pi d^3 / 6           rho = 3e3 kg/m^3, g = 9.81 m/s^2
Crossing diameters (force = weight), closed forms:
  d_vdW = sqrt(A / (4 pi h^2 rho g)),  d_cap = sqrt(6 gamma / (rho g)),
  d_el  = 3 eps0 E_b^2 / (2 rho g)
"""
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "docs", "interparticle_forces.png")

A, H = 6.5e-20, 1.65e-10
GAMMA = 72.8e-3
EPS0, EB = 8.8541878128e-12, 3e6
RHO, G = 3e3, 9.81


def f_vdw(d):
    return A * d / (24 * H ** 2)


def f_cap(d):
    return math.pi * d * GAMMA if np.isscalar(d) else np.pi * d * GAMMA


def f_el(d):
    q = np.pi * d ** 2 * EPS0 * EB
    return q ** 2 / (4 * np.pi * EPS0 * d ** 2)


def weight(d):
    return RHO * G * np.pi * d ** 3 / 6


CROSSINGS = {
    "van der Waals": math.sqrt(A / (4 * math.pi * H ** 2 * RHO * G)),
    "capillary": math.sqrt(6 * GAMMA / (RHO * G)),
    "electrostatic": 3 * EPS0 * EB ** 2 / (2 * RHO * G),
}


def main():
    d = np.logspace(-6, -2, 400)
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    curves = [("capillary", f_cap, "C0"), ("van der Waals", f_vdw, "C1"),
              ("electrostatic", f_el, "C2")]
    for name, f, c in curves:
        dc = CROSSINGS[name]
        ax.loglog(d * 1e6, f(d), color=c, label=f"{name} (= weight at d = {dc * 1e3:.2f} mm)")
        ax.plot(dc * 1e6, weight(dc), "o", color=c, mfc="none")
    ax.loglog(d * 1e6, weight(d), "k--", label="weight")
    ax.set_xlabel("particle diameter (µm)")
    ax.set_ylabel("interparticle force (N)")
    ax.set_xlim(1, 1e4)
    ax.set_ylim(1e-12, 1e-2)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title("Interparticle forces vs weight (after Rumpf 1962, [Zhu07 Fig. 4])", fontsize=9)
    fig.text(0.01, 0.005,
             "A = 6.5e-20 J, h = 1.65 Å; water γ = 72.8 mN/m, θ = 0; ε_r = 1, "
             "σ = ε0·3 MV/m; ρ = 3000 kg/m³. Circles: force = weight.", fontsize=6.5)
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    fig.savefig(OUT, dpi=130)
    for name, dc in CROSSINGS.items():
        print(f"{name:14s} crossing d = {dc:.6e} m")
    print(f"wrote {os.path.normpath(OUT)}")


if __name__ == "__main__":
    main()
