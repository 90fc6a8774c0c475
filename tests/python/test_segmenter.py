"""movseg.Segmenter through numpy: the CLI's masks bit for bit, every frame type, the results."""
import gc
import json
import subprocess
import sys
import threading
import tracemalloc
from concurrent.futures import ThreadPoolExecutor

import cv2
import numpy as np
import pytest

import movseg
from conftest import read_masks


def segment(frames, params=None):
    segmenter = movseg.Segmenter(params or movseg.Params())
    return [segmenter.process(frame) for frame in frames]


def test_masks_are_the_clis_bit_for_bit(frames, cli_masks):
    masks = [r.mask for r in segment(frames)]
    assert len(masks) == len(cli_masks)
    for index, (mask, expected) in enumerate(zip(masks, cli_masks)):
        assert mask.dtype == np.uint8 and mask.shape == expected.shape, index
        assert np.array_equal(mask, expected), f"frame {index}"


def test_frames_may_be_freed_after_the_call(frames, cli_masks):
    # The segmenter keeps the previous frame: the array it was given must stay valid.
    segmenter = movseg.Segmenter()
    for index, frame in enumerate(frames):
        mask = segmenter.process(frame.copy()).mask
        gc.collect()
        assert np.array_equal(mask, cli_masks[index]), f"frame {index}"


def test_bgra_uint16_and_strided_frames_give_the_bgr_masks(frames):
    expected = [r.mask for r in segment(frames[:3])]
    assert expected[-1].any()  # frames 0 and 1 give empty masks: frame 2 carries the test
    bgra = [np.dstack([f, np.full(f.shape[:2], 255, np.uint8)]) for f in frames[:3]]
    deep = [f.astype(np.uint16) * 256 for f in frames[:3]]
    padded = [np.pad(f, ((0, 0), (0, 7), (0, 0)))[:, :-7] for f in frames[:3]]  # padded rows
    fortran = [np.asfortranarray(f) for f in frames[:3]]  # channels not packed: copied once
    for variant in (bgra, deep, padded, fortran):
        masks = [r.mask for r in segment(variant)]
        assert len(masks) == len(expected)
        assert all(np.array_equal(a, b) for a, b in zip(masks, expected))


def test_grey_frames_give_the_masks_of_their_picture_in_three_channels(frames):
    grey = [f[:, :, 1].copy() for f in frames]
    expected = [r.mask for r in segment([np.dstack([g, g, g]) for g in grey])]
    assert expected[-1].any()  # equal empty masks would prove nothing
    masks = [r.mask for r in segment(grey)]
    assert len(masks) == len(expected)
    assert all(np.array_equal(a, b) for a, b in zip(masks, expected))


def test_result_arrays_and_diagnostics(frames):
    first, second = segment(frames[:2], movseg.Params(method="paper"))  # it has features
    assert first.diagnostics.first_frame and not first.mask.any()
    d = second.diagnostics
    assert d.model.shape == (3, 3) and d.model.dtype == np.float64
    assert d.model_is_affine and np.array_equal(d.model[2], [0, 0, 1])
    assert second.features.ndim == 2 and second.features.shape[1] == 3
    assert second.features.dtype == np.float32 and len(second.features) > 10
    assert set(np.unique(second.features[:, 2])) <= {0, 1, 2}
    assert d.total_ms > 0 and d.total_ms >= d.cut_ms
    assert d.matches > 0 and d.background_seeds > 0 and not d.first_frame
    assert d.lambda_ >= movseg.Params().lambda_
    assert "\n    matches=" in repr(d) and "movseg.Result(mask 160x120" in repr(second)


