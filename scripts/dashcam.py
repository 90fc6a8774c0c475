#!/usr/bin/env python3
"""DAVIS-style sequences as a dash-cam would film them: a bonnet and a timestamp fixed to the camera.

Usage: scripts/dashcam.py DATA OUT REGION [SEQUENCE ...]

For each sequence of DATA (<sequence>/frames + <sequence>/masks; all of them when none is named)
writes OUT/<sequence>-dashcam: every frame with a textured bonnet over the bottom eighth (an
ellipse, the same pixels in every frame) and a burnt-in timestamp box in the top left corner;
the masks cleared there (nothing that moves can be seen through them). REGION (an image file,
e.g. region.png, outside OUT) is written white where they are: `movseg segment --ignore` and
`movseg bench --ignore` take it. Frames are written as JPEG
at quality 95. README ("Things fixed to the camera") has the table.
"""
import os
import sys

import cv2
import numpy as np


def overlay_of(size):
    """The bonnet and timestamp picture (BGR) and where it covers the frame (0 / 255)."""
    width, height = size
    region = np.zeros((height, width), np.uint8)
    cv2.ellipse(region, (width // 2, height * 5 // 4), (width * 2 // 3, height * 3 // 8), 0, 0, 360,
                255, cv2.FILLED)
    box = (8, 8, 8 + width * 27 // 100, 8 + height // 16)
    cv2.rectangle(region, box[:2], box[2:], 255, cv2.FILLED)
    rng = np.random.default_rng(3)
    paint = cv2.GaussianBlur(rng.normal(70, 40, (height, width, 3)).astype(np.float32), (0, 0), 3)
    picture = np.clip(paint, 0, 255).astype(np.uint8)
    cv2.rectangle(picture, box[:2], box[2:], (0, 0, 0), cv2.FILLED)
    cv2.putText(picture, "2026-11-26 12:00:00", (box[0] + 6, box[3] - 8), cv2.FONT_HERSHEY_SIMPLEX,
                (box[3] - box[1]) / 50, (255, 255, 255), 2)
    return picture, region


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    data, out, region_file = sys.argv[1:4]
    names = sys.argv[4:] or sorted(
        n for n in os.listdir(data) if os.path.isdir(os.path.join(data, n, "frames")))
    overlay = None  # (picture, region, size): one region fits one frame size
    for name in names:
        frames_in = os.path.join(data, name, "frames")
        masks_in = os.path.join(data, name, "masks")
        folder = os.path.join(out, f"{name}-dashcam")
        for sub in ("frames", "masks"):
            os.makedirs(os.path.join(folder, sub), exist_ok=True)
        for file in sorted(f for f in os.listdir(frames_in) if f.lower().endswith((".jpg", ".png"))):
            frame = cv2.imread(os.path.join(frames_in, file), cv2.IMREAD_COLOR)
            size = frame.shape[1::-1]
            if overlay is None:
                overlay = (*overlay_of(size), size)
                cv2.imwrite(region_file, overlay[1])
            picture, region, region_size = overlay
            if size != region_size:
                sys.exit(f"{name}: frames of {size}, others of {region_size}: one region fits one size")
            covered = region > 0
            frame[covered] = picture[covered]
            stem = os.path.splitext(file)[0]
            cv2.imwrite(os.path.join(folder, "frames", stem + ".jpg"), frame,
                        [cv2.IMWRITE_JPEG_QUALITY, 95])
            mask = cv2.imread(os.path.join(masks_in, stem + ".png"), cv2.IMREAD_GRAYSCALE)
            if mask is not None:
                mask[covered] = 0
                cv2.imwrite(os.path.join(folder, "masks", stem + ".png"), mask)


if __name__ == "__main__":
    main()
