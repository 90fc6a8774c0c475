"""Shared fixtures: the movseg CLI of the build under test and a short synthetic clip.

ctest sets MOVSEG_CLI, MOVSEG_SOURCE_DIR and PYTHONPATH (tests/python/CMakeLists.txt).
"""
import os
import subprocess
from pathlib import Path

import cv2
import pytest

CLIP_FRAMES = 8


def read_masks(folder):
    return [cv2.imread(str(p), cv2.IMREAD_UNCHANGED) for p in sorted(Path(folder).glob("*.png"))]


@pytest.fixture(scope="session")
def cli():
    return os.environ["MOVSEG_CLI"]


@pytest.fixture(scope="session")
def source_dir():
    return Path(os.environ["MOVSEG_SOURCE_DIR"])


@pytest.fixture(scope="session")
def clip(cli, tmp_path_factory):
    """A synthetic sequence (frames/00000.png ...) and the CLI's masks of it (cli_masks/)."""
    folder = tmp_path_factory.mktemp("clip")
    subprocess.run([cli, "synth", "-o", str(folder), "--frames", str(CLIP_FRAMES), "--size", "160x120"],
                   check=True, capture_output=True)
    subprocess.run([cli, "segment", str(folder / "frames"), "-o", str(folder / "cli_masks"), "-q"],
                   check=True, capture_output=True)
    return folder


@pytest.fixture(scope="session")
def frames(clip):
    return [cv2.imread(str(p), cv2.IMREAD_UNCHANGED) for p in sorted((clip / "frames").glob("*.png"))]


@pytest.fixture(scope="session")
def cli_masks(clip):
    masks = read_masks(clip / "cli_masks")
    # Tests compare their masks with these: none, or all empty, would prove nothing.
    assert len(masks) == CLIP_FRAMES and masks[-1].any()
    return masks
