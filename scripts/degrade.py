#!/usr/bin/env python3
"""DAVIS-style sequences as a worse camera would film them, for `movseg bench`.

Usage: scripts/degrade.py DATA OUT [SEQUENCE ...]

For each sequence of DATA (<sequence>/frames + <sequence>/masks; all of them when none is named)
writes four to OUT, the masks linked, not copied:
  <sequence>-flicker  every other frame 8 % darker, the others 8 % brighter (a mains-lit lamp
                      filmed at a rate that beats with it);
  <sequence>-step     the frames from the 21st on 30 % brighter (an exposure that jumps);
  <sequence>-noise    Gaussian sensor noise of sigma 8 grey levels (a small sensor at night);
  <sequence>-repeat   every fifth frame shown twice (a frame rate padded from 24 to 30 a second,
                      or a stream that repeats its last frame when one is dropped).
Frames are written as JPEG at quality 95 (a repeat as the same file twice). README ("Changes of
light", "Repeated frames") has the tables.
"""
import os
import sys

import cv2
import numpy as np


def degrade(frame, t, variant, rng):
    image = frame.astype(np.float32)
    if variant == "flicker":
        image *= 1.08 if t % 2 else 0.92
    elif variant == "step":
        image *= 1.3 if t >= 20 else 1.0
    else:
        image += rng.normal(0, 8, image.shape)
    return np.clip(image + 0.5, 0, 255).astype(np.uint8)


def write_repeats(frames_in, files, masks_in, folder):
    """Every fifth frame twice, each mask beside its frame (linked)."""
    os.makedirs(os.path.join(folder, "masks"), exist_ok=True)
    masks = sorted(os.listdir(masks_in))
    out = 0
    for t, (file, mask) in enumerate(zip(files, masks)):
        frame = cv2.imread(os.path.join(frames_in, file), cv2.IMREAD_COLOR)
        for _ in range(2 if t % 5 == 4 else 1):
            cv2.imwrite(os.path.join(folder, "frames", f"{out:05d}.jpg"), frame,
                        [cv2.IMWRITE_JPEG_QUALITY, 95])
            link = os.path.join(folder, "masks", f"{out:05d}.png")
            if not os.path.lexists(link):
                os.symlink(os.path.abspath(os.path.join(masks_in, mask)), link)
            out += 1


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    data, out = sys.argv[1], sys.argv[2]
    names = sys.argv[3:] or sorted(
        n for n in os.listdir(data) if os.path.isdir(os.path.join(data, n, "frames")))
    for name in names:
        frames_in = os.path.join(data, name, "frames")
        files = sorted(f for f in os.listdir(frames_in) if f.lower().endswith((".jpg", ".png")))
        masks_in = os.path.join(data, name, "masks")
        repeat = os.path.join(out, f"{name}-repeat")
        os.makedirs(os.path.join(repeat, "frames"), exist_ok=True)
        write_repeats(frames_in, files, masks_in, repeat)
        for variant in ("flicker", "step", "noise"):
            rng = np.random.default_rng(1)
            folder = os.path.join(out, f"{name}-{variant}")
            os.makedirs(os.path.join(folder, "frames"), exist_ok=True)
            masks = os.path.join(folder, "masks")
            if not os.path.exists(masks):
                os.symlink(os.path.abspath(masks_in), masks)
            for t, file in enumerate(files):
                frame = cv2.imread(os.path.join(frames_in, file), cv2.IMREAD_COLOR)
                stem = os.path.splitext(file)[0]
                cv2.imwrite(os.path.join(folder, "frames", stem + ".jpg"),
                            degrade(frame, t, variant, rng), [cv2.IMWRITE_JPEG_QUALITY, 95])


if __name__ == "__main__":
    main()
