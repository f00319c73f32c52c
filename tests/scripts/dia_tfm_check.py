#!/usr/bin/env python3
"""The truth beside a synthetic camera's first image of a solids phase on the grid (the bed of
tests/scenes/tfm_camera.ini at rest: 15 cm at a solids fraction of 0.583 under 15 cm of
freeboard in view): every value finite, the image cells of the bed (1 cm, the grid's cells)
at the field's fraction through the depth, those above it empty. Usage: dia_tfm_check.py CELLS.csv"""
import csv
import math
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 15 * 30, f"{len(rows)} image cells, expected 450"
bad = [r for r in rows if not all(math.isfinite(float(v)) for v in r.values())]
assert not bad, f"values not finite in {len(bad)} cells, first {bad[0]}"
bed = [float(r["solids_depth"]) for r in rows if 16 <= int(r["row"]) <= 28]
free = [float(r["solids_depth"]) for r in rows if int(r["row"]) <= 13]
area = [float(r["area_fraction"]) for r in rows if 16 <= int(r["row"]) <= 28]
mean = sum(bed) / len(bed)
print(f"bed: solids fraction {mean:.4f} (field 0.583), cells {min(bed):.3f} to {max(bed):.3f}, "
      f"visible area {min(area):.3f} to {max(area):.3f}; freeboard at most {max(free):.3g}")
assert abs(mean - 0.583) < 0.01, "the bed's mean fraction is not the field's"
assert max(abs(b - 0.583) for b in bed) < 0.06, "a cell's fraction is far from the field's"
assert min(area) > 0.5, "the bed does not show"
assert max(free) == 0.0, "solids in the freeboard"
