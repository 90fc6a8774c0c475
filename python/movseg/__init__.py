"""movseg: moving object segmentation for freely moving cameras, online, two frames at a time.

    import cv2, movseg
    segmenter = movseg.Segmenter(movseg.Params(lambda_=400))
    mask = segmenter.process(frame).mask      # frame: HxWx3 uint8 BGR, as cv2 reads it

`python3 -m movseg ...` runs the movseg command-line tool. docs/usage.md has more.
"""
from ._movseg import (
    BackgroundSubtractor,
    Diagnostics,
    Params,
    Result,
    Segmenter,
    __version__,
    createMovingCameraSubtractor,
)

__all__ = [
    "BackgroundSubtractor",
    "Diagnostics",
    "Params",
    "Result",
    "Segmenter",
    "createMovingCameraSubtractor",
]
