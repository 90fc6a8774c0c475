"""movseg: moving object segmentation for freely moving cameras, online, frame by frame.

    import cv2, movseg
    segmenter = movseg.Segmenter(movseg.Params(lambda_=400))
    mask = segmenter.process(frame).mask      # frame: HxWx3 uint8 BGR, as cv2 reads it

movseg.StreamSegmenter(params, threads=2) segments one stream on two threads: push() returns the
previous frame's Result (the same masks), flush() the last one.

`python3 -m movseg ...` runs the movseg command-line tool. docs/usage.md has more.
"""
import sys

from ._build_info import PYTHON

try:
    import numpy  # noqa: F401 (the extension loads it only when it first converts an array)

    from ._movseg import (
        Diagnostics,
        Params,
        Result,
        Segmenter,
        StreamSegmenter,
        __version__,
        createMovingCameraSubtractor,
    )
except ImportError as error:
    # The extension is compiled for one interpreter and uses its numpy (and cv2); another
    # python3 found first on PATH (pyenv, a virtualenv) would fail here with a riddle.
    raise ImportError(
        f"movseg is built for {PYTHON} with its numpy and cv2 (Debian: python3-numpy, "
        f"python3-opencv); this is {sys.executable}, where it fails: {error}") from error

__all__ = [
    "Diagnostics",
    "Params",
    "Result",
    "Segmenter",
    "StreamSegmenter",
    "createMovingCameraSubtractor",
]
