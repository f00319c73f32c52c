#!/usr/bin/env bash
# The figure of Goldschmidt's binary bed by the multi-fluid model in docs/validation/tfm.md:
# Sun's segregation percentage s_p against time of four runs of
# scenes/tfm_goldschmidt_binary.ini (1.30 and 1.00 m/s, each without and with particle
# rotation), and each run's s_p averaged over 10-20 s with the standard error of ten blocks of
# 1 s, and the first time s_p reaches 0.3.
# usage: tools/tfm_binary_figure.sh RUN_1.30 RUN_1.30_ROT RUN_1.00 RUN_1.00_ROT OUT_DIR
set -euo pipefail
a=$1; b=$2; c=$3; d=$4; out=$5
mkdir -p "$out"
for run in "$a" "$b" "$c" "$d"; do
  awk -F, 'NR==1 { for (i = 1; i <= NF; i++) { if ($i == "segregation") s = i; if ($i == "time") t = i }; next }
           !reach && $s >= 0.3 { reach = $t }
           $t >= 10 && $t <= 20 { k = int($t - 10); if (k > 9) k = 9; sum_k[k] += $s; n[k]++ }
           END { for (k = 0; k < 10; ++k) { m = sum_k[k] / n[k]; sum += m; sq += m * m }
                 mean = sum / 10; se = sqrt((sq / 10 - mean * mean) / 9)
                 printf "%s: s_p over 10-20 s %.3f, standard error %.3f; first at 0.3: %s s\n", FILENAME, mean, se, reach ? reach : "never" }' \
    "$run/diagnostics.csv"
done
gnuplot <<GP
set terminal pngcairo size 760,480 font 'DejaVu Sans,11'
set output '$out/tfm_binary_segregation.png'
set datafile separator ','
set xlabel 'time [s]'
set ylabel 'segregation percentage s_p'
set grid
set key top left
set yrange [-0.05:1]
plot '$a/diagnostics.csv' every ::1 using 1:(column('segregation')) with lines lw 1.4 lc rgb '#c03030' title '1.30 m/s, no rotation', \
     '$b/diagnostics.csv' every ::1 using 1:(column('segregation')) with lines lw 1.4 dt 2 lc rgb '#c03030' title '1.30 m/s, rotation (e_{eff} 0.83 / 0.86)', \
     '$c/diagnostics.csv' every ::1 using 1:(column('segregation')) with lines lw 1.4 lc rgb '#3060c0' title '1.00 m/s, no rotation', \
     '$d/diagnostics.csv' every ::1 using 1:(column('segregation')) with lines lw 1.4 dt 2 lc rgb '#3060c0' title '1.00 m/s, rotation'
GP
