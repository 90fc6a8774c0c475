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


def test_segment_video_says_what_it_cannot_open_or_write(source_dir, clip, tmp_path):
    script = str(source_dir / "examples/python/segment_video.py")
    for args, words in [([str(tmp_path / "none.mp4"), str(tmp_path)], "cannot open"),
                        ([str(clip / "frames/%05d.png"), str(tmp_path / "missing")],
                         "cannot write")]:
        done = subprocess.run([sys.executable, script, *args], capture_output=True, text=True)
        # (cv2 may warn first: its lines are its own)
        assert done.returncode == 1 and done.stderr.splitlines()[-1].startswith(words), done.stderr