def test_homography_model(clip, frames):
    # The first pair's fitted homography is the generator's own (camera.jsonl, previous frame
    # to current) within a pixel at the frame's corners.
    r = segment(frames[:2], movseg.Params(motion_model="homography"))[1]
    assert not r.diagnostics.model_is_affine and r.diagnostics.model.shape == (3, 3)
    first = json.loads((clip / "camera.jsonl").read_text().splitlines()[0])
    assert first["frame"] == 1
    height, width = frames[0].shape[:2]
    corners = np.array([[0, width - 1, 0, width - 1], [0, 0, height - 1, height - 1], [1, 1, 1, 1]],
                       float)

    def moved(model):
        points = np.asarray(model) @ corners
        return points[:2] / points[2]

    assert np.abs(moved(r.diagnostics.model) - moved(first["model"])).max() < 1.0


@pytest.mark.parametrize("method", ["paper", "diff", "mog2", "mog2-comp"])
def test_every_method_gives_the_clis_masks(cli, clip, frames, method, tmp_path):
    subprocess.run([cli, "segment", str(clip / "frames"), "-o", str(tmp_path), "-q",
                    "--method", method], check=True, capture_output=True)
    expected = read_masks(tmp_path)
    results = segment(frames, movseg.Params(method=method))
    assert results[0].diagnostics.first_frame and any(m.any() for m in expected)
    assert len(results) == len(expected)
    assert all(np.array_equal(r.mask, m) for r, m in zip(results, expected))


def test_debug_pictures_and_compensated_previous_frame(frames):
    segmenter = movseg.Segmenter(movseg.Params(debug_images=True))
    assert segmenter.compensated_previous_frame() is None
    segmenter.process(frames[0])
    r = segmenter.process(frames[1])
    # dense's stages at its working scale (320 px wide at most); the edges and mask at the frame's
    stages = {"carried", "confirmation", "regions", "residual", "unary", "uncovered"}
    assert set(r.debug) == stages | {"edges", "mask"}
    assert all(r.debug[stage].shape == frames[1].shape[:2] for stage in stages)
    assert r.debug["edges"].shape == frames[1].shape and np.array_equal(r.debug["mask"], r.mask)
    assert r.debug["residual"].any() and r.debug["unary"].any()
    assert segmenter.compensated_previous_frame().shape == frames[1].shape
    segmenter.reset()
    assert segmenter.process(frames[2]).diagnostics.first_frame


@pytest.mark.parametrize("frame", [
    np.zeros((0, 0, 3), np.uint8),
    np.zeros((8, 8, 2), np.uint8),
    np.zeros((8, 8, 5), np.uint8),
    np.zeros((8, 8, 1000), np.uint8),
    np.zeros(8, np.uint8),
    np.zeros((2, 8, 8, 3), np.uint8),
    np.zeros((8, 8, 3), np.float16),
    np.zeros((8, 8, 3), bool),
    np.zeros((8, 8, 3), np.dtype(">u2")),
], ids=["empty", "2-channel", "5-channel", "1000-channel", "1-D", "4-D", "float16", "bool",
        "big-endian"])
def test_bad_frames_raise_value_error(frame):
    with pytest.raises(ValueError):
        movseg.Segmenter().process(frame)


def test_dimensions_beyond_int_raise_value_error():
    wide = np.lib.stride_tricks.as_strided(np.zeros(1, np.uint8), shape=(1, 2**32 + 16),
                                           strides=(0, 0))
    with pytest.raises(ValueError, match="does not fit"):
        movseg.Segmenter().process(wide)


def test_frames_beyond_the_warps_limit_raise_value_error():
    # Worked at native size: 40000 rows at both working scales, past remap's 32766.
    native = movseg.Params(alignment_width=0, segmentation_width=0)
    with pytest.raises(ValueError, match="too large"):
        movseg.Segmenter(native).process(np.zeros((40000, 10), np.uint8))
    # At the default working width a tall frame is scaled down as a wide one is.
    assert movseg.Segmenter().process(np.zeros((40000, 10), np.uint8)).mask.shape == (40000, 10)


