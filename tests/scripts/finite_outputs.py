#!/usr/bin/env python3
"""Checks that no output file of a run folder holds a non-finite number.

    finite_outputs.py RUN_FOLDER

Reads every file a run writes back as its reader would: the CSV files (diagnostics and the
series, contact files, the cameras' truth), the VTK PolyData files (.vtp, appended raw binary:
each Float64 array decoded) and the VTK ImageData files (.vti, ASCII). Prints each non-finite
number found with its file, column or array and row, and exits 1 if there is one.

NaN is accepted where a file uses it for "not defined": in the diagnostics columns a scene may
not define (probe_pressure_drop without probes, weight_ratio and mean_height without a gas,
segregation without two species, the rods' columns without rods; src/output/diagnostics.c, bdl_diagnostics_may_be_undefined), and in
species.csv and orientation.csv (a species or a histogram with no particles), and in fields.vti's
solids_velocity of a cell no solids passed through (its solids_fraction 0). Infinity never is.
"""
import math
import pathlib
import re
import struct
import sys

DIAGNOSTICS_UNDEFINED = {"probe_pressure_drop", "weight_ratio", "mean_height", "segregation",
                         "rod_vertical_cos", "rod_order"}
NAN_ANYWHERE = {"species.csv", "orientation.csv"}


def bad(value, nan_ok):
    return math.isinf(value) or (math.isnan(value) and not nan_ok)


def check_csv(path):
    lines = path.read_text().splitlines()
    lines = [l for l in lines if l and not l.startswith("#")]
    if not lines:
        return []
    header = lines[0].split(",")
    found = []
    for row, line in enumerate(lines[1:], start=2):
        for column, field in enumerate(line.split(",")):
            try:
                value = float(field)
            except ValueError:
                continue  # a file name, an empty field
            name = header[column] if column < len(header) else str(column + 1)
            nan_ok = path.name in NAN_ANYWHERE or (
                path.name == "diagnostics.csv" and name in DIAGNOSTICS_UNDEFINED)
            if bad(value, nan_ok):
                found.append(f"{path}: row {row}, {name} = {field}")
    return found


def check_vtp(path):
    data = path.read_bytes()
    head, _, appended = data.partition(b'<AppendedData encoding="raw">')
    appended = appended[appended.index(b"_") + 1:]
    found = []
    arrays = re.finditer(rb'<DataArray type="(\w+)" Name="([^"]+)"[^>]*offset="(\d+)"', head)
    for match in arrays:
        kind, name, offset = match.group(1), match.group(2).decode(), int(match.group(3))
        if kind != b"Float64":
            continue
        count = struct.unpack_from("<Q", appended, offset)[0] // 8
        values = struct.unpack_from(f"<{count}d", appended, offset + 8)
        found += [f"{path}: {name}[{i}] = {v}" for i, v in enumerate(values) if bad(v, False)]
    return found


def check_vti(path):
    found = []
    arrays = {m.group(1): [float(v) for v in m.group(2).split()] for m in
              re.finditer(r'Name="([^"]+)"[^>]*format="ascii">([^<]*)<', path.read_text())}
    empty = [f == 0.0 for f in arrays.get("solids_fraction", [])] if path.name == "fields.vti" \
        else []
    for name, values in arrays.items():
        undefined = (lambda i: name == "solids_velocity" and i // 3 < len(empty) and
                     empty[i // 3])
        found += [f"{path}: {name}[{i}] = {v}"
                  for i, v in enumerate(values) if bad(v, undefined(i))]
    return found


def main():
    folder = pathlib.Path(sys.argv[1])
    checks = {".csv": check_csv, ".vtp": check_vtp, ".vti": check_vti}
    files = [p for p in sorted(folder.rglob("*")) if p.suffix in checks and p.is_file()]
    found = [line for p in files for line in checks[p.suffix](p)]
    for line in found[:20]:
        print(line)
    print(f"{len(files)} files read back, {len(found)} non-finite numbers")
    return 1 if found or not files else 0


if __name__ == "__main__":
    sys.exit(main())
