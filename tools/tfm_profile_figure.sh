#!/usr/bin/env bash
# Width- and time-averaged solids fraction of each phase against height (Sun 2007, fig. 5.6)
# for two analyses of binary multi-fluid runs: `bedlam analyze profile RUN --from T --to T
# --out DIR` writes DIR/profile.csv (height, total, std, small, large).
# usage: tools/tfm_profile_figure.sh OUT.png DIR_A TITLE_A DIR_B TITLE_B
set -euo pipefail
out=$1; a=$2; ta=$3; b=$4; tb=$5
mkdir -p "$(dirname "$out")"
gnuplot <<GP
set terminal pngcairo size 760,520 font 'DejaVu Sans,11'
set output '$out'
set datafile separator ','
set xlabel 'solids fraction (layer mean over the width and 5-20 s)'
set ylabel 'height / 45 cm'
set grid
set key top right noenhanced
set yrange [0:0.5]
set xrange [0:0.6]
plot '$a/profile.csv' every ::1 using 4:(\$1/0.45) with lines lw 2 lc rgb '#c03030' title '$ta: small', \
     '$a/profile.csv' every ::1 using 5:(\$1/0.45) with lines lw 2 lc rgb '#3060c0' title '$ta: large', \
     '$b/profile.csv' every ::1 using 4:(\$1/0.45) with lines lw 2 dt 2 lc rgb '#c03030' title '$tb: small', \
     '$b/profile.csv' every ::1 using 5:(\$1/0.45) with lines lw 2 dt 2 lc rgb '#3060c0' title '$tb: large'
GP
