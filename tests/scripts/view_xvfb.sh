#!/bin/sh
# bedlam view under a virtual X display, driven by a key script: the window opens, draws the
# scene and answers every key (each logs a line), and the screenshot key writes a PNG.
# Usage: view_xvfb.sh BEDLAM SCENE WORK
set -e
bedlam=$1 scene=$2 work=$3
if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "xvfb-run not installed (Debian: xvfb xauth)"
    exit 77
fi
rm -rf "$work"
mkdir -p "$work"
cat > "$work/keys.txt" <<KEYS
# frame key
3 H
6 C
9 Space
12 N
15 2
18 O
21 X
24 ]
27 P
30 R
33 -
36 0
40 Q
KEYS
xvfb-run -a -s "-screen 0 1024x768x24" "$bedlam" view "$scene" --size 640x400 \
    --script "$work/keys.txt" --out "$work/shots" > "$work/out.txt" 2>&1 || {
    cat "$work/out.txt"
    exit 1
}
cat "$work/out.txt"
grep -Eq "view: drawing [1-9][0-9]* particles \([1-9][0-9]* visible\) at 640x400" "$work/out.txt" ||
    { echo "no particles drawn"; exit 1; }
for line in "help on" "colour " "paused" "step" "preset 2" \
    "orthographic" "clip on" "amplitude_scale = 1.1" "screenshot" "reset" "simulated s per s" \
    "full speed" "quit"; do
    grep -q -- "$line" "$work/out.txt" || { echo "missing: $line"; exit 1; }
done
test -s "$work/shots/view_0000.png" || { echo "no screenshot"; exit 1; }
echo "view answered every key"
