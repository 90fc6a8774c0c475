"""movseg.createMovingCameraSubtractor: cv2.BackgroundSubtractor's calls, the Segmenter's masks."""
import numpy as np
import pytest

import movseg


def test_apply_returns_the_segmenters_masks(frames, cli_masks):
    subtractor = movseg.createMovingCameraSubtractor(movseg.Params())
    assert subtractor.getBackgroundImage() is None
    for index, frame in enumerate(frames):
        mask = subtractor.apply(frame)
        assert np.array_equal(mask, cli_masks[index]), f"frame {index}"
    assert subtractor.getBackgroundImage().shape == frames[0].shape


def test_apply_fills_fgmask_and_ignores_the_learning_rate(frames, cli_masks):
    subtractor = movseg.createMovingCameraSubtractor()
    fgmask = np.empty(frames[0].shape[:2], np.uint8)
    for index, frame in enumerate(frames[:3]):
        assert subtractor.apply(frame, fgmask, 0.01) is fgmask
        assert np.array_equal(fgmask, cli_masks[index]), f"frame {index}"


def test_bad_fgmask_or_frame_raise_value_error(frames):
    subtractor = movseg.createMovingCameraSubtractor()
    with pytest.raises(ValueError):
        subtractor.apply(frames[0], np.empty((3, 3), np.uint8))
    with pytest.raises(ValueError):
        subtractor.apply(np.zeros((4, 4, 2), np.uint8))


@pytest.mark.parametrize("layout", ["view", "fortran"])
def test_fgmask_of_any_layout_is_written_in_place(frames, cli_masks, layout):
    subtractor = movseg.createMovingCameraSubtractor()
    height, width = frames[0].shape[:2]
    big = np.zeros((2 * height, 2 * width), np.uint8)
    fgmask = big[::2, ::2] if layout == "view" else np.zeros((height, width), np.uint8, order="F")
    for index, frame in enumerate(frames[:2]):
        assert subtractor.apply(frame, fgmask) is fgmask
        assert np.array_equal(fgmask, cli_masks[index]), f"frame {index}"
