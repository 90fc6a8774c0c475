"""segment's live side: --show needs a display, and a stream that ends keeps what was written."""
import os
import subprocess

import cv2

from conftest import read_masks


def run_cli(cli, *args, env=None):
    return subprocess.run([cli, *args], capture_output=True, text=True, env=env, timeout=60)


def test_show_without_a_display_fails_fast_with_one_line(cli, clip, tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    done = run_cli(cli, "segment", str(clip / "frames"), "-o", str(tmp_path / "out"), "--show", env=env)
    assert done.returncode == 1
    assert done.stderr == "movseg: error: --show needs a display; none found\n"
    assert not (tmp_path / "out").exists()


def test_a_display_that_is_not_there_counts_as_none(cli, clip, tmp_path):
    env = dict(os.environ, DISPLAY=":97", WAYLAND_DISPLAY="no-such-wayland-socket")
    done = run_cli(cli, "segment", str(clip / "frames"), "-o", str(tmp_path / "out"), "--show", env=env)
    assert done.returncode == 1 and "--show needs a display; none found" in done.stderr


def test_a_stream_that_ends_keeps_its_masks(cli, clip, frames, tmp_path):
    # Raw motion JPEG has no frame count, like a network stream or a camera: its end is an end,
    # not a stall (that is a timeout: tests/reliability/input_faults_test.cc).
    stream = tmp_path / "clip.mjpeg"
    stream.write_bytes(b"".join(cv2.imencode(".jpg", f)[1].tobytes() for f in frames))
    done = run_cli(cli, "segment", str(stream), "-o", str(tmp_path / "masks"))
    assert done.returncode == 0, done.stderr
    assert "error" not in done.stderr
    assert len(read_masks(tmp_path / "masks")) == len(frames)
