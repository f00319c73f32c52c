#!/usr/bin/env bash
# The figures of the Goldschmidt bed in docs/validation/seeds.md, from runs of
# scenes/goldschmidt_bed_3d.ini at 1.92 and 2.56 m/s (1.5 and 2.0 U_mf) and of
# scenes/goldschmidt_bed.ini (the single layer): the mean particle height against time with the
# experiment's time averages, and the solids fraction against height averaged over 5-10 s
# (bedlam analyze profile).
# usage: tools/goldschmidt_figure.sh RUN3D_1.5 RUN3D_2.0 LAYER_A LAYER_B OUT_DIR [BEDLAM]
#        (LAYER_A and LAYER_B: single-layer runs, labelled by their inlet velocity)
set -euo pipefail
a=$1; b=$2; la=$3; lb=$4; out=$5; bedlam=${6:-build/bedlam}
mkdir -p "$out"
for run in "$a" "$b" "$la" "$lb"; do
  "$bedlam" analyze profile "$run" --from 5 --to 10 --out "$run/analysis/profile" --no-plots
done
inlet() { awk -F, 'NR==1 { for (i = 1; i <= NF; i++) if ($i == "inlet_velocity") c = i; next }
                  { v = $c } END { printf "%.2f", v }' "$1/diagnostics.csv"; }
ua=$(inlet "$la"); ub=$(inlet "$lb")
gnuplot <<GP
set terminal pngcairo size 1000,480 font 'DejaVu Sans,11'
set output '$out/goldschmidt_height.png'
set datafile separator ','
set multiplot layout 1,2
set xlabel 'time [s]'
set ylabel 'mean particle height [cm]'
set grid
set key bottom right
set yrange [6:17]
set title 'real depth (1.5 cm, 24 000 spheres)'
plot '$a/diagnostics.csv' every ::1 using 1:(100*column('mean_height')) with lines lw 1.5 lc rgb '#c03030' title '1.92 m/s (1.5 U_{mf})', \
     '$b/diagnostics.csv' every ::1 using 1:(100*column('mean_height')) with lines lw 1.5 lc rgb '#3060c0' title '2.56 m/s (2.0 U_{mf})', \
     11.40 with lines dt 2 lw 2 lc rgb '#c03030' title 'experiment, 1.5 U_{mf} (5-10 s)', \
     11.80 with lines dt 2 lw 2 lc rgb '#3060c0' title 'experiment, 2.0 U_{mf} (5-10 s)'
set title 'single layer (4000 spheres)'
plot '$la/diagnostics.csv' every ::1 using 1:(100*column('mean_height')) with lines lw 1.5 lc rgb '#c03030' title '$ua m/s', \
     '$lb/diagnostics.csv' every ::1 using 1:(100*column('mean_height')) with lines lw 1.5 lc rgb '#3060c0' title '$ub m/s', \
     11.40 with lines dt 2 lw 2 lc rgb '#c03030' title 'experiment, 1.5 U_{mf}', \
     11.80 with lines dt 2 lw 2 lc rgb '#3060c0' title 'experiment, 2.0 U_{mf}'
unset multiplot
set output '$out/goldschmidt_profile.png'
set terminal pngcairo size 640,520 font 'DejaVu Sans,11'
set xlabel 'solids fraction (width-averaged, 5-10 s)'
set ylabel 'height [cm]'
set yrange [0:40]
set xrange [0:0.7]
set key top right
unset title
plot '$a/analysis/profile/profile.csv' every ::1 using 2:(100*\$1) with linespoints lw 2 pt 7 ps 0.6 lc rgb '#c03030' title 'real depth, 1.92 m/s', \
     '$b/analysis/profile/profile.csv' every ::1 using 2:(100*\$1) with linespoints lw 2 pt 7 ps 0.6 lc rgb '#3060c0' title 'real depth, 2.56 m/s', \
     '$la/analysis/profile/profile.csv' every ::1 using 2:(100*\$1) with linespoints lw 1.5 dt 2 pt 6 ps 0.6 lc rgb '#c03030' title 'single layer, $ua m/s', \
     '$lb/analysis/profile/profile.csv' every ::1 using 2:(100*\$1) with linespoints lw 1.5 dt 2 pt 6 ps 0.6 lc rgb '#3060c0' title 'single layer, $ub m/s'
GP
