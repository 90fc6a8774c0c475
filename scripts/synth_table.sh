#!/usr/bin/env bash
# The synthetic accuracy table of README: one sequence per camera motion at 320x240 and
# 640x480, every method, exact ground truth.
#   scripts/synth_table.sh [OUT_DIR] [extra `movseg bench` options]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-/tmp/movseg-synth-table}
shift || true
bin=${MOVSEG:-build/movseg}
for size in 320x240 640x480; do
  for camera in pan zoom rotate shake static; do
    "$bin" synth -o "$out/$size/$camera" --overwrite --size "$size" --camera "$camera" --frames 60 \
      --seed 7 >/dev/null
  done
  echo "== $size"
  "$bin" bench "$out/$size" "$@"
done
