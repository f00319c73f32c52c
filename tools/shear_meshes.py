#!/usr/bin/env python3
"""Writes the corrugated plate that drives the wall-driven shear cell (scenes/meshes/).

  shear_plate.obj  an egg-crate surface z = (h/2) (w(x) + w(y)), w the triangle wave from 0 at
                   multiples of the period p = 6 mm to 1 halfway between, height h = 3 mm:
                   square dimples with flat faces (two triangles per half period), over
                   x in [-12, 84] mm and y in [-12, 60] mm: the 72 x 48 mm box of
                   scenes/shear_cell_walls.ini (12 and 8 periods) and two periods beyond each side,
                   so that it repeats along x and y ([wall] periodic = x y) as it moves

Coordinates in metres. A 5.3 mm sphere sits in a dimple and cannot slide along the plate without
climbing out of it: the plate drags the spheres by normal forces alone, as bumpy walls of glued
particles do.
"""
import math
import os
import sys

PERIOD = 0.006
HEIGHT = 0.003
FACETS = 2  # a vertex every half period: the surface is flat between
X0, X1, Y0, Y1 = -0.012, 0.084, -0.012, 0.060


def wave(x):
    """The triangle wave: 0 at multiples of the period, 1 halfway between."""
    f = x / PERIOD - math.floor(x / PERIOD)
    return 2 * f if f <= 0.5 else 2 - 2 * f


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("scenes", "meshes")
    nx = round((X1 - X0) / PERIOD) * FACETS
    ny = round((Y1 - Y0) / PERIOD) * FACETS
    verts = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            x = X0 + (X1 - X0) * i / nx
            y = Y0 + (Y1 - Y0) * j / ny
            z = 0.5 * HEIGHT * (wave(x) + wave(y))
            verts.append((x, y, z))
    faces = []
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i + 1
            b, c, d = a + 1, a + nx + 2, a + nx + 1
            faces += [(a, b, c), (a, c, d)]
    path = os.path.join(out, "shear_plate.obj")
    with open(path, "w") as f:
        f.write("# corrugated plate of the wall-driven shear cell\n")
        f.write("# written by tools/shear_meshes.py; coordinates in metres\n")
        for v in verts:
            f.write("v %.9g %.9g %.9g\n" % v)
        for t in faces:
            f.write("f %d %d %d\n" % t)
    print("%s: %d vertices, %d triangles" % (path, len(verts), len(faces)))


if __name__ == "__main__":
    main()
