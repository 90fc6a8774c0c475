"""A cv2 background subtraction loop, switched from MOG2 to movseg by one line.

Usage: python3 drop_in.py INPUT   (INPUT: video file, stream URL, or frames/%05d.png)
"""
import sys

import cv2
import movseg  # built for one interpreter: /usr/bin/python3 unless the build chose another

video = cv2.VideoCapture(sys.argv[1])
# Was: subtractor = cv2.createBackgroundSubtractorMOG2()
subtractor = movseg.createMovingCameraSubtractor(movseg.Params())
index = 0
while True:
    ok, frame = video.read()
    if not ok:
        break
    mask = subtractor.apply(frame)
    print(f"frame {index}: {cv2.countNonZero(mask)} moving pixels")
    index += 1
