"""Segments the moving objects of a video and writes one mask per frame, OUTDIR/00000.png, ...

Usage: python3 segment_video.py INPUT OUTDIR   (INPUT: video file, stream URL, or frames/%05d.png)
"""
import sys

import cv2
import movseg  # built for one interpreter: /usr/bin/python3 unless the build chose another

video = cv2.VideoCapture(sys.argv[1])
if not video.isOpened():
    sys.exit(f"cannot open {sys.argv[1]}")
# Any field of include/movseg/params.def by name (lambda is lambda_); static_camera=True suits a
# fixed camera.
segmenter = movseg.Segmenter(movseg.Params(static_camera=False))
index = 0
while True:
    ok, frame = video.read()  # HxWx3 uint8 BGR
    if not ok:
        break
    result = segmenter.process(frame)
    path = f"{sys.argv[2]}/{index:05d}.png"
    if not cv2.imwrite(path, result.mask):  # HxW uint8, 0 / 255
        sys.exit(f"cannot write {path}")
    moving = result.features[result.features[:, 2] == 1]  # rows of (x, y, label)
    print(f"frame {index}: {cv2.countNonZero(result.mask)} moving pixels, "
          f"{len(moving)} moving features, {result.diagnostics.total_ms:.1f} ms")
    index += 1
