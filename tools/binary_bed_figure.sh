#!/usr/bin/env bash
# The figures of the vibrated binary bed in docs/validation/seeds.md, from four runs of
# scenes/vibrated_binary_bed.ini (vibrated and gas only, from mixed and segregated starts): the
# Lacey index of the glass against time, horizontal and vertical, and the spectra of the bed
# height and of the pressure drop between the probes, vibrated against gas only.
# usage: tools/binary_bed_figure.sh VIB_MIXED GAS_MIXED VIB_SEG GAS_SEG OUT_DIR [BEDLAM] [FROM]
set -euo pipefail
vm=$1; gm=$2; vs=$3; gs=$4; out=$5; bedlam=${6:-build/bedlam}; from=${7:-1.5}
mkdir -p "$out"
gnuplot <<GP
set terminal pngcairo size 1000,520 font 'DejaVu Sans,11'
set output '$out/binary_bed_lacey.png'
set datafile separator ','
set multiplot layout 1,2
set xlabel 'time [s]'
set grid
set yrange [0:1.2]
set key left center
set title 'vertical mixing (Lacey index on layers)'
set ylabel 'Lacey index of the glass'
plot '$vm/species.csv' every ::1 using 1:'lacey_vertical' with lines lw 2 lc rgb '#c03030' title 'vibrated, mixed start', \
     '$gm/species.csv' every ::1 using 1:'lacey_vertical' with lines lw 2 lc rgb '#3060c0' title 'gas only, mixed start', \
     '$vs/species.csv' every ::1 using 1:'lacey_vertical' with lines lw 2 dt 2 lc rgb '#c03030' title 'vibrated, segregated start', \
     '$gs/species.csv' every ::1 using 1:'lacey_vertical' with lines lw 2 dt 2 lc rgb '#3060c0' title 'gas only, segregated start'
set title 'horizontal mixing (Lacey index on columns)'
plot '$vm/species.csv' every ::1 using 1:'lacey_horizontal' with lines lw 2 lc rgb '#c03030' title 'vibrated, mixed start', \
     '$gm/species.csv' every ::1 using 1:'lacey_horizontal' with lines lw 2 lc rgb '#3060c0' title 'gas only, mixed start', \
     '$vs/species.csv' every ::1 using 1:'lacey_horizontal' with lines lw 2 dt 2 lc rgb '#c03030' title 'vibrated, segregated start', \
     '$gs/species.csv' every ::1 using 1:'lacey_horizontal' with lines lw 2 dt 2 lc rgb '#3060c0' title 'gas only, segregated start'
unset multiplot
GP
for run in "$vm" "$gm"; do
  for column in bed_height probe_pressure_drop; do
    "$bedlam" analyze spectrum "$run" --column $column --from "$from" --fmin 0.5 --fmax 20 \
      --out "$run/analysis/$column" --no-plots
  done
done
gnuplot <<GP
set terminal pngcairo size 1000,460 font 'DejaVu Sans,11'
set output '$out/binary_bed_spectra.png'
set datafile separator ','
set multiplot layout 1,2
set xlabel 'frequency [Hz]'
set ylabel 'power (normalised to its peak)'
set grid
set xrange [0:15]
set key top right
set arrow from 5, graph 0 to 5, graph 1 nohead dt 2 lc rgb '#808080'
do for [c in 'bed_height probe_pressure_drop'] {
  set title (c eq 'bed_height' ? 'bed height' : 'pressure drop between the probes at 5 and 35 mm')
  stats '$vm/analysis/'.c.'/spectrum_'.c.'.csv' every ::1 using 2 nooutput name 'V'
  stats '$gm/analysis/'.c.'/spectrum_'.c.'.csv' every ::1 using 2 nooutput name 'G'
  plot '$vm/analysis/'.c.'/spectrum_'.c.'.csv' every ::1 using 1:(\$2/V_max) with lines lw 2 lc rgb '#c03030' title 'vibrated (5 Hz)', \
       '$gm/analysis/'.c.'/spectrum_'.c.'.csv' every ::1 using 1:(\$2/G_max) with lines lw 2 lc rgb '#3060c0' title 'gas only'
}
unset multiplot
GP
