#!/bin/sh
# Every scene opens in bedlam view: under a virtual X display the window draws the scene's
# particles for a few frames, takes a screenshot and quits.
# Usage: view_open.sh BEDLAM WORK SCENE...
set -e
bedlam=$1 work=$2
shift 2
if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "xvfb-run not installed (Debian: xvfb xauth)"
    exit 77
fi
rm -rf "$work"
mkdir -p "$work"
printf "# frame key\n4 P\n8 Q\n" > "$work/keys.txt"
for scene in "$@"; do
    name=$(basename "$scene" .ini)
    xvfb-run -a -s "-screen 0 1024x768x24" "$bedlam" view "$scene" --size 480x320 \
        --script "$work/keys.txt" --out "$work/$name" > "$work/$name.txt" 2>&1 || {
        cat "$work/$name.txt"
        echo "$name: bedlam view failed"
        exit 1
    }
    grep -Eq "view: drawing [1-9][0-9]* particles \([1-9][0-9]* visible\) at 480x320" "$work/$name.txt" ||
        { cat "$work/$name.txt"; echo "$name: no particles drawn"; exit 1; }
    test -s "$work/$name/view_0000.png" || { echo "$name: no screenshot"; exit 1; }
    echo "$name: opened, drew its particles, took a screenshot"
done
