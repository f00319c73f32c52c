#!/usr/bin/env python3
"""Writes a denser start for the rod shear cell from a sheared state: the rods of a particle VTK
file (bedlam's `vtk_interval` output) with their centres scaled by s about the origin, inside a
box scaled by the same s, so that the solids fraction grows by 1/s^3 while the structure of the
sheared bed is kept (a lattice start denser than about 0.6 slides in layers for tens of strains
before it breaks up). Axes are kept, and velocities less the shear profile, which the new run
adds back. Prints the --set options that run it: the file, the smaller box, and a guard on
initial overlaps wide enough for those of a sheared bed. The overlaps the scaling adds, about
(1 - s) times the centre distance, relax in the first strains of the run, which the averages
leave out. The snapshot must be taken when the Lees-Edwards images are in register (shear rate
x box height x time a multiple of the box length: in the default box at 100/s every 0.015 s, so
a run to be squeezed further ends at 0.405 s rather than 0.4). The box is taken to start at the
origin (the scene's domain.min = 0 0 0); the rods' spins are not carried over (the first strains
give them back), and the register is not checked: the snapshot's time is the user's to choose.

usage: tools/rod_compress.py PARTICLES.vtp OUT.csv SOLIDS_FRACTION [BOX_X BOX_Y BOX_Z]
  (the box of the file's run; default 0.072 0.048 0.048 m, scenes/shear_cell_rods.ini's;
  the shear rate is 100/s, or the environment's SHEAR_RATE)
"""
import math
import os
import re
import struct
import sys


def read_vtp(path):
    """Returns {name: (components, values)} for every Float64 array and the points."""
    data = open(path, "rb").read()
    head_end = data.index(b"<AppendedData")
    head = data[:head_end].decode()
    start = data.index(b"_", head_end) + 1
    arrays = {}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="([^"]+)" NumberOfComponents="(\d+)"'
                         r' format="appended" offset="(\d+)"', head):
        kind, name, comps, offset = m.group(1), m.group(2), int(m.group(3)), int(m.group(4))
        if kind != "Float64":
            continue
        at = start + offset
        size = struct.unpack_from("<Q", data, at)[0]
        values = struct.unpack_from("<%dd" % (size // 8), data, at + 8)
        arrays[name] = (comps, values)
    return arrays


def rod_volume(radius, length):
    return math.pi * radius ** 2 * (length - 2 * radius) + 4.0 / 3.0 * math.pi * radius ** 3


def main():
    if len(sys.argv) not in (4, 7):
        sys.exit(__doc__)
    arrays = read_vtp(sys.argv[1])
    target = float(sys.argv[3])
    box = [float(v) for v in sys.argv[4:7]] if len(sys.argv) == 7 else [0.072, 0.048, 0.048]
    points, vel, axis = arrays["Points"][1], arrays["velocity"][1], arrays["axis"][1]
    radius, length = arrays["radius"][1], arrays["length"][1]
    n = len(radius)
    rate = float(os.environ.get("SHEAR_RATE", "100"))
    volume = sum(rod_volume(radius[i], length[i]) for i in range(n))
    now = volume / (box[0] * box[1] * box[2])
    s = (now / target) ** (1.0 / 3.0)
    new_box = [b * s for b in box]
    with open(sys.argv[2], "w") as f:
        f.write("x,y,z,vx,vy,vz,ux,uy,uz\n")
        for i in range(n):
            p = [(points[3 * i + k] % box[k]) * s for k in range(3)]
            vx = vel[3 * i] - rate * (points[3 * i + 2] - 0.5 * box[2])
            f.write("%.7f,%.7f,%.7f,%.5f,%.5f,%.5f,%.6f,%.6f,%.6f\n"
                    % (p[0], p[1], p[2], vx, vel[3 * i + 1], vel[3 * i + 2],
                       axis[3 * i], axis[3 * i + 1], axis[3 * i + 2]))
    print("%d rods: solids fraction %.4f -> %.4f, scale %.5f" % (n, now, target, s))
    print("--set create.bed.file=%s --set 'domain.max=%.7f %.7f %.7f' "
          "--set guards.initial_overlap=0.2" % ((os.path.abspath(sys.argv[2]),) + tuple(new_box)))


if __name__ == "__main__":
    main()
