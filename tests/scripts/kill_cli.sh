#!/bin/sh
# Nothing is lost to kill -9: a run killed at KILLS moments and resumed each time ends with the
# same files as one never interrupted.
#
#   kill_cli.sh BEDLAM SCENE WORK [KILLS]
#
# The reference runs SCENE (tests/scenes/kill.ini: every output a run writes) on one thread. The
# other run, on two threads, is killed KILLS times (default 20) and resumed from its folder after
# each kill, then to the end. The kills come at steps drawn from a fixed pseudo-random sequence,
# plus four chosen ones: the first step, the step of the second checkpoint (373: killed just
# before that checkpoint is written, so the run goes back to the first), the step after it, and
# the last step. Each kill is the run killing itself with SIGKILL, as kill -9 does from outside:
# BEDLAM_TEST_KILL_AT_STEP=N (read by src/run/outputs.c, for tests only) raises it at step N
# after that step's outputs, just before its checkpoint would be written. Killing at a step, not
# after a wall-clock time, makes the test repeatable.
#
# Then: diagnostics.csv holds the reference's rows, each once (every column but wall_seconds);
# the final checkpoint is the same bytes; and every other file -- species.csv, profile.csv, the
# VTK files and both .pvd collections, contact files, frames, the camera's images, truth and
# frames.csv, fields.vti and the sums beside the checkpoint -- is the same bytes, with no file
# missing, doubled or left over.
set -u
bedlam=$1
scene=$2
work=$3
kills=${4:-20}
rm -rf "$work"
mkdir -p "$work"
ref=$work/reference
run=$work/killed
fail() {
    echo "FAIL: $*"
    exit 1
}

"$bedlam" run "$scene" --quiet --threads 1 --out "$ref" || fail "the reference run failed"
total=$(tail -n 1 "$ref/diagnostics.csv" | cut -d, -f2)
[ "$total" -gt 1000 ] || fail "the reference ends at step $total"

# KILLS - 4 steps in [2, total - 1] from a linear congruential sequence, the four chosen ones,
# in order; distinct, so that every kill happens in a run of its own.
x=12345
steps="1 373 374 $total"
n=4
while [ "$n" -lt "$kills" ]; do
    x=$(((x * 1103515245 + 12345) % 2147483648))
    s=$((2 + (x / 65536) % (total - 2)))
    case " $steps " in *" $s "*) continue ;; esac
    steps="$steps $s"
    n=$((n + 1))
done
steps=$(echo "$steps" | tr ' ' '\n' | sort -n | tr '\n' ' ')
echo "kills at steps: $steps"

first=1
for s in $steps; do
    if [ $first -eq 1 ]; then
        BEDLAM_TEST_KILL_AT_STEP=$s "$bedlam" run "$scene" --quiet --threads 2 --out "$run"
    else
        BEDLAM_TEST_KILL_AT_STEP=$s "$bedlam" run "$scene" --quiet --threads 2 --resume "$run"
    fi
    rc=$?
    [ $rc -eq 137 ] || fail "the run to be killed at step $s ended with exit code $rc, not 137"
    first=0
done
"$bedlam" run "$scene" --quiet --threads 2 --resume "$run" || fail "the last resume failed"
resumes=$(grep -c "resumed from" "$run/run.log")
[ "$resumes" -eq "$kills" ] || fail "$resumes resumes in run.log, expected $kills"
echo "resumed from steps: $(sed -n 's/.*resumed from .* step \([0-9]*\)$/\1/p' "$run/run.log" | tr '\n' ' ')"

# The diagnostics, every column but the wall clock: the same rows, each once.
cut -d, -f1,2,4- "$ref/diagnostics.csv" >"$work/reference.rows"
cut -d, -f1,2,4- "$run/diagnostics.csv" >"$work/killed.rows"
if ! cmp -s "$work/reference.rows" "$work/killed.rows"; then
    diff "$work/reference.rows" "$work/killed.rows" | head -20
    fail "diagnostics.csv differs from the reference's ($(wc -l <"$work/reference.rows") rows, \
the killed run has $(wc -l <"$work/killed.rows"))"
fi
dups=$(cut -d, -f2 "$run/diagnostics.csv" | sort | uniq -d | wc -l)
[ "$dups" -eq 0 ] || fail "$dups steps have more than one diagnostics row"

# Every other file: the same set, the same bytes.
(cd "$ref" && find . -type f ! -name run.log ! -name diagnostics.csv | sort) >"$work/reference.files"
(cd "$run" && find . -type f ! -name run.log ! -name diagnostics.csv | sort) >"$work/killed.files"
if ! cmp -s "$work/reference.files" "$work/killed.files"; then
    diff "$work/reference.files" "$work/killed.files" | head -20
    fail "the killed run's files are not the reference's"
fi
different=0
while read -r f; do
    cmp -s "$ref/$f" "$run/$f" || {
        echo "differs: $f"
        different=$((different + 1))
    }
done <"$work/reference.files"
[ $different -eq 0 ] || fail "$different files differ from the reference's"
count=$(wc -l <"$work/reference.files")
echo "killed $kills times and resumed: $(wc -l <"$work/reference.rows") diagnostics rows and \
$count files, the final checkpoint among them, the same as the uninterrupted run's"
