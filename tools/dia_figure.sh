#!/usr/bin/env bash
# The figure of docs/dia.md: a synthetic camera image beside the solids fraction the camera sees
# (f2D per image cell, after thresholding) and the true solids fraction behind it (f3D over the
# depth), from a run's dia/NAME folder and a `bedlam calibrate` points.csv.
# usage: tools/dia_figure.sh DIA_DIR POINTS.csv FRAME OUT.png
set -euo pipefail
dir=$1; points=$2; frame=$3; out=$4
stem=$(printf '%s/frame_%06d' "$dir" "$frame")
image=${stem}_a.png; [ -f "$image" ] || image=${stem}.png
read -r nx ny < <(grep -o '"cells": \[[0-9]*, [0-9]*\]' "$dir/camera.json" | tr -dc '0-9 ' | awk '{print $1, $2}')
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# f2D per cell of this frame (cells outside the bed: 0), as "column row value".
awk -F, -v f="$frame" -v nx="$nx" -v ny="$ny" 'NR > 1 && $1 == f { v[$2] = $3 }
  END { for (c = 0; c < nx * ny; ++c) print c % nx, int(c / nx), (c in v ? v[c] : 0) }' \
  "$points" > "$tmp/f2d.dat"
awk -F, 'NR > 1 { print $1, $2, $8 }' "${stem}_cells.csv" > "$tmp/f3d.dat"
gnuplot <<GP
set terminal pngcairo size 1000,1000 font 'DejaVu Sans,11'
set output '$out'
set multiplot layout 1,3 title 'frame $frame of a bubbling bed: the image, what thresholding sees, and the truth'
unset key; unset xtics; unset ytics
set size ratio -1
set title 'camera image'
plot '$image' binary filetype=png with rgbimage
set palette defined (0 'black', 1 'white')
set cbrange [0:1]
set xrange [-0.5:$nx-0.5]; set yrange [$ny-0.5:-0.5]
set title 'f_{2D} (particle pixels)'
plot '$tmp/f2d.dat' using 1:2:3 with image
set cbrange [0:0.6]
set title 'f_{3D} over the depth (truth)'
plot '$tmp/f3d.dat' using 1:2:3 with image
unset multiplot
GP
