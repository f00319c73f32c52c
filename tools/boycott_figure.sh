#!/usr/bin/env bash
# The figure of the Boycott effect in docs/parcels.md from docs/img/parcels_boycott.dat: the
# interface of the 35-degree column (bedlam verify parcel_boycott) against the Ponder-Nakamura-
# Kuroda estimate without and with the sediment, and the same column upright against the model's
# hindered speed.
# usage: tools/boycott_figure.sh [DATA] [OUT_PNG]
set -euo pipefail
data=${1:-docs/img/parcels_boycott.dat}; out=${2:-docs/img/parcels_boycott.png}
gnuplot <<GP
set terminal pngcairo size 900,560 font 'DejaVu Sans,11'
set output '$out'
set xlabel 't [s]'
set ylabel "interface along the column's axis [cm]"
set grid
set key bottom left
set xrange [0:820]
set yrange [0:55]
plot '$data' using 1:3 with lines lw 2 lc rgb 'black' title "Ponder-Nakamura-Kuroda, 35 degrees (model's v0)", \
     '$data' using 1:4 with lines lw 2 dt 4 lc rgb '#707070' title 'the same above the sediment (model A, mean 0.511)', \
     '$data' using 1:2 with points pt 7 ps 0.8 lc rgb '#d03030' title 'parcels, 35 degrees', \
     '$data' using 1:6 with lines lw 2 dt 2 lc rgb 'black' title "upright, the model's hindered speed v0", \
     '$data' using 1:5 with points pt 6 ps 0.8 lc rgb '#3070c0' title 'parcels upright, random fill'
GP
