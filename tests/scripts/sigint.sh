#!/bin/sh
# Ctrl-C stops a run cleanly: exit code 1, diagnostics flushed, a checkpoint written, and the run
# can be resumed from it.
set -u
bedlam=$1; scene=$2; out=$3
rm -rf "$out"
"$bedlam" run "$scene" --quiet --out "$out" &
pid=$!
sleep 2
kill -INT $pid
wait $pid
rc=$?
[ $rc -eq 1 ] || { echo "exit code $rc, expected 1"; exit 1; }
[ -s "$out/checkpoint/state.bdlckpt" ] || { echo "no checkpoint"; exit 1; }
grep -q "interrupted" "$out/run.log" || { echo "run.log does not say interrupted"; exit 1; }
rows=$(wc -l < "$out/diagnostics.csv")
[ "$rows" -ge 2 ] || { echo "diagnostics not flushed"; exit 1; }
"$bedlam" run "$scene" --quiet --resume "$out" --steps 100 || { echo "resume failed"; exit 1; }
grep -q "resumed from" "$out/run.log" || { echo "no resume in run.log"; exit 1; }
echo "interrupted cleanly after $rows diagnostics rows; resumed"
