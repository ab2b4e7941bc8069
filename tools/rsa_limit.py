#!/usr/bin/python3
"""How many particles random sequential addition (RSA) places in a region, against the bound with
which fluidem refuses a random insertion at once (src/particles/insertion.cpp, check_random_fill):

    N_bound = phi_J V / v_p + S / d^(D-1)

phi_J the jamming fraction of RSA in unbounded space, 0.547069 for discs [Hinrichsen, Feder &
Jossang, J. Stat. Phys. 44 (1986) 793] and 0.384131 for spheres [Zhang & Torquato, Phys. Rev. E 88
(2013) 053312]; V the region's area (volume), v_p a particle's; S its perimeter (surface), i.e.
one particle per diameter (d^2) of edge, for the packing against the edges, which exceeds the bulk
fraction in regions a few diameters wide (a 1 x 10 strip holds 9 discs, the bulk fraction 7).

Here each region (sides in diameters, centres kept one radius from its faces as fluidem does) is
filled by RSA until 20 000 attempts in a row fail, over several seeds, and the largest count is
compared with the bound. Exits 1 if any region reaches it.

Run:  /usr/bin/python3 tools/rsa_limit.py        (about a minute)
"""
import itertools
import math
import random
import sys

PHI_J = {2: 0.547069, 3: 0.384131}
STALL = 20000


def rsa_count(sides, rng):
    dim = len(sides)
    cells, count, fails = {}, 0, 0
    while fails < STALL:
        x = tuple(0.5 + (sides[a] - 1.0) * rng.random() for a in range(dim))
        c = tuple(math.floor(v) for v in x)
        free = True
        for dc in itertools.product((-1, 0, 1), repeat=dim):
            for p in cells.get(tuple(c[a] + dc[a] for a in range(dim)), ()):
                if sum((p[a] - x[a]) ** 2 for a in range(dim)) < 1.0:
                    free = False
                    break
            if not free:
                break
        if free:
            cells.setdefault(c, []).append(x)
            count += 1
            fails = 0
        else:
            fails += 1
    return count


def bound(sides):
    dim = len(sides)
    size = math.prod(sides)
    particle = math.pi / 4 if dim == 2 else math.pi / 6
    if dim == 2:
        edge = 2 * (sides[0] + sides[1])
    else:
        edge = 2 * (sides[0] * sides[1] + sides[1] * sides[2] + sides[2] * sides[0])
    return math.floor(PHI_J[dim] * size / particle + edge)


def main():
    rng = random.Random(1986)
    regions = [(1, 10), (1.9, 20), (1, 1), (2, 2), (2.5, 2.5), (3, 3), (5, 5), (10, 10), (30, 30),
               (60, 60), (1, 1, 10), (1.5, 1.5, 10), (1, 1, 1), (2, 2, 2), (3, 3, 3), (1, 10, 10),
               (6, 6, 6), (12, 12, 12)]
    worst = 0.0
    for sides in regions:
        trials = 30 if math.prod(sides) < 200 else 4
        most = max(rsa_count(sides, rng) for _ in range(trials))
        b = bound(sides)
        worst = max(worst, most / b)
        print(f"region {str(sides):16s} RSA placed at most {most:5d}, bound {b:5d}")
    print(f"largest count / bound: {worst:.3f}")
    return 0 if worst < 1.0 else 1


if __name__ == "__main__":
    sys.exit(main())
