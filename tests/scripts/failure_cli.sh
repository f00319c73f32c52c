#!/bin/sh
# Failures keep the last good checkpoint and never write a non-finite number, and failed writes
# exit with 1 and name the file.
#
#   failure_cli.sh BEDLAM TESTS_SOURCE_DIR WORK
#
# 1. A run that blows up (tests/scenes/blowup.ini: its kinetic energy overflows at step 900,
#    between two guard checks): exit 1, the stop names the column, the value and the step; its
#    state goes to checkpoint/failed.bdlckpt beside the good state.bdlckpt of t = 0.1 s; no output
#    file holds a non-finite number (finite_outputs.py reads them all back, VTK included).
#    Resuming the folder takes the good checkpoint: with the same scene it fails again at the
#    same step, in the same state byte for byte; with a stable time step it runs to the end.
# 2. A gas inflow raised 10^4 times by a sweep after t = 0.02 s (tests/scenes/kill.ini): the gas
#    step stops the run with its reason (it used to print an empty "run stopped:"), the state goes
#    to failed.bdlckpt, outputs are finite, and the folder resumes without the sweep to the end.
#    The same with the inflow raised 100 times, and with gravity reversed (a clean run to the end).
# 3. The final checkpoint cannot be written (a folder where checkpoint/state.bdlckpt should be):
#    exit 1 with the path; a file where the checkpoint folder should be: exit 2 before the run.
# 4. A full disk: diagnostics.csv a link to /dev/full, and a run in a 600 kB tmpfs when one can
#    be mounted (root): exit 1, "PATH: no space left on device (ENOSPC)".
set -u
bedlam=$1
tests=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
fail() {
    echo "FAIL: $*"
    exit 1
}
# run CODE PATTERN ARGS...: runs bedlam with ARGS, expects exit code CODE and PATTERN (an
# extended regular expression; empty: anything) in what it printed.
run() {
    code=$1
    pattern=$2
    shift 2
    "$bedlam" "$@" >"$work/out.txt" 2>&1
    rc=$?
    [ $rc -eq "$code" ] || {
        cat "$work/out.txt"
        fail "bedlam $*: exit code $rc, expected $code"
    }
    [ -z "$pattern" ] || grep -Eq "$pattern" "$work/out.txt" || {
        cat "$work/out.txt"
        fail "bedlam $*: the output does not match '$pattern'"
    }
}
finite() {
    "${PYTHON:-python3}" "$tests/scripts/finite_outputs.py" "$1" || fail "non-finite numbers in $1"
}

# 1. The blow-up.
blowup=$tests/scenes/blowup.ini
out=$work/blowup
run 1 "run stopped: diagnostics.csv: the kinetic_energy of t = 0.198 s \(step 900\) would be inf" \
    run "$blowup" --quiet --out "$out"
grep -q "state at the stop is in $out/checkpoint/failed.bdlckpt" "$work/out.txt" ||
    fail "the stop does not say where the failed state is"
grep -q "last good checkpoint is $out/checkpoint/state.bdlckpt (t = 0.1001 s, step 455)" \
    "$work/out.txt" || fail "the stop does not name the last good checkpoint"
[ -s "$out/checkpoint/state.bdlckpt" ] && [ -s "$out/checkpoint/failed.bdlckpt" ] ||
    fail "state.bdlckpt and failed.bdlckpt are not both there"
finite "$out"
cp "$out/checkpoint/failed.bdlckpt" "$work/first_failure.bdlckpt"
run 1 "run stopped: diagnostics.csv: the kinetic_energy of t = 0.198 s \(step 900\)" \
    run "$blowup" --quiet --resume "$out"
grep -Eq "resumed from $out/checkpoint/state.bdlckpt at t = 0.100099[0-9]* s, step 455" \
    "$out/run.log" || fail "the resume did not start from the good checkpoint"
cmp -s "$out/checkpoint/failed.bdlckpt" "$work/first_failure.bdlckpt" ||
    fail "the resumed run failed in another state"
run 0 "continues with the scene's dt = 2e-05 s" run "$blowup" --quiet --resume "$out" \
    --set run.dt=0.00002
