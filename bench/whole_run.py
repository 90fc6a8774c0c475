"""A whole `movseg segment` run against a Python cv2 MOG2 run doing the same reads and writes.

Usage: /usr/bin/python3 bench/whole_run.py [DATA] [--size 320x240] [--method dense] [--rounds 3]
       (also the last step of `make bench`)

DATA (default ../shared/data/davis2016 beside the source tree, or $MOVSEG_DATA/davis2016) holds
DAVIS sequences as <name>/frames/*.jpg. Four of them (blackswan, car-shadow, dog, goat), resized
to --size and played twice, are written as one folder of PNG frames (480 frames); then each
round times, as separate processes on one core each (OpenCV's threads at 1 in both):
  movseg segment FRAMES -o OUT --method M    (reads PNGs, writes mask PNGs and its manifest)
  python3 -c <cv2 MOG2 loop>                 (reads PNGs, writes mask PNGs)
and prints the medians over the rounds and their ratio. Exit status 0 even when the ratio is
above the target (1.25): this is a measurement, not a test.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import cv2

HERE = Path(__file__).resolve().parent
SEQUENCES = ["blackswan", "car-shadow", "dog", "goat"]
MOG2_LOOP = """
import sys
from pathlib import Path
import cv2
cv2.setNumThreads(1)
subtractor = cv2.createBackgroundSubtractorMOG2()
out = Path(sys.argv[2])
for i, path in enumerate(sorted(Path(sys.argv[1]).glob("*.png"))):
    mask = subtractor.apply(cv2.imread(str(path)))
    cv2.imwrite(str(out / f"{i:05d}.png"), mask)
"""


def default_data():
    root = os.environ.get("MOVSEG_DATA", str(HERE.parent.parent / "shared" / "data"))
    return str(Path(root) / "davis2016")


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("data", nargs="?", default=default_data())
    parser.add_argument("--size", default="320x240")
    parser.add_argument("--method", default="dense")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--movseg", default=str(HERE.parent / "build" / "movseg"))
    parser.add_argument("--skip-without-data", action="store_true",
                        help="exit 0 with a note when DATA holds no DAVIS sequences")
    return parser.parse_args()


def write_frames(data, size, folder):
    """The sequences resized and played twice, as numbered PNGs; how many were written."""
    width, height = (int(v) for v in size.split("x"))
    frames = []
    for name in SEQUENCES:
        files = sorted(Path(data, name, "frames").glob("*.jpg"))
        if not files:
            sys.exit(f"whole_run: no frames in {Path(data, name, 'frames')}")
        frames += [cv2.resize(cv2.imread(str(f)), (width, height), interpolation=cv2.INTER_AREA)
                   for f in files]
    for i, frame in enumerate(frames + frames):
        cv2.imwrite(str(Path(folder, f"{i:05d}.png")), frame)
    return 2 * len(frames)


def timed(command):
    start = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True)
    return time.perf_counter() - start


def main():
    args = parse_arguments()
    if args.skip_without_data and not Path(args.data, SEQUENCES[0], "frames").is_dir():
        print(f"whole_run: skipped, no DAVIS sequences in {args.data}")
        return
    with tempfile.TemporaryDirectory() as scratch:
        frames = Path(scratch, "frames")
        frames.mkdir()
        count = write_frames(args.data, args.size, frames)
        movseg_out, mog2_out = Path(scratch, "movseg"), Path(scratch, "mog2")
        mog2_out.mkdir()
        movseg_times, mog2_times = [], []
        for _ in range(args.rounds):  # alternated, so that both see the same machine
            movseg_times.append(timed([args.movseg, "segment", str(frames), "-o", str(movseg_out),
                                       "--method", args.method, "--overwrite", "-q"]))
            mog2_times.append(timed([sys.executable, "-c", MOG2_LOOP, str(frames), str(mog2_out)]))
    movseg_s, mog2_s = statistics.median(movseg_times), statistics.median(mog2_times)
    print(f"whole run, {count} frames at {args.size} (PNG in, PNG masks out), median of "
          f"{args.rounds} rounds")
    print(f"| run | seconds | fps |\n|---|---|---|")
    print(f"| movseg segment --method {args.method} | {movseg_s:.2f} | {count / movseg_s:.0f} |")
    print(f"| Python cv2 MOG2 | {mog2_s:.2f} | {count / mog2_s:.0f} |")
    print(f"ratio movseg / MOG2: {movseg_s / mog2_s:.2f} (target 1.25)")


if __name__ == "__main__":
    main()
