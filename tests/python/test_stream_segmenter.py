"""movseg.StreamSegmenter: one stream on two threads gives Segmenter's masks, one push later."""
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import movseg


def streamed(frames, threads, params=None):
    stream = movseg.StreamSegmenter(params or movseg.Params(), threads=threads)
    results = [stream.push(frame.copy()) for frame in frames]  # copies: freed after the call
    assert results[0] is None and all(r is not None for r in results[1:])
    last = stream.flush()
    assert stream.flush() is None
    return [r.mask for r in results[1:]] + [last.mask]


@pytest.mark.parametrize("threads", [1, 2])
@pytest.mark.parametrize("method", ["dense", "paper"])
def test_masks_are_the_segmenters(frames, threads, method):
    params = movseg.Params(method=method)
    segmenter = movseg.Segmenter(params)
    expected = [segmenter.process(frame).mask for frame in frames]
    masks = streamed(frames, threads, params)
    assert len(masks) == len(expected)
    for index, (mask, want) in enumerate(zip(masks, expected)):
        assert np.array_equal(mask, want), f"frame {index}"


def test_streams_on_python_threads_give_each_ones_masks(frames, cli_masks):
    # push() runs without the GIL: streams of their own on Python threads run at once.
    with ThreadPoolExecutor(2) as pool:
        for masks in pool.map(lambda _: streamed(frames, 2), range(2)):
            assert len(masks) == len(cli_masks)
            assert all(np.array_equal(a, b) for a, b in zip(masks, cli_masks))


def test_reset_params_and_bad_arguments(frames):
    stream = movseg.StreamSegmenter(movseg.Params(lambda_=400))
    assert stream.params.lambda_ == 400
    stream.push(frames[0])
    stream.reset()  # drops frame 0's result
    assert stream.push(frames[1]) is None
    assert stream.flush().diagnostics.first_frame
    with pytest.raises(ValueError):
        stream.push(np.zeros((8, 8, 2), np.uint8))
    for threads in (0, 3):
        with pytest.raises(ValueError, match="threads"):
            movseg.StreamSegmenter(threads=threads)
