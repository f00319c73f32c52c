#!/usr/bin/env bash
# The figure of Goldschmidt's bed by the two-fluid model in docs/validation/tfm.md: the mean
# particle height against time of two runs of scenes/tfm_goldschmidt_bed.ini, at 1.92 and
# 2.56 m/s (1.5 and 2.0 U_mf), with the thesis's model (without rotation) and the experiment's
# time averages over 5-10 s; and those runs' averages over 5-10 s with the standard error of ten
# blocks of 0.5 s.
# usage: tools/tfm_goldschmidt_figure.sh RUN_1.5 RUN_2.0 OUT_DIR
set -euo pipefail
a=$1; b=$2; out=$3
mkdir -p "$out"
for run in "$a" "$b"; do
  awk -F, 'NR==1 { for (i = 1; i <= NF; i++) { if ($i == "mean_height") h = i; if ($i == "time") t = i }; next }
           $t >= 5 && $t <= 10 { k = int(($t - 5) / 0.5); if (k > 9) k = 9; s[k] += $h; n[k]++ }
           END { for (k = 0; k < 10; ++k) { m = s[k] / n[k]; sum += m; sq += m * m }
                 mean = sum / 10; se = sqrt((sq / 10 - mean * mean) / 9)
                 printf "%s: mean particle height over 5-10 s %.4f m, standard error %.4f m\n", FILENAME, mean, se }' \
    "$run/diagnostics.csv"
done
gnuplot <<GP
set terminal pngcairo size 760,480 font 'DejaVu Sans,11'
set output '$out/tfm_goldschmidt_height.png'
set datafile separator ','
set xlabel 'time [s]'
set ylabel 'mean particle height [cm]'
set grid
set key top right
set yrange [6:24]
plot '$a/diagnostics.csv' every ::1 using 1:(100*column('mean_height')) with lines lw 1.2 lc rgb '#c03030' title '1.92 m/s (1.5 U_{mf})', \
     '$b/diagnostics.csv' every ::1 using 1:(100*column('mean_height')) with lines lw 1.2 lc rgb '#3060c0' title '2.56 m/s (2.0 U_{mf})', \
     9.21 with lines dt 2 lw 2 lc rgb '#c03030' title 'Sun, two-fluid model, 1.5 U_{mf}', \
     11.02 with lines dt 2 lw 2 lc rgb '#3060c0' title 'Sun, two-fluid model, 2.0 U_{mf}', \
     11.40 with lines dt 3 lw 2 lc rgb '#e08080' title 'experiment, 1.5 U_{mf}', \
     11.80 with lines dt 3 lw 2 lc rgb '#80a0e0' title 'experiment, 2.0 U_{mf}'
GP
