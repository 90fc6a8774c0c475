#!/usr/bin/env bash
# Runs each libFuzzer target of fuzz/ for SECONDS, starting from its committed corpus
# fuzz/corpus/<target>/. New interesting inputs go to BUILD_DIR/fuzz/new-corpus/<target>/; a
# crash leaves its input in BUILD_DIR/fuzz/artifacts/, prints the end of the log and fails.
# Usage: fuzz/run.sh BUILD_DIR [SECONDS]   (`make test-fuzz` builds BUILD_DIR and calls it)
set -euo pipefail
build=$1
seconds=${2:-60}
here=$(cd "$(dirname "$0")" && pwd)

# OpenCV allocates whatever an image header claims, up to 2^30 pixels: a 100-byte file can ask
# for gigabytes and trip libFuzzer's memory limit. Capped, the fuzzer hunts our bugs instead.
export OPENCV_IO_MAX_IMAGE_PIXELS=4194304

for target in segmenter readers video; do
  new="$build/fuzz/new-corpus/$target"
  artifacts="$build/fuzz/artifacts"
  log="$build/fuzz/$target.log"
  rm -rf "$new"
  mkdir -p "$new" "$artifacts"
  dict=()
  if [ -f "$here/$target.dict" ]; then dict=(-dict="$here/$target.dict"); fi
  if "$build/fuzz/${target}_fuzz" "$new" "$here/corpus/$target" -max_total_time="$seconds" \
      -max_len=8192 -timeout=20 -print_final_stats=1 -artifact_prefix="$artifacts/" \
      "${dict[@]}" >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    echo "fuzz: $target: $runs runs in ${seconds} s, no crash (log: $log)"
  else
    tail -n 40 "$log"
    echo "fuzz: $target: FAILED; the input is in $artifacts/ (log: $log)" >&2
    exit 1
  fi
done
