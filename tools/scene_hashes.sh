#!/usr/bin/env bash
# Runs every scene of scenes/ for a number of steps on 1 and 2 threads and prints, per scene and
# thread count, the exit code, the md5 of the checkpoint (the whole state) and the md5 of every
# other output (diagnostics without the wall-clock column, series, VTK, frames, camera images).
# Two builds whose lines are equal computed the same bits; a refactoring shows it this way.
#
#   tools/scene_hashes.sh BEDLAM OUTDIR [STEPS] > hashes.txt     (STEPS default 1000)
set -uo pipefail
bin=$1 out=$2 steps=${3:-1000}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
for scene in "$here"/scenes/*.ini; do
  name=$(basename "$scene" .ini)
  for threads in 1 2; do
    dir=$out/$name.$threads
    rm -rf "$dir"
    "$bin" run "$scene" --steps "$steps" --threads "$threads" --out "$dir" --quiet \
      > /dev/null 2> "$dir.err"
    rc=$?
    state=$(md5sum < "$dir/checkpoint/state.bdlckpt" | cut -c1-16)
    outputs=$( (cut -d, -f1,2,4- "$dir/diagnostics.csv"
                cd "$dir" && find . -type f ! -name run.log ! -name diagnostics.csv \
                  ! -path './checkpoint/*' | sort | xargs md5sum) | md5sum | cut -c1-16)
    echo "$name $threads rc=$rc $state $outputs"
  done
done
