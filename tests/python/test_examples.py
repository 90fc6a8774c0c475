"""The Python examples that docs/usage.md shows, run on the synthetic clip."""
import subprocess
import sys

from conftest import read_masks


def run_example(source_dir, name, *args):
    done = subprocess.run([sys.executable, str(source_dir / "examples/python" / name), *args],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_segment_video_writes_the_clis_masks(source_dir, clip, cli_masks, tmp_path):
    output = run_example(source_dir, "segment_video.py", str(clip / "frames/%05d.png"), str(tmp_path))
    masks = read_masks(tmp_path)
    assert len(masks) == len(cli_masks) == len(output.splitlines())
    assert all((a == b).all() for a, b in zip(masks, cli_masks))


def test_drop_in_finds_the_same_moving_pixels(source_dir, clip, cli_masks):
    output = run_example(source_dir, "drop_in.py", str(clip / "frames/%05d.png"))
    expected = [f"frame {i}: {(mask > 0).sum()} moving pixels" for i, mask in enumerate(cli_masks)]
    assert output.splitlines() == expected
