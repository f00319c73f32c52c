#!/usr/bin/env bash
# The figures of the Brazil-nut section of docs/validation/seeds.md, from three runs of
# scenes/brazil_nut.ini with wall friction 0.5, 0.1 and 0: the intruder's height against the
# shaking cycles for the three, and (bedlam analyze) the coordination number and the walls' force
# over a cycle and the force networks at the start of cycle 10 for wall friction 0.5.
# usage: tools/brazil_nut_figure.sh RUN_0.5 RUN_0.1 RUN_0 OUT_DIR [BEDLAM]
set -euo pipefail
r05=$1; r01=$2; r0=$3; out=$4; bedlam=${5:-build/bedlam}
d0=0.002 start=0.53377 period=0.133442
mkdir -p "$out"
gnuplot <<GP
set terminal pngcairo size 900,560 font 'DejaVu Sans,11'
set output '$out/brazil_nut_rise.png'
set datafile separator ','
set xlabel 'shaking cycles'
set ylabel 'height above the base [d_0]'
set key top left
set grid
set xrange [0:*]
c(t) = (t - $start) / $period
plot '$r05/species.csv' every ::1 using (c(\$1)):(\$7/$d0) with lines lw 2 lc rgb '#c03030' title 'intruder, wall friction 0.5', \
     '$r01/species.csv' every ::1 using (c(\$1)):(\$7/$d0) with lines lw 2 lc rgb '#3060c0' title 'intruder, wall friction 0.1', \
     '$r0/species.csv' every ::1 using (c(\$1)):(\$7/$d0) with lines lw 2 lc rgb '#30a030' title 'intruder, wall friction 0', \
     '$r05/species.csv' every ::1 using (c(\$1)):(2*\$3/$d0) with lines lw 1 dt 2 lc rgb '#606060' title 'bed surface (twice the mean height of the small spheres), 0.5'
GP
"$bedlam" analyze phase "$r05" --column mean_coordination --period $period --start $start \
  --from-cycle 5 --out "$out/phase" --bins 50
"$bedlam" analyze phase "$r05" --column wall_force --period $period --start $start \
  --from-cycle 5 --out "$out/phase" --bins 50 --below 0.0035
cp "$out/phase/phase_mean_coordination.png" "$out/brazil_nut_coordination.png"
cp "$out/phase/phase_wall_force.png" "$out/brazil_nut_wall_force.png"
# Cycle 10 starts at start + 10 periods: contact file round(t / period).
n=$(awk -v s=$start -v p=$period 'BEGIN { printf "%06d", int((s + 10 * p) / p + 0.5) }')
"$bedlam" analyze networks "$r05/contacts/contacts_$n.csv" --out "$out/phase"
cp "$out/phase/force_pdf.png" "$out/brazil_nut_force_pdf.png"
