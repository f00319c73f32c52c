#!/usr/bin/env bash
# The spheres' figure of docs/validation/rheology.md: Lees-Edwards shear of smooth spheres
# (restitution E) against the solids fraction, by the numbers that do not depend on the
# solids fraction in the dilute limit — the reduced viscosity eta/eta0 and reduced shear rate
# g/nu0 at each run's own temperature (eta0 = (5/96) rho d sqrt(pi T), nu0 = rho nu T/eta0) —
# and N1/p, beside the kinetic theory of Lun et al. (1984) (eta/eta0 = F, g/nu0 = (5/96)
# sqrt(4608 h (1 - h) g0 / 5F), h = (1 + E)/2, Carnahan-Starling g0; N1 = 0) and the limit
# nu -> 0 of the Boltzmann equation's steady shear solved by Grad's method
# (bdl_grad_dilute_shear: (beta - zeta)/beta^2, sqrt((3/2) zeta beta^2/(beta - zeta)),
# 3 zeta/beta, zeta = (5/12)(1 - E^2), beta = (1 + E)(3 - E)/4). CSV is the rheology.csv of
# `bedlam analyze rheology RUN... --restitution E --out DIR`.
# usage: tools/shear_dilute_figure.sh CSV E OUT_DIR
set -euo pipefail
[ $# -eq 3 ] || { sed -n '2,12p' "$0"; exit 2; }
csv=$1; e=$2; out=$3
mkdir -p "$out"
gnuplot <<GP
set terminal pngcairo size 1000,440 font 'DejaVu Sans,11'
set output '$out/shear_dilute.png'
set datafile separator ','
set datafile columnheaders
e = $e
h = (1 + e) / 2
z = 5.0 / 12 * (1 - e * e); b = (1 + e) * (3 - e) / 4
g0(n) = (1 - n / 2) / (1 - n)**3
aa(n) = 1.6 * h * n * g0(n)
F(n) = (1 + aa(n)) * (1 + aa(n) * (3 * h - 2)) / (h * (2 - h) * g0(n)) + 768 / (25 * pi) * h * n * n * g0(n)
rate(n) = 5.0 / 96 * sqrt(4608 * h * (1 - h) * g0(n) / (5 * F(n)))
set multiplot layout 1,2
set grid
set xrange [0:0.42]
set xlabel 'solids fraction'
set samples 200
set logscale y
set yrange [0.5:10]
set ylabel 'eta / eta_0 at the run''s T'
set key top left
plot '$csv' using (column('solids_fraction')):(column('reduced_viscosity')) with points pt 7 ps 1.3 lc rgb '#30a050' title 'bedlam, Lees-Edwards', \
     F(x) with lines dt 2 lw 1.5 lc rgb '#30a050' title 'Lun et al. (1984)', \
     '+' using (0.003):((b - z) / b**2) every ::0::0 with points pt 6 ps 2.2 lw 2 lc rgb '#000000' title 'Boltzmann (Grad), nu -> 0'
unset logscale y
set yrange [0:1.05]
set ylabel ''
set key top right
plot '$csv' using (column('solids_fraction')):(column('reduced_shear_rate')) with points pt 7 ps 1.3 lc rgb '#c03030' title 'shear rate / nu_0', \
     rate(x) with lines dt 2 lw 1.5 lc rgb '#c03030' title 'shear rate / nu_0, Lun et al.', \
     '+' using (0.003):(sqrt(1.5 * z * b**2 / (b - z))) every ::0::0 with points pt 6 ps 2.2 lw 2 lc rgb '#c03030' title 'shear rate / nu_0, Boltzmann (Grad)', \
     '$csv' using (column('solids_fraction')):(column('n1')/column('pressure')) with points pt 5 ps 1.3 lc rgb '#804080' title 'N1 / p (Lun et al.: 0)', \
     '+' using (0.003):(3 * z / b) every ::0::0 with points pt 4 ps 2.2 lw 2 lc rgb '#804080' title 'N1 / p, Boltzmann (Grad)'
unset multiplot
GP
echo "wrote $out/shear_dilute.png"
