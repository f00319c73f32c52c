#!/usr/bin/env bash
# Draws docs/img/architecture.png: the folders of src/ by layer and the include edges between
# them (transitively reduced: an edge implied by two others is left out), from the same table
# the build and the layer test read. Needs Graphviz (Debian: graphviz).
set -euo pipefail
cd "$(dirname "$0")/.."
dot_file=$(mktemp)
trap 'rm -f "$dot_file"' EXIT
cmake -DSRC=src -DDOT="$dot_file" -P cmake/check_layers.cmake > /dev/null 2>&1
tred "$dot_file" | dot -Tpng -Gdpi=110 -o docs/img/architecture.png
echo "docs/img/architecture.png"
