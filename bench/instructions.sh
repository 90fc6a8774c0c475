#!/usr/bin/env bash
# Instruction counts of a Segmenter run (valgrind --tool=callgrind): a figure that, unlike
# time, does not depend on what else the machine runs. Compare two variants with the same
# FOLDER and N.
# Usage: bench/instructions.sh FOLDER [N] [name=value ...]   (needs `make` first)
#   e.g. bench/instructions.sh ../shared/data/davis2016/dog/frames 10 method=paper
# Prints the instructions per frame of the whole run and of the library's top functions.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
driver=${MOVSEG_BUILD_DIR:-$here/../build}/bench/movseg_frames
out=$(mktemp)
trap 'rm -f "$out"' EXIT
frames=${2:-10}
valgrind --tool=callgrind --callgrind-out-file="$out" "$driver" "$@" 2>&1 |
  grep -v '^==' || true
total=$(callgrind_annotate "$out" | sed -n 's/^ *\([0-9,]*\) .*PROGRAM TOTALS.*/\1/p' | tr -d ,)
echo "instructions per frame: $((total / frames)) (whole run, decoding included)"
callgrind_annotate --inclusive=yes "$out" 2>/dev/null |
  sed -nE 's/^ *([0-9,]+) \( *[0-9.]+%\) +[^:]*:(movseg::([^(]|\(anonymous namespace\))*).*/\1\t\2/p' |
  awk -F'\t' -v n="$frames" '!seen[$2]++ && shown++ < 15 { gsub(",", "", $1); printf "%12d  %s\n", $1 / n, $2 }'
