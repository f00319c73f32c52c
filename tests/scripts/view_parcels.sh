#!/bin/sh
# bedlam view of a scene of parcels under a virtual X display: the window draws the parcels, the
# colour key C cycles through every colour mode but the coordination number (parcels have no
# contacts) and the screenshot key writes a PNG.
# Usage: view_parcels.sh BEDLAM SCENE WORK
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
2 C
4 C
6 C
8 C
10 C
12 C
14 C
16 C
18 P
20 Q
KEYS
xvfb-run -a -s "-screen 0 1024x768x24" "$bedlam" view "$scene" --size 480x320 --paused \
    --script "$work/keys.txt" --out "$work/shots" > "$work/out.txt" 2>&1 || {
    cat "$work/out.txt"
    exit 1
}
cat "$work/out.txt"
grep -Eq "view: drawing [1-9][0-9]* particles \([1-9][0-9]* visible\) at 480x320" "$work/out.txt" ||
    { echo "no parcels drawn"; exit 1; }
for mode in species speed vx vy vz voidage solids; do
    grep -q "view: colour $mode\$" "$work/out.txt" || { echo "C never reached colour $mode"; exit 1; }
done
if grep -q "view: colour coordination" "$work/out.txt"; then
    echo "parcels were coloured by their coordination number"
    exit 1
fi
test -s "$work/shots/view_0000.png" || { echo "no screenshot"; exit 1; }
echo "the viewer drew the parcels in every colour mode that applies to them"
