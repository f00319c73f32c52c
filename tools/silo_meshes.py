#!/usr/bin/env python3
"""Writes the OBJ meshes of the silo, hopper and mixer scenes (scenes/meshes/).

  silo_floor_D18.obj, silo_floor_D24.obj  the flat floor of a silo, an annulus from the orifice
                                           (diameter 18 or 24 mm) out to a radius of 40 mm
  hopper_cone.obj                          a conical hopper: 60 degrees included angle, outlet
                                           18 mm, rim 120 mm across, 49 mm high
  mixer_blades.obj                         two flat blades pitched at 45 degrees, from 5 to 34 mm
                                           off the z axis, 16 mm wide, centred at z = 10 mm: an
                                           impeller turning about z lifts the beads ahead of it

Coordinates in metres, the orifice centred on the z axis at z = 0. Circles are polygons of 96
sides (their area is 0.9993 of the circle's).
"""
import math
import os
import sys

SIDES = 96


def ring(radius, z):
    return [(radius * math.cos(2 * math.pi * k / SIDES), radius * math.sin(2 * math.pi * k / SIDES), z)
            for k in range(SIDES)]


def band(inner, outer):
    """Faces joining two rings of SIDES vertices (1-based OBJ indices of their first vertex)."""
    faces = []
    for k in range(SIDES):
        a, b = inner + k, inner + (k + 1) % SIDES
        c, d = outer + (k + 1) % SIDES, outer + k
        faces += [(a, b, c), (a, c, d)]
    return faces


def write(path, title, vertices, faces):
    with open(path, "w") as f:
        f.write("# %s\n# written by tools/silo_meshes.py; coordinates in metres\n" % title)
        for v in vertices:
            f.write("v %.9f %.9f %.9f\n" % v)
        for t in faces:
            f.write("f %d %d %d\n" % t)


def blades():
    """Two pitched blades, each a grid of 6 x 2 quads, the one at -x the one at +x turned half a
    turn about z. Each leans back by 45 degrees from the way it moves when the impeller turns
    about +z (its leading face looks up), so that both lift what they push."""
    vertices, faces = [], []
    c, s = math.cos(math.radians(45.0)), math.sin(math.radians(45.0))
    for side in (1, -1):
        first = len(vertices) + 1
        for i in range(7):
            r = 0.005 + (0.034 - 0.005) * i / 6
            for j in range(3):
                w = -0.008 + 0.008 * j          # across the blade, in its own plane
                vertices.append((side * r, side * w * c, 0.010 - w * s))
        for i in range(6):
            for j in range(2):
                a = first + 3 * i + j
                faces += [(a, a + 3, a + 4), (a, a + 4, a + 1)]
    return vertices, faces


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes", "meshes")
    os.makedirs(out, exist_ok=True)
    for d_mm in (18, 24):
        write(os.path.join(out, "silo_floor_D%d.obj" % d_mm),
              "flat silo floor with a central orifice of %d mm, out to a radius of 40 mm" % d_mm,
              ring(0.0005 * d_mm, 0.0) + ring(0.040, 0.0), band(1, 1 + SIDES))
    half = math.radians(30.0)
    r_out, r_rim = 0.009, 0.060
    height = (r_rim - r_out) / math.tan(half)
    write(os.path.join(out, "hopper_cone.obj"),
          "conical hopper, 60 degrees included angle, outlet 18 mm, rim 120 mm, %.1f mm high" % (1000 * height),
          ring(r_out, 0.0) + ring(r_rim, height), band(1, 1 + SIDES))
    vertices, faces = blades()
    write(os.path.join(out, "mixer_blades.obj"),
          "two flat blades pitched at 45 degrees about the z axis, 5 to 34 mm out, 16 mm wide", vertices, faces)


if __name__ == "__main__":
    main()
