"""scripts/synth_sets.sh and scripts/group_means.py: the benchmark sets per seed and their
means per group, as README's synthetic table is made."""
import json
import os
import subprocess
import sys
from pathlib import Path

SOURCE = Path(os.environ.get("MOVSEG_SOURCE_DIR", Path(__file__).resolve().parents[2]))
INDEP_SYNTH = str(SOURCE / "scripts" / "indep_synth.py")


def group_means(tmp_path, rows):
    """The lines scripts/group_means.py prints for a bench report of `rows`."""
    report = tmp_path / "bench.json"
    report.write_text(json.dumps({"rows": rows}))
    return subprocess.run([sys.executable, str(SOURCE / "scripts" / "group_means.py"),
                           str(report)], capture_output=True, text=True,
                          check=True).stdout.splitlines()


def test_group_means_averages_each_group_over_cameras_and_seeds(tmp_path):
    rows = [{"sequence": name, "method": method, "J": j} for name, method, j in [
        ("std-pan-s7", "dense", 0.9), ("std-zoom-s8", "dense", 0.7),
        ("depth-camo-dolly-s7", "dense", 0.2), ("depth-dolly-s7", "dense", 0.6),
        ("std-pan-s7", "paper", 0.5), ("std-zoom-s8", "paper", 0.3),
        ("depth-camo-dolly-s7", "paper", 0.1), ("depth-dolly-s7", "paper", 0.4)]]
    out = group_means(tmp_path, rows)
    table = {line.split("|")[1].strip(): line for line in out[2:]}
    assert set(table) == {"std", "depth", "depth-camo"}  # depth-camo is not depth's
    assert "| std | 2 | 0.800 (0.70 std-zoom-s8) | 0.400 (0.30 std-zoom-s8) |" in out
    assert "| depth-camo | 1 | 0.200 (0.20 depth-camo-dolly-s7) |" in table["depth-camo"]


def test_group_means_groups_independent_sequences_by_camera(tmp_path):
    rows = [{"sequence": name, "method": "dense", "J": j} for name, j in [
        ("indep-fractal-pan-7", 0.9), ("indep-davis-pan-13", 0.5), ("indep-davis-dolly-2", 0.1)]]
    out = group_means(tmp_path, rows)
    assert "| indep-pan | 2 | 0.700 (0.50 indep-davis-pan-13) |" in out
    assert "| indep-dolly | 1 | 0.100 (0.10 indep-davis-dolly-2) |" in out


def test_synth_sets_names_each_seed(tmp_path):
    cli = os.environ["MOVSEG_CLI"]
    subprocess.run(["bash", str(SOURCE / "scripts" / "synth_sets.sh"), str(tmp_path / "two"), "3",
                    "4"], env={**os.environ, "MOVSEG": cli, "FRAMES": "2"}, check=True, capture_output=True)
    names = sorted(p.name for p in (tmp_path / "two").iterdir())
    assert len(names) == 2 * 19
    assert "depth-camo-forward-s4" in names and "std-pan-s3" in names
    subprocess.run(["bash", str(SOURCE / "scripts" / "synth_sets.sh"), str(tmp_path / "one"), "3"],
                   env={**os.environ, "MOVSEG": cli, "FRAMES": "2"}, check=True, capture_output=True)
    assert "std-pan" in {p.name for p in (tmp_path / "one").iterdir()}


def test_indep_synth_makes_frames_with_masks_of_small_movers(tmp_path):
    subprocess.run([sys.executable, INDEP_SYNTH, str(tmp_path), "--seeds", "7"], check=True,
                   capture_output=True)
    import cv2
    import numpy as np
    clip = tmp_path / "indep-fractal-pan-7"
    frames = sorted((clip / "frames").iterdir())
    masks = sorted((clip / "masks").iterdir())
    assert [p.name for p in frames] == [p.name for p in masks] and len(frames) == 40
    assert cv2.imread(str(frames[0])).shape == (240, 320, 3)
    shares = [np.count_nonzero(cv2.imread(str(m), 0)) / (320 * 240) for m in masks]
    assert all(0.005 < s < 0.08 for s in shares)  # small movers, always in view
    first, last = (cv2.imread(str(masks[i]), 0) > 0 for i in (0, -1))
    assert np.count_nonzero(first & ~last) > 0  # they move


def test_indep_synth_refuses_a_missing_davis_folder(tmp_path):
    run = subprocess.run([sys.executable, INDEP_SYNTH, str(tmp_path), "--davis",
                          str(tmp_path / "nothing")], capture_output=True, text=True)
    assert run.returncode != 0 and "no such folder" in run.stderr
    assert not any(tmp_path.iterdir())


