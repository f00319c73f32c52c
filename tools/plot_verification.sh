#!/usr/bin/env bash
# Plots the restitution error against the time step from test_bounce's table, and the oblique
# impact's rebound against incidence from test_oblique's curve (gnuplot).
# Usage: tools/plot_verification.sh [build dir]   -> docs/img/restitution_vs_dt.png, oblique_psi.png
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
data=$(mktemp)
"$build/tests/test_bounce" | awk -F'|' '/^\| (linear|hertz) \| [0-9.]+ \| 0.5 \|/ {
  gsub(/ /, "", $2); gsub(/ /, "", $3);
  printf "%s,e=%s", $2, $3;
  for (k = 5; k <= 9; ++k) { gsub(/ /, "", $k); printf " %s", $k }
  printf "\n" }' > "$data"
gnuplot <<GP
set terminal pngcairo size 800,560 font "DejaVu Sans,11" noenhanced
set output "docs/img/restitution_vs_dt.png"
set logscale xy
set xlabel "time step dt / t_c"
set format y "%.0e"
set ylabel "worst relative error of the restitution"
set title "Sphere-wall impact: restitution error vs time step (worst over 8 contact phases)"
set key left top
set grid
set xrange [0.002:0.05]
plot for [i=1:6] "< awk 'NR==" . i . " {split(\"0.04 0.02 0.01 0.005 0.0025\", d, \" \"); for (k = 2; k <= 6; ++k) print d[k-1], \$k; print \"\"}' $data" \
        using 1:2 with linespoints lw 2 title system("awk 'NR==" . i . " {print \$1}' $data"), \
     0.5*x title "first order" dashtype 2 lc rgb "gray"
GP
rm -f "$data"
echo "wrote docs/img/restitution_vs_dt.png"

# The oblique impact: reduced rebound psi2 against reduced incidence psi1 (test_oblique's curve),
# bedlam beside Maw, Barber & Fawcett's theory and the rigid-body line of gross sliding.
data=$(mktemp)
"$build/tests/test_oblique" | awk '/^curve / { print $2, $3, $4 }' > "$data"
gnuplot <<GP
set terminal pngcairo size 800,560 font "DejaVu Sans,11" noenhanced
set output "docs/img/oblique_psi.png"
set xlabel "reduced incidence psi1 = kappa v_t1 / (mu v_n1)"
set ylabel "reduced rebound psi2 = kappa v_t2 / (mu v_n1)"
set title "Elastic sphere on a plane, steel (nu = 0.3), Hertz-Mindlin, mu = 0.3"
set key left top
set grid
chi = 0.7 / 1.7 * 3.5
plot "$data" using 1:3 with lines lw 2 lc rgb "black" title "Maw, Barber & Fawcett (theory, by MDR)", \
     "$data" using 1:2 with linespoints lw 2 pt 7 ps 0.6 lc rgb "#c03030" title "bedlam, dt = t_c/100", \
     (x >= 4 * chi - 1 ? x - 4 * chi : 1/0) with lines dashtype 2 lc rgb "gray" title "rigid body, gross sliding"
GP
rm -f "$data"
echo "wrote docs/img/oblique_psi.png"
