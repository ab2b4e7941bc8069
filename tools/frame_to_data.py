#!/usr/bin/python3
"""Write one frame of a fluidem particles.h5 (H5MD) as a LAMMPS data file
(Atoms section: id type diameter density x y z), the format of [[insert]] placement = "file".

usage: frame_to_data.py particles.h5 out.data [--frame K] [--density RHO] [--species S]
The frame defaults to the last one. H5MD files do not store the density: give it (kg/m^3).
--species S writes only the particles of species index S (0 = the case's first [[species]]),
for an [[insert]] batch of that species.
"""
import argparse
import sys

import h5py
import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("h5")
    ap.add_argument("out")
    ap.add_argument("--frame", type=int, default=-1)
    ap.add_argument("--density", type=float, required=True, help="particle density, kg/m^3")
    ap.add_argument("--species", type=int, default=None, help="only this species index")
    a = ap.parse_args()
    with h5py.File(a.h5, "r") as f:
        g = f["particles/all"]
        pos = np.asarray(g["position/value"][a.frame])
        rad = np.asarray(g["radius/value"][a.frame])
        species = np.asarray(g["species/value"][a.frame])
        ids = np.asarray(g["id/value"][a.frame])
    if a.species is not None:
        keep = species == a.species
        pos, rad, species, ids = pos[keep], rad[keep], species[keep], ids[keep]
    n = len(rad)
    with open(a.out, "w") as o:
        o.write(f"# frame {a.frame} of {a.h5} (fluidem tools/frame_to_data.py)\n\n")
        types = 1 if a.species is not None or not n else int(species.max()) + 1
        o.write(f"{n} atoms\n{types} atom types\n\nAtoms # sphere\n\n")
        for k in range(n):
            t = 1 if a.species is not None else int(species[k]) + 1
            o.write(f"{int(ids[k]) + 1} {t} {2.0 * rad[k]:.17g} {a.density:.17g} "
                    f"{pos[k][0]:.17g} {pos[k][1]:.17g} {pos[k][2]:.17g}\n")
    print(f"wrote {n} particles to {a.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
