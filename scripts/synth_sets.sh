#!/usr/bin/env bash
# Synthetic benchmark sets, one dataset folder that `movseg bench OUT_DIR` reads
# (OUT_DIR/<name>/frames, OUT_DIR/<name>/masks): 60 frames each at 320x240 (docs/synth.md).
#   std-<camera>   pan zoom rotate shake static mix: the plane, default objects and sensor (the
#                  320x240 sequences of scripts/synth_table.sh)
#   camo-<camera>  the same cameras, with the hard parts: camouflaged objects moving 1-3.5
#                  px/frame, sensor noise sigma 2, gain drifting within ±10 %
#   depth-<camera> dolly forward pan shake mix: the 3-D scene (near posts, parallax), default
#                  objects and sensor
#   depth-camo-<camera>  dolly forward: the 3-D scene with the hard parts of camo-*
# One set of 19 per seed (default: seeds 7 8 9, named <name>-s<seed>); a single seed gives the
# names alone. One seed is one draw of objects and textures: a figure from one seed can be far
# from the method's typical one (docs/synth.md).
#   scripts/synth_sets.sh OUT_DIR [SEED ...]        then: build/movseg bench OUT_DIR
#   (MOVSEG=path/to/movseg for another build, FRAMES=N for shorter sequences)
#   scripts/group_means.py BENCH.json              means per group (std, camo, depth, depth-camo)
set -euo pipefail
if [[ $# -lt 1 ]]; then
  echo "usage: $0 OUT_DIR [SEED ...]" >&2
  exit 2
fi
out=$1
shift
seeds=("$@")
[[ ${#seeds[@]} -gt 0 ]] || seeds=(7 8 9)
bin=${MOVSEG:-$(dirname "$0")/../build/movseg}
hard=(--camouflage --object-speed 1-3.5 --noise 2 --illumination 0.1)

make_set() {  # NAME SEED OPTIONS...
  local name=$1 seed=$2
  shift 2
  [[ ${#seeds[@]} -eq 1 ]] || name="$name-s$seed"
  "$bin" synth -o "$out/$name" --overwrite --frames "${FRAMES:-60}" --size 320x240 \
    --seed "$seed" "$@" >/dev/null
  echo "$out/$name"
}

for seed in "${seeds[@]}"; do
  for camera in pan zoom rotate shake static mix; do
    make_set "std-$camera" "$seed" --camera "$camera"
    make_set "camo-$camera" "$seed" --camera "$camera" "${hard[@]}"
  done
  for camera in dolly forward pan shake mix; do
    make_set "depth-$camera" "$seed" --scene depth --camera "$camera"
  done
  for camera in dolly forward; do
    make_set "depth-camo-$camera" "$seed" --scene depth --camera "$camera" "${hard[@]}"
  done
done
echo "benchmark: $bin bench $out"
