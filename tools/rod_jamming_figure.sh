#!/usr/bin/env bash
# The rod figure of docs/validation/rheology.md: the contact pressure over rho d_v^2 (shear
# rate)^2 against the solids fraction for the three frictions, beside the dense branch of the
# thesis's collapse at 100/s (Mahajan 2019, eq. 6.3, a2 = 39.56, b2 = 82.64, k_n = 6e5 N/m, with
# its nu_cr of 0.65, 0.63, 0.59; dotted, the branch's inertial limit), and the contact friction
# against the inertial number beside its eq. 6.4 (0.57 I^0.22 + 0.36, fitted for friction 0.46).
# Each CSV is the rheology.csv that `bedlam analyze rheology RUN... --out DIR` writes for one
# friction's runs.
# usage: tools/rod_jamming_figure.sh MU0.csv MU0.1.csv MU0.46.csv OUT_DIR
set -euo pipefail
[ $# -eq 4 ] || { sed -n '2,9p' "$0"; exit 2; }
m0=$1; m1=$2; m4=$3; out=$4
mkdir -p "$out"
gnuplot <<GP
set terminal pngcairo size 1000,460 font 'DejaVu Sans,11'
set output '$out/shear_rods_jamming.png'
set datafile separator ','
set datafile columnheaders
set multiplot layout 1,2
a = 1.0 / 82.64**2
rho = 1395.0; dv = 5.295e-3; kn = 6e5; rate = 100.0
law(nu, cr) = nu < cr ? a * (cr - nu)**-4 : 1/0
gss(D) = rate * dv * D**(-7.0/3) / sqrt(kn / (rho * dv))
soft(nu, cr) = nu < cr ? kn / dv * (cr - nu)**(2.0/3) * (gss(cr - nu) / (39.56 * gss(cr - nu) + 82.64))**2 / (rho * dv**2 * rate**2) : 1/0
set logscale y
set grid
set key bottom right
set xrange [0.38:0.72]
set yrange [0.05:1e4]
set xlabel 'solids fraction'
set ylabel 'contact pressure / (rho d_v^2 shear rate^2)'
set samples 400
plot '$m0' using (column('solids_fraction')):(column('contact_pressure_scaled')) with points pt 7 ps 1.3 lc rgb '#3060c0' title 'friction 0', \
     '$m1' using (column('solids_fraction')):(column('contact_pressure_scaled')) with points pt 5 ps 1.3 lc rgb '#30a050' title 'friction 0.1', \
     '$m4' using (column('solids_fraction')):(column('contact_pressure_scaled')) with points pt 9 ps 1.5 lc rgb '#c03030' title 'friction 0.46', \
     soft(x, 0.65) with lines dt 2 lw 1.5 lc rgb '#3060c0' title 'thesis eq. 6.3, nu_{cr} 0.65', \
     soft(x, 0.63) with lines dt 2 lw 1.5 lc rgb '#30a050' title 'thesis eq. 6.3, nu_{cr} 0.63', \
     soft(x, 0.59) with lines dt 2 lw 1.5 lc rgb '#c03030' title 'thesis eq. 6.3, nu_{cr} 0.59', \
     law(x, 0.65) with lines dt 3 lw 1 lc rgb '#3060c0' notitle, \
     law(x, 0.63) with lines dt 3 lw 1 lc rgb '#30a050' notitle, \
     law(x, 0.59) with lines dt 3 lw 1 lc rgb '#c03030' notitle
unset logscale y
set logscale x
set xrange [0.02:5]
set yrange [0:1.2]
set xlabel 'inertial number I'
set ylabel 'contact friction sigma_c / P_c'
set key top left
plot '$m0' using (column('inertial_number')):(column('contact_friction')) with points pt 7 ps 1.3 lc rgb '#3060c0' title 'friction 0', \
     '$m1' using (column('inertial_number')):(column('contact_friction')) with points pt 5 ps 1.3 lc rgb '#30a050' title 'friction 0.1', \
     '$m4' using (column('inertial_number')):(column('contact_friction')) with points pt 9 ps 1.5 lc rgb '#c03030' title 'friction 0.46', \
     0.57 * x**0.22 + 0.36 with lines dt 2 lw 1.5 lc rgb '#c03030' title 'thesis, friction 0.46 (eq. 6.4)'
unset multiplot
GP
echo "wrote $out/shear_rods_jamming.png"
