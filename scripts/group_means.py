#!/usr/bin/env python3
"""Mean J per group and method of a `movseg bench --json` report of scripts/synth_sets.sh's sets.

Usage: scripts/group_means.py BENCH.json

A group is a set's name without its camera and seed (std, camo, depth, depth-camo), or for
scripts/indep_synth.py's sequences their camera (indep-pan: both textures, every seed); each
sequence weighs the same. Prints one Markdown table: a row per group, a column per method, the
lowest sequence of each group beside its mean.
"""
import json
import re
import sys
from collections import defaultdict


def group_of(sequence):
    """'depth-camo-dolly-s8' -> 'depth-camo', 'std-pan' -> 'std', 'indep-davis-pan-13' ->
    'indep-pan'."""
    independent = re.fullmatch(r"indep-(?:fractal|davis)-(\w+)-\d+", sequence)
    if independent:
        return f"indep-{independent.group(1)}"
    name = re.sub(r"-s\d+$", "", sequence)
    return name.rsplit("-", 1)[0]


def main(path):
    with open(path, encoding="utf-8") as report:
        rows = json.load(report)["rows"]
    scores = defaultdict(lambda: defaultdict(list))  # group -> method -> [(J, sequence)]
    for row in rows:
        scores[group_of(row["sequence"])][row["method"]].append((row["J"], row["sequence"]))
    methods = sorted({row["method"] for row in rows})
    print("| group | sequences | " + " | ".join(f"{m} mean J (lowest)" for m in methods) + " |")
    print("|---|---|" + "---|" * len(methods))
    for group in sorted(scores):
        cells = []
        for method in methods:
            values = scores[group][method]
            mean = sum(j for j, _ in values) / len(values)
            lowest = min(values)
            cells.append(f"{mean:.3f} ({lowest[0]:.2f} {lowest[1]})")
        print(f"| {group} | {len(scores[group][methods[0]])} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__.splitlines()[2])
    main(sys.argv[1])