def test_an_opencv_failure_raises_runtime_error():
    # 40000 px wide: segmented at 320 px, but the compensated previous frame is warped at full
    # width, past remap's 32766.
    segmenter = movseg.Segmenter(movseg.Params(method="paper"))
    frame = np.zeros((8, 40000, 3), np.uint8)
    segmenter.process(frame)
    segmenter.process(frame)
    with pytest.raises(RuntimeError, match="OpenCV failed"):
        segmenter.compensated_previous_frame()


def test_not_an_array_raises_a_short_type_error(frames):
    with pytest.raises(TypeError):
        movseg.Segmenter().process("frame.png")
    with pytest.raises(TypeError) as error:
        movseg.Segmenter().process(frames)  # a list of frames: named, not printed
    assert "numpy array" in str(error.value) and "got list" in str(error.value)
    assert len(str(error.value)) < 200


def test_rgb_and_rgba_frames_with_rgb_give_the_bgr_masks(frames, cli_masks):
    segmenter, with_alpha = movseg.Segmenter(), movseg.Segmenter()
    for index, frame in enumerate(frames[:3]):
        rgb = frame[:, :, ::-1]  # as PIL and imageio give it (a view with a negative stride)
        rgba = np.dstack([rgb, np.full(frame.shape[:2], 255, np.uint8)])
        assert np.array_equal(segmenter.process(rgb, rgb=True).mask, cli_masks[index])
        assert np.array_equal(with_alpha.process(rgba, rgb=True).mask, cli_masks[index])


def test_float_frames_in_0_1_give_the_clis_masks_and_in_0_255_raise(frames, cli_masks):
    segmenter = movseg.Segmenter()
    for index, frame in enumerate(frames):
        assert np.array_equal(segmenter.process(frame / 255.0).mask, cli_masks[index]), index
    assert cli_masks[-1].any()
    with pytest.raises(ValueError, match=r"float frame values must be in \[0, 1\]"):
        segmenter.process(frames[1].astype(np.float32))


def test_segmenters_in_parallel_threads_give_the_clis_masks(frames, cli_masks):
    with ThreadPoolExecutor(max_workers=4) as pool:
        runs = list(pool.map(lambda _: [r.mask for r in segment(frames)], range(4)))
    assert cli_masks[-1].any()
    for masks in runs:
        assert len(masks) == len(cli_masks)
        assert all(np.array_equal(a, b) for a, b in zip(masks, cli_masks))


def ran_beside(call):
    """Whether another Python thread ran while `call` did. The switch interval is made longer
    than any call, so the interpreter never takes the GIL from the thread that holds it: the
    other thread, free to go as the call starts, runs before the call returns only if the call
    lets go of the GIL itself."""
    go, ran = threading.Event(), threading.Event()

    def beside():
        go.wait()
        ran.set()

    thread = threading.Thread(target=beside)
    thread.start()
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        go.set()
        call()
        return ran.is_set()
    finally:
        sys.setswitchinterval(interval)
        thread.join()


def test_ran_beside_sees_a_call_that_holds_the_gil():
    # The instrument itself: Python code holds the GIL from start to end; cv2's resize lets go.
    assert not ran_beside(lambda: sum(i * i for i in range(200_000)))
    big = np.zeros((3072, 4096, 3), np.uint8)
    assert ran_beside(lambda: cv2.resize(big, (2048, 1536), interpolation=cv2.INTER_AREA))


@pytest.mark.parametrize("api", ["process", "push", "push on 2 threads", "flush"])
def test_a_call_lets_other_python_threads_run(frames, api):
    # Frames large enough that the call (about 70 ms) outlasts by far the waking of the thread
    # beside it, even on a busy machine: a call shorter than that would return before the
    # thread could take the GIL. On two threads push and flush wait for the analysis in flight.
    big = [cv2.resize(frame, (4096, 3072)) for frame in frames[:3]]
    if api == "process":
        segmenter = movseg.Segmenter()
        segmenter.process(big[0])
        assert ran_beside(lambda: segmenter.process(big[1]))
        return
    stream = movseg.StreamSegmenter(threads=2 if api == "push on 2 threads" else 1)
    stream.push(big[0])
    stream.push(big[1])
    if api == "flush":
        assert ran_beside(stream.flush)
    else:
        assert ran_beside(lambda: stream.push(big[2]))


