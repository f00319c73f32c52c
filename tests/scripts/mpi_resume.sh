#!/usr/bin/env bash
# bedlam run under mpirun (tests/mpi.cmake): a run on 2 ranks to 0.02 s, its checkpoint resumed
# to 0.04 s on 1, 2 and 4 ranks and continued by an uninterrupted run on 2: the last rows of
# diagnostics.csv (the energies and their balance, coordination) agree to
# 1e-9 of each (the divided runs add their forces in another order than one process: their
# differences, near 1e-13 of the box after 1000 steps, grow slowly in a frictional bed).
# Usage: mpi_resume.sh MPIEXEC BEDLAM SCENE WORK
set -euo pipefail
mpiexec=$1 bedlam=$2 scene=$3 work=$4
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
rm -rf "$work" && mkdir -p "$work"
run() { # ranks, then bedlam run's options
  local n=$1; shift
  "$mpiexec" -np "$n" --oversubscribe "$bedlam" run "$scene" --quiet "$@"
}
run 2 --until 0.02 --out "$work/half"
run 2 --until 0.04 --out "$work/whole"
grep -q "ranks: 2 (MPI)" "$work/whole/run.log"
for n in 1 2 4; do
  cp -r "$work/half" "$work/resumed$n"
  run "$n" --until 0.04 --resume "$work/resumed$n" --out "$work/resumed$n"
done
# Columns 5-9: kinetic, rotational, potential, elastic energy, mean coordination; 12 the energy
# balance, 27 the springs' released work (each contact's booked once, on any rank count).
last() { tail -n 1 "$1/diagnostics.csv" | cut -d, -f1,2,5-9,12,27; }
reference=$(last "$work/whole")
echo "uninterrupted on 2 ranks: $reference"
for n in 1 2 4; do
  row=$(last "$work/resumed$n")
  echo "resumed on $n:              $row"
  python3 - "$reference" "$row" <<'PY'
import sys
a = [float(x) for x in sys.argv[1].split(',')]
b = [float(x) for x in sys.argv[2].split(',')]
assert a[1] == b[1], "steps differ: %s %s" % (a[1], b[1])
for x, y in zip(a, b):
    assert abs(x - y) <= 1e-9 * max(abs(x), abs(y), 1e-30), "%r vs %r" % (x, y)
PY
done
echo "mpi_resume: the continuations agree"
