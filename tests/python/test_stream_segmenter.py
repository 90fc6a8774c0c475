"""movseg.StreamSegmenter: one stream on two threads gives Segmenter's masks, one push later."""
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import movseg


def pushed(stream, frames):
    results = [stream.push(frame.copy()) for frame in frames]  # copies: freed after the call
    assert results[0] is None and all(r is not None for r in results[1:])
    last = stream.flush()
    assert stream.flush() is None
    return [r.mask for r in results[1:]] + [last.mask]


def streamed(frames, threads, params=None):
    return pushed(movseg.StreamSegmenter(params or movseg.Params(), threads=threads), frames)


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


@pytest.mark.parametrize("threads", [1, 2])
def test_an_ignored_region_gives_the_segmenters_masks(frames, threads):
    # The half of the frame where the clip's movers are most, ignored from the start: the
    # stream gives Segmenter's masks with the same region, nothing there; None clears it, and
    # the stream's masks are those without a region.
    plain = streamed(frames, 1)
    width = frames[0].shape[1]
    left = sum(int(mask[:, : width // 2].sum()) for mask in plain)
    right = sum(int(mask[:, width // 2 :].sum()) for mask in plain)
    region = np.zeros(frames[0].shape[:2], np.uint8)
    half = slice(0, width // 2) if left >= right else slice(width // 2, width)
    region[:, half] = 1
    assert any(mask[:, half].any() for mask in plain), "no mover in either half"
    segmenter = movseg.Segmenter()
    segmenter.set_ignored_region(region)
    expected = [segmenter.process(frame).mask for frame in frames]
    assert not any(mask[:, half].any() for mask in expected)
    stream = movseg.StreamSegmenter(threads=threads)
    stream.set_ignored_region(region)
    masks = pushed(stream, frames)
    assert len(masks) == len(expected)
    for index, (mask, want) in enumerate(zip(masks, expected)):
        assert np.array_equal(mask, want), f"frame {index}"
    stream.set_ignored_region(None)
    stream.reset()
    cleared = pushed(stream, frames)
    assert all(np.array_equal(a, b) for a, b in zip(cleared, plain))


def test_reset_params_and_bad_arguments(frames):
    stream = movseg.StreamSegmenter(movseg.Params(lambda_=400))
    assert stream.params.lambda_ == 400
    stream.push(frames[0])
    stream.reset()  # drops frame 0's result
    assert stream.push(frames[1]) is None
    assert stream.flush().diagnostics.first_frame
    with pytest.raises(ValueError):
        stream.push(np.zeros((8, 8, 2), np.uint8))
    for threads in (0, 3, -1, 2**32 + 2, 2**40):  # beyond int: the same error, not a TypeError
        with pytest.raises(ValueError, match="threads"):
            movseg.StreamSegmenter(threads=threads)


FORKED = {}  # what a forked child finds in its copy of the parent's memory


def push_in_forked_child():
    """What a push of the stream made in the parent does in a forked child, and whether a stream
    made in the child works there."""
    frames = FORKED["frames"]
    try:
        FORKED["stream"].push(frames[1])
        said = "no error"
    except RuntimeError as error:
        said = str(error)
    fresh = movseg.StreamSegmenter(threads=2)
    fresh.push(frames[1])
    return said, fresh.push(frames[2]) is not None


def test_a_two_thread_stream_refuses_a_forked_child_instead_of_hanging(frames):
    import multiprocessing

    FORKED.update(stream=movseg.StreamSegmenter(threads=2), frames=frames)
    FORKED["stream"].push(frames[0])  # its thread analyses this frame as the child is forked
    with multiprocessing.get_context("fork").Pool(1) as pool:
        said, fresh_works = pool.apply_async(push_in_forked_child).get(timeout=60)
    assert said.startswith("this object's thread was started in the process it was forked from")
    assert fresh_works
    assert FORKED.pop("stream").push(frames[1]) is not None  # the parent's goes on
