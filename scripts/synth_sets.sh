#!/usr/bin/env bash
# Synthetic benchmark sets, one dataset folder that `movseg bench OUT_DIR` reads
# (OUT_DIR/<name>/frames, OUT_DIR/<name>/masks): 60 frames each at 320x240, seed 7
# (docs/synth.md).
#   std-<camera>   pan zoom rotate shake static mix: the plane, default objects and sensor (the
#                  320x240 sequences of scripts/synth_table.sh)
#   camo-<camera>  the same cameras, with the hard parts: camouflaged objects moving 1-3.5
#                  px/frame, sensor noise sigma 2, gain drifting within ±10 %
#   depth-<camera> dolly forward pan shake mix: the 3-D scene (near posts, parallax), default
#                  objects and sensor
#   depth-camo-<camera>  dolly forward: the 3-D scene with the hard parts of camo-*
#   scripts/synth_sets.sh OUT_DIR        then: build/movseg bench OUT_DIR
set -euo pipefail
if [[ $# -ne 1 ]]; then
  echo "usage: $0 OUT_DIR" >&2
  exit 2
fi
out=$1
bin=${MOVSEG:-$(dirname "$0")/../build/movseg}
common=(--frames 60 --size 320x240 --seed 7)
hard=(--camouflage --object-speed 1-3.5 --noise 2 --illumination 0.1)

make_set() {  # NAME OPTIONS...
  local name=$1
  shift
  "$bin" synth -o "$out/$name" "${common[@]}" "$@" >/dev/null
  echo "$out/$name"
}

for camera in pan zoom rotate shake static mix; do
  make_set "std-$camera" --camera "$camera"
  make_set "camo-$camera" --camera "$camera" "${hard[@]}"
done
for camera in dolly forward pan shake mix; do
  make_set "depth-$camera" --scene depth --camera "$camera"
done
for camera in dolly forward; do
  make_set "depth-camo-$camera" --scene depth --camera "$camera" "${hard[@]}"
done
echo "benchmark: $bin bench $out"
