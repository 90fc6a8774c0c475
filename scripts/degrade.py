#!/usr/bin/env python3
"""DAVIS-style sequences as a worse camera would film them, for `movseg bench`.

Usage: scripts/degrade.py DATA OUT [SEQUENCE ...]

For each sequence of DATA (<sequence>/frames + <sequence>/masks; all of them when none is named)
writes nine to OUT, the masks linked where they are unchanged:
  <sequence>-flicker  every other frame 8 % darker, the others 8 % brighter (a mains-lit lamp
                      filmed at a rate that beats with it);
  <sequence>-step     the frames from the 21st on 30 % brighter (an exposure that jumps);
  <sequence>-noise    Gaussian sensor noise of sigma 8 grey levels (a small sensor at night);
  <sequence>-grey     the frames in grey (a monochrome camera: infrared at night, thermal);
  <sequence>-repeat   every fifth frame shown twice (a frame rate padded from 24 to 30 a second,
                      or a stream that repeats its last frame when one is dropped);
  <sequence>-letterbox  black bars of an eighth of the height above and below (a wide picture
                      in a taller frame), the masks padded alike;
  <sequence>-pillarbox  black bars of an eighth of the width left and right (a 4:3 picture in a
                      16:9 frame), the masks padded alike;
  <sequence>-third    every third frame only (a camera at 8 frames a second);
  <sequence>-portrait the frames and masks turned a quarter clockwise (a phone held upright).
Frames are written as JPEG at quality 95 (a repeat as the same file twice). README ("Changes of
light", "Repeated frames", "Black bars", "Portrait video", "Grey video") has the tables.
"""
import os
import sys

import cv2
import numpy as np


def degrade(frame, t, variant, rng):
    if variant == "grey":
        return cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)
    image = frame.astype(np.float32)
    if variant == "flicker":
        image *= 1.08 if t % 2 else 0.92
    elif variant == "step":
        image *= 1.3 if t >= 20 else 1.0
    else:
        image += rng.normal(0, 8, image.shape)
    return np.clip(image + 0.5, 0, 255).astype(np.uint8)


def link_mask(mask, link):
    """`link` made a symbolic link to the mask file `mask`, unless it is there already."""
    if not os.path.lexists(link):
        os.symlink(os.path.abspath(mask), link)


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
            link_mask(os.path.join(masks_in, mask), os.path.join(folder, "masks", f"{out:05d}.png"))
            out += 1


def reframed(image, variant):
    """`image` letterboxed, pillarboxed (black bars of an eighth of the side) or turned."""
    if variant == "portrait":
        return cv2.rotate(image, cv2.ROTATE_90_CLOCKWISE)
    height, width = image.shape[:2]
    pad = (height // 8, height // 8, 0, 0) if variant == "letterbox" else \
        (0, 0, width // 8, width // 8)
    return cv2.copyMakeBorder(image, *pad, cv2.BORDER_CONSTANT, value=0)


def write_framed(frames_in, files, masks_in, folder, variant):
    """The letterboxed, pillarboxed or turned frames and their masks alike."""
    for sub in ("frames", "masks"):
        os.makedirs(os.path.join(folder, sub), exist_ok=True)
    for file in files:
        frame = cv2.imread(os.path.join(frames_in, file), cv2.IMREAD_COLOR)
        stem = os.path.splitext(file)[0]
        cv2.imwrite(os.path.join(folder, "frames", stem + ".jpg"), reframed(frame, variant),
                    [cv2.IMWRITE_JPEG_QUALITY, 95])
        mask = cv2.imread(os.path.join(masks_in, stem + ".png"), cv2.IMREAD_GRAYSCALE)
        if mask is not None:
            cv2.imwrite(os.path.join(folder, "masks", stem + ".png"), reframed(mask, variant))


def write_every_third(frames_in, files, masks_in, folder):
    """Frames 0, 3, 6, ... numbered 0, 1, 2, ... as a slower camera numbers them, each mask
    beside its frame (linked)."""
    for sub in ("frames", "masks"):
        os.makedirs(os.path.join(folder, sub), exist_ok=True)
    for out, file in enumerate(files[::3]):
        stem = os.path.splitext(file)[0]
        frame = cv2.imread(os.path.join(frames_in, file), cv2.IMREAD_COLOR)
        cv2.imwrite(os.path.join(folder, "frames", f"{out:05d}.jpg"), frame,
                    [cv2.IMWRITE_JPEG_QUALITY, 95])
        mask = os.path.join(masks_in, stem + ".png")
        if os.path.exists(mask):
            link_mask(mask, os.path.join(folder, "masks", f"{out:05d}.png"))


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
        for variant in ("letterbox", "pillarbox", "portrait"):
            write_framed(frames_in, files, masks_in, os.path.join(out, f"{name}-{variant}"),
                         variant)
        write_every_third(frames_in, files, masks_in, os.path.join(out, f"{name}-third"))
        for variant in ("flicker", "step", "noise", "grey"):
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
