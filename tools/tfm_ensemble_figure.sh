#!/usr/bin/env bash
# An ensemble's segregation in docs/validation/tfm.md: Sun's s_p against time averaged over
# runs of scenes/tfm_goldschmidt_binary.ini that differ only in their step (each a realisation of
# the same chaotic bed), one line per model with a band of one standard error of the mean over
# its runs; and per model the mean over its runs of s_p over 5-20 s and 10-20 s with that
# standard error.
# usage: tools/tfm_ensemble_figure.sh OUT.png TITLE "RUN RUN ..." [TITLE "RUN RUN ..."]
# (every run must write diagnostics.csv at the same nominal times, [output]
# diagnostics_interval; at a fixed step a row's time is the step's nearest to it, and the first
# run's times label the mean. The script stops with exit code 2 when the row counts differ, a
# column is missing or a run has no rows from 10 to 20 s.)
set -euo pipefail
out=$1; shift
mkdir -p "$(dirname "$out")"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
colors=('#c03030' '#3060c0' '#309040' '#a060c0')
plot=""
k=0
while [ $# -ge 2 ]; do
  title=$1; runs=$2; shift 2
  # time, mean and standard error over the runs, row by row (the runs' rows must match)
  r=0
  rows=""
  for run in $runs; do
    awk -F, 'NR==1 { for (i = 1; i <= NF; i++) { if ($i == "segregation") s = i; if ($i == "time") t = i }
                     if (!s || !t) { print FILENAME ": no time or segregation column" > "/dev/stderr"; exit 2 }; next }
             { printf "%.6f %s\n", $t, $s }' "$run/diagnostics.csv" > "$work/run.$k.$(printf %04d $r)"
    n=$(wc -l < "$work/run.$k.$(printf %04d $r)")
    if [ -n "$rows" ] && [ "$n" != "$rows" ]; then
      echo "$run: $n rows of diagnostics.csv, the first run of '$title' has $rows" >&2; exit 2
    fi
    rows=$n
    r=$((r + 1))
  done
  paste -d' ' "$work"/run."$k".* | awk '{ n = NF / 2; sum = 0; sq = 0
        for (i = 2; i <= NF; i += 2) { sum += $i; sq += $i * $i }
        m = sum / n; v = n > 1 ? (sq - n * m * m) / (n - 1) : 0; if (v < 0) v = 0
        printf "%s %.6f %.6f\n", $1, m, sqrt(v / n) }' > "$work/mean.$k"
  for run in $runs; do
    awk -F, 'NR==1 { for (i = 1; i <= NF; i++) { if ($i == "segregation") s = i; if ($i == "time") t = i }; next }
             $t >= 5 && $t <= 20 { a += $s; na++ } $t >= 10 && $t <= 20 { b += $s; nb++ }
             END { if (!nb) { print FILENAME ": no rows from 10 to 20 s" > "/dev/stderr"; exit 2 }
                   printf "%.4f %.4f\n", a / na, b / nb }' "$run/diagnostics.csv"
  done | awk -v name="$title" '{ a[NR] = $1; b[NR] = $2; sa += $1; sb += $2 }
      END { n = NR; ma = sa / n; mb = sb / n
            for (i = 1; i <= n; i++) { va += (a[i] - ma) ^ 2; vb += (b[i] - mb) ^ 2 }
            if (n < 2) { printf "%s (1 run): s_p over 5-20 s %.3f; over 10-20 s %.3f\n", name, ma, mb; exit }
            printf "%s (%d runs): s_p over 5-20 s %.3f +- %.3f; over 10-20 s %.3f +- %.3f\n",
                   name, n, ma, sqrt(va / (n - 1) / n), mb, sqrt(vb / (n - 1) / n) }'
  c=${colors[$((k % 4))]}
  [ -n "$plot" ] && plot="$plot, "
  plot="$plot'$work/mean.$k' using 1:(\$2-\$3):(\$2+\$3) with filledcurves fs transparent solid 0.25 noborder lc rgb '$c' notitle"
  plot="$plot, '$work/mean.$k' using 1:2 with lines lw 1.5 lc rgb '$c' title '$title'"
  k=$((k + 1))
done
gnuplot <<GP
set terminal pngcairo size 760,480 font 'DejaVu Sans,11'
set output '$out'
set xlabel 'time [s]'
set ylabel 'segregation percentage s_p, mean over the runs'
set grid
set key top right noenhanced
set yrange [${YRANGE:--0.05:0.8}]
set xrange [0:20]
plot $plot
GP
