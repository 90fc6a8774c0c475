"""python3 -m movseg runs the movseg command-line tool."""
import subprocess
import sys

from conftest import read_masks


def run_module(*args):
    return subprocess.run([sys.executable, "-m", "movseg", *args], capture_output=True, text=True)


def test_segment_writes_the_clis_masks(clip, cli_masks, tmp_path):
    done = run_module("segment", str(clip / "frames"), "-o", str(tmp_path), "-q")
    assert done.returncode == 0, done.stderr
    masks = read_masks(tmp_path)
    assert len(masks) == len(cli_masks)
    assert all((a == b).all() for a, b in zip(masks, cli_masks))


def test_errors_and_exit_codes_pass_through(tmp_path):
    assert run_module("--help").returncode == 0
    done = run_module("segment", str(tmp_path / "missing"), "-o", str(tmp_path / "out"))
    assert done.returncode == 1 and done.stderr.startswith("movseg: error:")
