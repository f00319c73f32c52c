#!/usr/bin/env python3
"""Writes a dense start for rods in the shear cell: N rods of the thesis's large AR-4 size (3 mm
across, 12 mm tip to tip) standing along z, the shear's gradient, on a lattice of the
72 x 48 x 48 mm box — 4 along z tip to tip, 22 x 15 across at 3.2 mm — taken at random sites,
with a random velocity of 0.1 m/s. Random insertion of rods jams near a solids fraction of
0.2-0.3; this lattice holds up to 1320 rods (0.619). More rods (up to 1656, 0.776) are placed on
a triangular lattice instead: 23 across x at 3.13 mm, 18 rows at 2.67 mm (neighbours 3.09 mm
apart), commensurate with the periodic faces. Rods standing across the flow are tipped
over by the shear at once, which disorders the start within a few strains (rods lying along the
flow would slide past each other in layers for tens of strains).

usage: tools/rod_shear_fill.py N OUT.csv [SEED]
"""
import math
import random
import sys


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    n, out = int(sys.argv[1]), sys.argv[2]
    rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
    sites = [(0.0016 + 0.0032 * i + 0.0004 * (k % 2), 0.0016 + 0.0032 * j, 0.006 + 0.012 * k)
             for i in range(22) for j in range(15) for k in range(4)]
    if n > len(sites):
        dx, dy = 0.072 / 23, 0.048 / 18
        sites = [(dx * (i + 0.25 + 0.5 * (j % 2)) + 0.0004 * (k % 2), dy * (j + 0.5),
                  0.006 + 0.012 * k)
                 for i in range(23) for j in range(18) for k in range(4)]
    if n > len(sites):
        sys.exit("at most %d rods fit" % len(sites))
    rng.shuffle(sites)
    with open(out, "w") as f:
        f.write("x,y,z,vx,vy,vz,ux,uy,uz\n")
        for x, y, z in sites[:n]:
            a, b = rng.uniform(0, 2 * math.pi), rng.uniform(-1, 1)
            s = math.sqrt(1 - b * b)
            f.write("%.6f,%.6f,%.6f,%.5f,%.5f,%.5f,0,0,1\n"
                    % (x, y, z, 0.1 * s * math.cos(a), 0.1 * s * math.sin(a), 0.1 * b))


if __name__ == "__main__":
    main()
