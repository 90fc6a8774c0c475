"""movseg.createMovingCameraSubtractor: a cv2.BackgroundSubtractor, the Segmenter's masks."""
import cv2
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


def test_a_bad_frame_raises_cv2_error_as_mog2s_apply_does():
    subtractor = movseg.createMovingCameraSubtractor()
    with pytest.raises(cv2.error, match="unsupported channel count"):
        subtractor.apply(np.zeros((4, 4, 2), np.uint8))


# cv2 writes an output array in place or refuses it, as for MOG2: a view or a Fortran-ordered
# fgmask is never left untouched in silence (a temporary copy written instead).
@pytest.mark.parametrize("layout", ["view", "fortran"])
def test_fgmask_of_another_layout_raises_cv2_error_as_mog2s_apply_does(frames, layout):
    height, width = frames[0].shape[:2]
    big = np.zeros((2 * height, 2 * width), np.uint8)
    fgmask = big[::2, ::2] if layout == "view" else np.zeros((height, width), np.uint8, order="F")
    for subtractor in movseg.createMovingCameraSubtractor(), cv2.createBackgroundSubtractorMOG2():
        with pytest.raises(cv2.error, match="Layout of the output array fgmask is incompatible"):
            subtractor.apply(frames[0], fgmask)


def test_is_a_cv2_background_subtractor_whose_methods_all_run(frames):
    subtractor = movseg.createMovingCameraSubtractor(movseg.Params(method="diff"))
    assert type(subtractor) is cv2.BackgroundSubtractor
    for frame in frames[:3]:
        subtractor.apply(frame)
    subtractor.clear()  # forgets the stream: the next frame is a first frame
    assert not subtractor.apply(frames[3]).any()
    assert not subtractor.empty() and subtractor.getDefaultName()


def test_an_ignored_region_is_the_segmenters(frames):
    region = np.zeros(frames[0].shape[:2], np.uint8)
    region[:, : region.shape[1] // 2] = 1
    segmenter = movseg.Segmenter()
    segmenter.set_ignored_region(region)
    told = movseg.createMovingCameraSubtractor(ignored_region=region)
    untold = movseg.createMovingCameraSubtractor()
    moving_in_region_untold = 0
    for index, frame in enumerate(frames):
        mask = told.apply(frame)
        assert np.array_equal(mask, segmenter.process(frame).mask), f"frame {index}"
        assert not mask[region > 0].any(), f"frame {index}"
        moving_in_region_untold += np.count_nonzero(untold.apply(frame)[region > 0])
    assert moving_in_region_untold > 100
    with pytest.raises(ValueError, match="2-D array"):
        movseg.createMovingCameraSubtractor(ignored_region=np.zeros((4, 4, 3)))