def test_indep_synth_dolly_is_a_3d_scene_the_plane_cannot_explain(tmp_path):
    subprocess.run([sys.executable, INDEP_SYNTH, str(tmp_path), "--seeds", "7", "--cameras",
                    "dolly"], check=True, capture_output=True)
    import cv2
    import numpy as np
    clip = tmp_path / "indep-fractal-dolly-7"
    frames = [cv2.imread(str(p), 0).astype(np.float32)
              for p in sorted((clip / "frames").iterdir())[:2]]
    # The wall (top rows, 20 m) shifts less than the ground at the bottom (under 4 m): parallax.
    wall, _ = cv2.phaseCorrelate(frames[0][:80], frames[1][:80])
    ground, _ = cv2.phaseCorrelate(frames[0][200:], frames[1][200:])
    assert abs(ground[0]) > 2 * abs(wall[0]) > 0.5
    masks = [cv2.imread(str(p), 0) for p in sorted((clip / "masks").iterdir())]
    assert len(masks) == 40 and sum(np.count_nonzero(m) > 0 for m in masks) >= 20


def test_indep_synth_refuses_an_unknown_camera(tmp_path):
    run = subprocess.run([sys.executable, INDEP_SYNTH, str(tmp_path), "--cameras", "pan,crane"],
                         capture_output=True, text=True)
    assert run.returncode != 0 and "no such camera: crane" in run.stderr
    assert not any(tmp_path.iterdir())


def synth_data(tmp_path, frames):
    """A dataset folder holding one synthetic sequence `s` of 160x120 frames (frames/, masks/)."""
    subprocess.run([os.environ["MOVSEG_CLI"], "synth", "-o", str(tmp_path / "data" / "s"),
                    "--frames", str(frames), "--size", "160x120"], check=True, capture_output=True)
    return tmp_path / "data"


def test_dashcam_pastes_one_region_and_clears_the_masks_under_it(tmp_path):
    import cv2
    data = synth_data(tmp_path, 3)
    subprocess.run([sys.executable, str(SOURCE / "scripts" / "dashcam.py"), str(data),
                    str(tmp_path / "out"), str(tmp_path / "region.png")], check=True,
                   capture_output=True)
    region = cv2.imread(str(tmp_path / "region.png"), cv2.IMREAD_GRAYSCALE) > 0
    assert region.shape == (120, 160) and 0.05 < region.mean() < 0.3
    out = tmp_path / "out" / "s-dashcam"
    assert len(list((out / "frames").iterdir())) == 3
    for mask_file in (out / "masks").iterdir():
        assert not cv2.imread(str(mask_file), cv2.IMREAD_GRAYSCALE)[region].any()
    frames = [cv2.imread(str(p)).astype(int) for p in sorted((out / "frames").iterdir())]
    assert abs(frames[0] - frames[2])[region].mean() < 2  # the same pixels in every frame


def test_degrade_frames_pictures_in_bars_and_keeps_every_third_frame(tmp_path):
    import cv2
    data = synth_data(tmp_path, 7)
    subprocess.run([sys.executable, str(SOURCE / "scripts" / "degrade.py"), str(data),
                    str(tmp_path / "out")], check=True, capture_output=True)
    out = tmp_path / "out"
    letterbox = cv2.imread(str(out / "s-letterbox" / "frames" / "00000.jpg"))
    pillarbox = cv2.imread(str(out / "s-pillarbox" / "masks" / "00000.png"), cv2.IMREAD_GRAYSCALE)
    assert letterbox.shape == (150, 160, 3) and letterbox[:15].mean() < 8  # JPEG rings a little
    assert pillarbox.shape == (120, 200) and not pillarbox[:, :20].any()
    mask = cv2.imread(str(data / "s" / "masks" / "00000.png"), cv2.IMREAD_GRAYSCALE)
    portrait = cv2.imread(str(out / "s-portrait" / "masks" / "00000.png"), cv2.IMREAD_GRAYSCALE)
    assert portrait.shape == (160, 120) and (portrait == mask[::-1].T).all()  # turned clockwise
    grey = cv2.imread(str(out / "s-grey" / "frames" / "00000.jpg"), cv2.IMREAD_UNCHANGED)
    assert grey.shape == (120, 160)  # one channel
    third = sorted(p.name for p in (out / "s-third" / "masks").iterdir())
    assert third == ["00000.png", "00001.png", "00002.png"]  # frames 0, 3 and 6, renumbered
    assert os.readlink(out / "s-third" / "masks" / "00002.png").endswith("00006.png")
