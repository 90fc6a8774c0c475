#!/usr/bin/env bash
# Instructions per pair of the dense flow (valgrind --tool=callgrind), OpenCV's DIS against
# movseg's DisFlow on the same frames: the first N images of FOLDER, each pair from the previous
# pair's flow, as DenseFlow runs (bench/flow_driver.cc). The first call (a first frame: no pair)
# is counted too; for DisFlow it prepares the frame that the first pair reuses.
# Usage: bench/flow_instructions.sh FOLDER [N]   (needs `make` first)
#   e.g. bench/flow_instructions.sh /tmp/dog320 13
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
driver=${MOVSEG_BUILD_DIR:-$here/../build}/bench/movseg_flow
out=$(mktemp)
trap 'rm -f "$out"' EXIT
frames=${2:-13}
for impl in opencv movseg; do
  valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect='*flowPair*' \
    "$driver" "$1" "$frames" "$impl" 2>&1 | grep -v '^==' || true
  total=$(callgrind_annotate "$out" | sed -n 's/^ *\([0-9,]*\) .*PROGRAM TOTALS.*/\1/p' | tr -d ,)
  echo "$impl: $((total / (frames - 1))) instructions per pair"
  if [ "$impl" = movseg ]; then
    # DisFlow's phases, per pair.
    callgrind_annotate --inclusive=yes "$out" 2>/dev/null |
      sed -nE 's/^ *([0-9,]+) \( *[0-9.]+%\) +[^:]*:movseg::(DisFlow::[a-zA-Z]+).*/\1\t\2/p' |
      awk -F'\t' -v n="$((frames - 1))" '!seen[$2]++ { gsub(",", "", $1); printf "%12d  %s\n", $1 / n, $2 }'
  fi
done
