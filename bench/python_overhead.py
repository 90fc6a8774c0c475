"""Python call overhead of movseg.Segmenter.process at 320x240, against the C++ time.

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--frames N] [--rounds R]

For every call it compares the wall time seen from Python (converting the numpy frame, the call,
and reading mask, features and model back) with Result.diagnostics.total_ms, measured
inside Segmenter::process. The overhead is the median of their differences; it must stay under
5 % of the median C++ time. The frames come from `movseg synth` (320x240, camera "mix").
"""
import argparse
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import cv2
import movseg
from movseg.__main__ import cli_path


def synth_frames(count, size="320x240"):
    with tempfile.TemporaryDirectory() as folder:
        subprocess.run([cli_path(), "synth", "-o", folder, "--frames", str(count), "--size", size],
                       check=True, capture_output=True)
        return [cv2.imread(str(p)) for p in sorted(Path(folder, "frames").glob("*.png"))]


def measure(frames, rounds):
    """Median C++ ms per frame, median Python ms per frame, median overhead ms per frame."""
    cpp, python, overhead = [], [], []
    for _ in range(rounds):
        segmenter = movseg.Segmenter()
        for frame in frames:
            start = time.perf_counter()
            result = segmenter.process(frame)
            _ = (result.mask, result.features, result.diagnostics.model)  # what callers read
            wall = (time.perf_counter() - start) * 1000
            inside = result.diagnostics.total_ms
            if not result.diagnostics.first_frame:
                cpp.append(inside)
                python.append(wall)
                overhead.append(wall - inside)
    return statistics.median(cpp), statistics.median(python), statistics.median(overhead)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=30)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    cpp, python, overhead = measure(synth_frames(args.frames), args.rounds)
    print(f"320x240, {args.frames} frames x {args.rounds} rounds (medians per frame)")
    print(f"  C++ Segmenter::process   {cpp:8.3f} ms")
    print(f"  Python Segmenter.process {python:8.3f} ms")
    print(f"  overhead                 {overhead:8.3f} ms = {100 * overhead / cpp:.2f} % (limit 5 %)")


if __name__ == "__main__":
    main()