finite "$out"

# 2. The gas inflow raised 10^4 times.
kill=$tests/scenes/kill.ini
out=$work/gas
run 1 "run stopped: gas step at t = 0.0201831 s \(step 711\): the gas step [0-9.e-]+ s is above twice the stable limit" \
    run "$kill" --quiet --out "$out" --set output.frame_interval=0 --set gas.sweep=up \
    --set gas.sweep_to=25000 --set gas.sweep_step=24997.5 --set gas.sweep_dwell=0.02
grep -q "last good checkpoint is $out/checkpoint/state.bdlckpt (t = 0.0158966583 s, step 560)" \
    "$work/out.txt" || fail "the gas stop does not name the last good checkpoint"
[ -s "$out/checkpoint/failed.bdlckpt" ] || fail "no failed.bdlckpt after the gas stop"
finite "$out"
run 0 "" run "$kill" --quiet --resume "$out" --set output.frame_interval=0
finite "$out"

# 2b. The inflow raised 100 times, and gravity reversed: the same clean stop with the last good
#     checkpoint resumable; upside down the beads rest on the lid to the end. No output holds a
#     non-finite number.
out=$work/gas100
run 1 "run stopped: gas step at t = 0.0201831 s \(step 711\)" \
    run "$kill" --quiet --out "$out" --set output.frame_interval=0 --set gas.sweep=up \
    --set gas.sweep_to=250 --set gas.sweep_step=247.5 --set gas.sweep_dwell=0.02
[ -s "$out/checkpoint/failed.bdlckpt" ] || fail "no failed.bdlckpt after the 100x inflow"
finite "$out"
run 0 "" run "$kill" --quiet --resume "$out" --set output.frame_interval=0
finite "$out"
out=$work/upside_down
run 0 "" run "$kill" --quiet --out "$out" --set output.frame_interval=0 --set "run.gravity=0 0 9.81"
finite "$out"

# 3. Checkpoints that cannot be written.
out=$work/checkpoint
run 0 "" run "$kill" --quiet --out "$out/base" --steps 50 --set output.frame_interval=0
mkdir -p "$out/resumed/checkpoint/state.bdlckpt"
run 1 "run failed: cannot write the checkpoint: $out/resumed/checkpoint/state.bdlckpt: is a directory" \
    run "$kill" --quiet --resume "$out/base/checkpoint/state.bdlckpt" --out "$out/resumed" \
    --steps 20 --set output.frame_interval=0 --set output.checkpoint_interval=0
mkdir -p "$out/file"
: >"$out/file/checkpoint"
run 2 "$out/file/checkpoint: not a directory" run "$kill" --quiet --out "$out/file" \
    --set output.frame_interval=0

# 4. A full disk.
out=$work/full
mkdir -p "$out/devfull"
ln -s /dev/full "$out/devfull/diagnostics.csv"
run 1 "$out/devfull/diagnostics.csv: no space left on device \(ENOSPC\)" run "$kill" --quiet \
    --out "$out/devfull" --set output.frame_interval=0
mkdir -p "$out/tmpfs"
if mount -t tmpfs -o size=600k tmpfs "$out/tmpfs" 2>/dev/null; then
    "$bedlam" run "$kill" --quiet --out "$out/tmpfs/run" --set output.frame_interval=0 \
        >"$work/out.txt" 2>&1
    rc=$?
    df -k "$out/tmpfs" | tail -n 1
    umount "$out/tmpfs"
    [ $rc -eq 1 ] || fail "a run on a full tmpfs: exit code $rc, expected 1"
    grep -Eq "$out/tmpfs/run/[^ ]+: no space left on device \(ENOSPC\)" "$work/out.txt" || {
        cat "$work/out.txt"
        fail "a run on a full tmpfs does not say which file found the disk full"
    }
    grep -E "ENOSPC" "$work/out.txt"
else
    echo "a tmpfs cannot be mounted here (not root): the /dev/full case stands for a full disk"
fi
echo "failures: the last good checkpoint kept, outputs finite, failed writes named"
