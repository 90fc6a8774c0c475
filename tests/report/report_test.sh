#!/usr/bin/env bash
# The HTML reports of `movseg bench --html` and `movseg eval --html`, rendered by headless
# Chromium: a screenshot is made, the rendered page holds every J and F of the JSON report and
# every chart was drawn, and the page loads nothing from elsewhere (it works offline).
# Usage: report_test.sh BUILD_DIR WORK_DIR
set -euo pipefail

cli=$1/movseg
work=$2
rm -rf "$work" && mkdir -p "$work"

fail() { echo "FAIL: $*" >&2; exit 1; }

# Chromium with no network, no profile of the user's, nothing started besides the page.
chromium_run() {
  chromium --headless --no-sandbox --disable-gpu --disable-background-networking \
    --disable-component-update --disable-sync --no-first-run --user-data-dir="$work/profile" \
    --virtual-time-budget=5000 "$@" 2>>"$work/chromium.log"
}

# Every J and F of a JSON report (bench: rows and means; eval: sequences and mean), as the
# page prints them.
figures() {
  /usr/bin/python3 - "$1" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
rows = report.get("rows", []) + report.get("means", []) + report.get("sequences", [])
rows += [report["mean"]] if len(report.get("sequences", [])) > 1 else []
for row in rows:
    print(f"{row['J']:.3f}")
    print(f"{row['F']:.3f}")
PY
}

check_page() {
  local page=$1 json=$2 charts=$3
  grep -Eq '(src|href)="(https?:)?//' "$page" && fail "$page loads something from elsewhere"
  chromium_run --window-size=1200,2400 --screenshot="$page.png" "file://$page" >/dev/null
  [ -s "$page.png" ] || fail "no screenshot of $page: $(tail -3 "$work/chromium.log")"
  chromium_run --dump-dom "file://$page" > "$page.dom"
  grep -q "data-charts=\"$charts\"" "$page.dom" ||
    fail "$page: not $charts charts drawn: $(grep -o 'data-charts="[0-9]*"' "$page.dom")"
  # Assigned first: set -e does not see a failing substitution in a for list, and a loop over
  # nothing would check no cell. Both reports here hold at least two rows (4 figures).
  local figs
  figs=$(figures "$json")
  [ "$(wc -l <<<"$figs")" -ge 4 ] || fail "no figures read from $json: $figs"
  for figure in $figs; do
    grep -q "<td>$figure</td>" "$page.dom" || fail "$page: no cell $figure"
  done
  [ "$(grep -o '<img alt="frame' "$page.dom" | wc -l)" -gt 0 ] || fail "$page: no thumbnails"
}

# The second name would end the page's data element early or hide its scripts, were it not
# escaped there (the charts then are not drawn).
for name in walk '<!--<script> run'; do
  "$cli" synth -o "$work/data/$name" --frames 8 --size 160x120 --seed "${#name}" >/dev/null
  "$cli" segment "$work/data/$name/frames" -o "$work/pred/$name" -q
done

"$cli" bench "$work/data" --methods paper,diff --html "$work/bench.html" --json "$work/bench.json" \
  >/dev/null
check_page "$work/bench.html" "$work/bench.json" 3  # J per sequence + a curve per sequence

"$cli" eval "$work/pred" "$work/data" --html "$work/eval.html" --json "$work/eval.json" >/dev/null
check_page "$work/eval.html" "$work/eval.json" 3

echo "ok: screenshots $work/bench.html.png and $work/eval.html.png"
