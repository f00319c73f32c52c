#!/usr/bin/env bash
# The figure of the packed rod bed in docs/theory-rods.md: left, the rods' settling in a run of
# scenes/rod_bed_packed.ini (kinetic energy per rod over m g d, and the mean |cos| of their axes
# to the vertical); right, the packed bed's tilt histogram from test_rod_bed against random axes.
# usage: tools/rod_bed_figure.sh RUN_DIR TEST_OUTPUT OUT_PNG
#   RUN_DIR      bedlam run scenes/rod_bed_packed.ini --set run.end_time=0.6 --out RUN_DIR
#   TEST_OUTPUT  the printout of build/tests/test_rod_bed (or of ctest -R test_rod_bed -V)
set -euo pipefail
run=$1; test_out=$2; png=$3
mgd=$(awk 'BEGIN { printf "%.6e", 8070 * 1.3558e-5 * 9.81 * 1.5e-3 }') # m g d of all the rods
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# "   0-10 deg   0.360  (0.174)": the bin's centre, bedlam's share, random axes' share.
awk '/ deg / { sub(/^[0-9]+: */, ""); $0 = $0; split($1, b, "-"); gsub(/[()]/, "", $4); print (b[1] + b[2]) / 2, $3, $4 }' \
  "$test_out" > "$tmp/tilt.dat"
test -s "$tmp/tilt.dat" || { echo "no tilt histogram in $test_out" >&2; exit 2; }
gnuplot <<GP
set terminal pngcairo size 1300,480 font 'DejaVu Sans,11'
set output '$png'
set multiplot layout 1,2
set datafile separator ','
set xlabel 'time [s]'
set ylabel 'kinetic energy per rod [m g d]'
set y2label 'mean |cos| of the axis to the vertical'
set logscale y
set yrange [1e-11:1e4]
set format y '10^{%L}'
set ytics nomirror
set y2tics
set y2range [0:0.6]
set key bottom left opaque box
set grid
plot '$run/diagnostics.csv' every ::1 using 1:((\$5 + \$6) / $mgd) with lines lw 2 lc rgb '#c03030' title 'kinetic energy (translation and rotation)', \
     '' every ::1 using 1:(column('rod_vertical_cos')) axes x1y2 with lines lw 2 lc rgb '#3060c0' title 'mean |cos| to the vertical (random: 0.5)'
unset logscale y
unset y2tics
unset y2label
set format y '%g'
set datafile separator whitespace
set xlabel 'angle of the axis to the horizontal [deg]'
set ylabel 'share of the rods'
set xrange [0:90]
set key top right opaque box
set yrange [0:0.4]
set xtics 10
set style fill solid 0.6 border -1
set boxwidth 4
plot '$tmp/tilt.dat' using (\$1 - 2):2 with boxes lc rgb '#c08030' title 'packed bed (bedlam)', \
     '' using (\$1 + 2):3 with boxes lc rgb '#8090a0' title 'random axes'
unset multiplot
GP
echo "wrote $png"
