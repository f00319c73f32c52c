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
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Per cycle: the bead's height over the surface (twice the small spheres' mean height), averaged
# over the cycle, which is steadier than a snapshot when the bed flies.
for r in "$r05" "$r01" "$r0"; do
  awk -F, -v s=$start -v p=$period 'NR > 1 { c = ($1 - s) / p; if (c < 0) next; k = int(c)
      r[k] += $7 / (2 * $3); n[k]++; if (k > m) m = k }
      END { for (k = 0; k <= m; k++) if (n[k]) printf "%d,%.4f\n", k, r[k] / n[k] }' \
      "$r/species.csv" > "$tmp/$(basename "$r").csv"
done
c05=$tmp/$(basename "$r05").csv; c01=$tmp/$(basename "$r01").csv; c0=$tmp/$(basename "$r0").csv
gnuplot <<GP
set terminal pngcairo size 1300,520 font 'DejaVu Sans,11'
set output '$out/brazil_nut_rise.png'
set multiplot layout 1,2
set datafile separator ','
set xlabel 'shaking cycles'
set ylabel 'height above the base [d_0]'
set key top left opaque box
set grid
set xrange [0:*]
set yrange [0:230]
c(t) = (t - $start) / $period
plot '$r05/species.csv' every ::1 using (c(\$1)):(\$7/$d0) with lines lw 2 lc rgb '#c03030' title 'intruder, wall friction 0.5', \
     '$r01/species.csv' every ::1 using (c(\$1)):(\$7/$d0) with lines lw 2 lc rgb '#3060c0' title 'intruder, wall friction 0.1', \
     '$r0/species.csv' every ::1 using (c(\$1)):(\$7/$d0) with lines lw 2 lc rgb '#30a030' title 'intruder, wall friction 0', \
     '$r05/species.csv' every ::1 using (c(\$1)):(2*\$3/$d0) with lines lw 1 dt 2 lc rgb '#606060' title 'surface (twice the seeds'' mean height), wall friction 0.5', \
     '$r0/species.csv' every ::1 using (c(\$1)):(2*\$3/$d0) with lines lw 1 dt 2 lc rgb '#80c080' title 'bed surface, wall friction 0'
set ylabel 'bead height / surface height, mean over the cycle'
set yrange [0:1.1]
set xrange [0:40]
plot '$c05' using (\$1+0.5):2 with linespoints lw 2 pt 7 ps 0.5 lc rgb '#c03030' title 'wall friction 0.5', \
     '$c01' using (\$1+0.5):2 with linespoints lw 2 pt 7 ps 0.5 lc rgb '#3060c0' title 'wall friction 0.1', \
     '$c0' using (\$1+0.5):2 with linespoints lw 2 pt 7 ps 0.5 lc rgb '#30a030' title 'wall friction 0'
unset multiplot
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