def test_the_frame_and_the_mask_are_not_copied_into_python_memory(frames):
    # What keeps the call cheap (bench/python_overhead.py: about 0.06 ms at 320x240): the frame
    # is read where numpy holds it and the mask is handed over as the C++ result's memory.
    # tracemalloc sees Python's allocations: a copy of either would be megabytes at this size.
    big = [cv2.resize(frame, (2048, 1536)) for frame in frames[:2]]
    segmenter = movseg.Segmenter()
    segmenter.process(big[0])
    tracemalloc.start()
    result = segmenter.process(big[1])
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert result.mask.shape == (1536, 2048)
    assert result.mask.any()
    assert peak < 100_000, peak  # the frame is 9.4 MB, the mask 3.1 MB


def test_one_segmenter_shared_by_threads_does_not_crash(frames):
    segmenter = movseg.Segmenter()
    with ThreadPoolExecutor(max_workers=4) as pool:
        results = list(pool.map(lambda f: segmenter.process(f.copy()), frames * 3))
    # The calls are serialised in some order: whichever it was, every mask is a valid one.
    assert all(r.mask.shape == frames[0].shape[:2] and r.mask.dtype == np.uint8 for r in results)
    assert all(set(np.unique(r.mask)) <= {0, 255} for r in results)
    assert sum(r.diagnostics.first_frame for r in results) == 1


def test_an_ignored_region_is_the_clis(cli, tmp_path):
    # A boolean array at half the frames' size (the left half), scaled to them; the CLI's
    # --ignore image gives the same masks, and None clears it. The clip is 320x240 (its movers
    # cover both halves; at the shared clip's 160x120 the region's margin, the flow's reach of
    # 16 px, would take its one mover) and the masks without the region have pixels in it, so
    # the region is what keeps them out.
    clip = tmp_path / "clip"
    subprocess.run([cli, "synth", "-o", str(clip), "--frames", "8", "--size", "320x240"],
                   check=True, capture_output=True)
    subprocess.run([cli, "segment", str(clip / "frames"), "-o", str(tmp_path / "plain"), "-q"],
                   check=True, capture_output=True)
    plain = read_masks(tmp_path / "plain")
    frames = [cv2.imread(str(p), cv2.IMREAD_UNCHANGED)
              for p in sorted((clip / "frames").glob("*.png"))]
    height, width = frames[0].shape[:2]
    assert sum(np.count_nonzero(mask[:, : width // 2]) for mask in plain) > 10_000
    region = np.zeros((height // 2, width // 2), bool)
    region[:, : width // 4] = True
    segmenter = movseg.Segmenter()
    segmenter.set_ignored_region(region)
    masks = [segmenter.process(frame).mask for frame in frames]
    assert not any(mask[:, : width // 2].any() for mask in masks)
    assert sum(np.count_nonzero(mask) for mask in masks) > 10_000
    image = np.zeros((height, width), np.uint8)
    image[:, : width // 2] = 255
    cv2.imwrite(str(tmp_path / "region.png"), image)
    subprocess.run([cli, "segment", str(clip / "frames"), "-o", str(tmp_path / "out"), "-q",
                    "--ignore", str(tmp_path / "region.png")], check=True, capture_output=True)
    for index, expected in enumerate(read_masks(tmp_path / "out")):
        assert np.array_equal(masks[index], expected), f"frame {index}"
    segmenter.set_ignored_region(None)
    segmenter.reset()
    cleared = [segmenter.process(frame).mask for frame in frames]
    assert len(cleared) == len(plain)
    for index, expected in enumerate(plain):
        assert np.array_equal(cleared[index], expected), f"cleared, frame {index}"
    with pytest.raises(ValueError, match="2-D"):
        segmenter.set_ignored_region(np.zeros((4, 4, 3), np.uint8))
