#!/usr/bin/env bash
# The figure of Goldschmidt's binary bed by the multi-fluid model in docs/validation/tfm.md:
# Sun's segregation percentage s_p against time of runs of scenes/tfm_goldschmidt_binary.ini,
# and each run's s_p averaged over 5-20 s and over 10-20 s (with the standard error of ten
# blocks of 1 s), and the first time s_p reaches 0.3.
# usage: tools/tfm_binary_figure.sh OUT.png RUN TITLE [RUN TITLE ...]
# YRANGE (gnuplot's lo:hi) sets the s_p axis; -0.05:1 by default.
set -euo pipefail
out=$1; shift
mkdir -p "$(dirname "$out")"
plot=""
colors=('#c03030' '#c03030' '#3060c0' '#3060c0' '#309040' '#309040')
k=0
while [ $# -ge 2 ]; do
  run=$1; title=$2; shift 2
  awk -F, -v name="$title" 'NR==1 { for (i = 1; i <= NF; i++) { if ($i == "segregation") s = i; if ($i == "time") t = i }; next }
           !reach && $s >= 0.3 { reach = $t }
           $t >= 5 && $t <= 20 { all += $s; count++ }
           $t >= 10 && $t <= 20 { k = int($t - 10); if (k > 9) k = 9; sum_k[k] += $s; n[k]++ }
           END { b = 0; for (k = 0; k < 10; ++k) if (n[k]) { m = sum_k[k] / n[k]; sum += m; sq += m * m; ++b }
                 if (b < 2) { printf "%s: s_p over 5-20 s %.3f (no 10-20 s blocks)\n", name, count ? all / count : 0; exit }
                 mean = sum / b; se = sqrt((sq / b - mean * mean) / (b - 1))
                 printf "%s: s_p over 5-20 s %.3f; over 10-20 s %.3f, standard error %.3f; first at 0.3: %s s\n", name, all / count, mean, se, reach ? sprintf("%.1f", reach) : "never" }' \
    "$run/diagnostics.csv"
  [ -n "$plot" ] && plot="$plot, "
  dash=$(( k % 2 == 0 ? 1 : 2 ))
  plot="$plot'$run/diagnostics.csv' every ::1 using 1:(column('segregation')) with lines lw 1.3 dt $dash lc rgb '${colors[$((k % 6))]}' title '$title'"
  k=$((k + 1))
done
gnuplot <<GP
set terminal pngcairo size 760,480 font 'DejaVu Sans,11'
set output '$out'
set datafile separator ','
set xlabel 'time [s]'
set ylabel 'segregation percentage s_p'
set grid
set key top right noenhanced
set yrange [${YRANGE:--0.05:1}]
set xrange [0:*]
set autoscale xfix
plot $plot
GP
