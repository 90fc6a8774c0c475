"""python3 -m movseg batch: three inputs, one of them corrupt, on a 2-worker local cluster; then
the same through a scheduler and a worker started as docs/usage.md shows."""
import csv
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time

import cv2
import numpy as np
import pytest

from conftest import read_masks

# Not skipped without Dask: scripts/install-deps.sh installs it, and `batch` is a promise.
import distributed  # noqa: F401  pylint: disable=unused-import,wrong-import-order


def batch(*args):
    return subprocess.run([sys.executable, "-m", "movseg", "batch", *args],
                          capture_output=True, text=True, timeout=240)


def summary(output):
    with open(output / "summary.csv", encoding="utf-8") as rows:
        return {row["name"]: row for row in csv.DictReader(rows)}


@pytest.fixture(scope="module")
def inputs(cli, tmp_path_factory):
    """data/walk and data/run: synthetic sequences (frames/, masks/); bad.mp4: not a video (with
    ground truth in data/bad); inputs.txt lists walk's frames and bad.mp4."""
    data = tmp_path_factory.mktemp("data")
    for name, seed in [("walk", "1"), ("run", "2")]:
        subprocess.run([cli, "synth", "-o", str(data / name), "--frames", "6", "--size", "128x96",
                        "--seed", seed], check=True, capture_output=True)
        subprocess.run([cli, "segment", str(data / name / "frames"), "-o", str(data / name / "cli"),
                        "-q"], check=True, capture_output=True)
    (data / "bad.mp4").write_bytes(b"\x00\x00\x00\x18ftypmp42" + bytes(range(256)) * 8)
    shutil.copytree(data / "walk" / "masks", data / "bad" / "masks")  # its ground truth
    (data / "inputs.txt").write_text("# two of the three\nwalk/frames\n\nbad.mp4\n")
    return data


def test_corrupt_input_fails_alone_and_reruns_skip_finished_ones(inputs, tmp_path):
    out = tmp_path / "out"
    done = batch(str(inputs / "inputs.txt"), str(inputs / "run/frames"), "-o", str(out),
                 "--workers", "2", "--gt", str(inputs))
    assert done.returncode == 1, done.stdout + done.stderr
    rows = summary(out)
    assert [rows[name]["status"] for name in ("walk", "bad", "run")] == ["done", "failed", "done"]
    assert rows["bad"]["error"].startswith("movseg: error:"), rows["bad"]
    assert "batch: [3/3]" in done.stdout and "2 of 3 inputs segmented, 1 failed" in done.stdout
    for name in ("walk", "run"):
        masks = read_masks(out / name / "masks")
        assert len(masks) == 6 and all(np.array_equal(a, b) for a, b in
                                       zip(masks, read_masks(inputs / name / "cli")))
        assert len((out / name / "stats.jsonl").read_text().splitlines()) == 6
        assert float(rows[name]["J"]) > 0.5 and float(rows[name]["F"]) > 0
        assert json.loads((out / name / "summary.json").read_text())["frames"] == 6
    assert sorted(os.listdir(out)) == ["run", "summary.csv", "walk"]  # no partial folder left
    umask = os.umask(0)
    os.umask(umask)
    assert (out / "walk").stat().st_mode & 0o777 == 0o777 & ~umask  # not a temporary's 0700

    again = batch(str(inputs / "inputs.txt"), str(inputs / "run/frames"), "-o", str(out),
                  "--workers", "2")
    assert again.returncode == 1
    assert again.stdout.count("(finished before; --force redoes it)") == 2
    assert summary(out)["walk"]["status"] == "skipped"

    stamp = (out / "walk" / "summary.json").stat().st_mtime_ns
    region = np.zeros((96, 128), np.uint8)
    region[:, :64] = 255  # the left half, ignored
    cv2.imwrite(str(tmp_path / "region.png"), region)
    forced = batch(str(inputs / "walk/frames"), "-o", str(out), "--workers", "2", "--force",
                   "--method", "diff", "--set", "lk_window=15",
                   "--ignore", str(tmp_path / "region.png"))
    assert forced.returncode == 0, forced.stdout + forced.stderr
    assert (out / "walk" / "summary.json").stat().st_mtime_ns != stamp
    masks = read_masks(out / "walk" / "masks")
    assert not any(mask[:, :64].any() for mask in masks) and any(mask.any() for mask in masks)


def test_two_inputs_of_one_name_are_refused(inputs, tmp_path):
    (tmp_path / "walk").mkdir()
    done = batch(str(inputs / "walk"), str(tmp_path / "walk"), "-o", str(tmp_path / "out"))
    assert done.returncode == 2
    assert done.stderr.startswith("movseg batch: error: ") and "rename one" in done.stderr


def test_folders_it_did_not_write_and_inputs_in_their_own_output_are_never_replaced(inputs,
                                                                                   tmp_path):
    data = tmp_path / "data"
    shutil.copytree(inputs / "walk", data / "walk")
    before = sorted(os.listdir(data / "walk" / "frames"))
    (tmp_path / "out" / "run").mkdir(parents=True)  # a folder of the user's, no summary.json
    for sources, output, words in [
            ([data / "walk" / "frames"], data, "which the batch replaces"),  # data/walk/frames
            ([data / "walk" / "frames"], data / "walk" / "frames" / "out", "lies in the input"),
            ([inputs / "run" / "frames"], tmp_path / "out", "is no batch result"),
            # an input inside another input's result folder, which --force would replace
            ([inputs / "walk" / "frames", tmp_path / "out2" / "walk" / "masks"], tmp_path / "out2",
             "which the batch replaces")]:
        done = batch(*map(str, sources), "-o", str(output), "--force")
        assert done.returncode == 2 and words in done.stderr, done.stdout + done.stderr
        assert done.stderr.count("\n") == 1 and "batch: [" not in done.stdout
    assert sorted(os.listdir(data / "walk" / "frames")) == before
    assert os.listdir(tmp_path / "out" / "run") == []


def test_an_input_named_as_the_summary_and_an_empty_list_are_refused(inputs, tmp_path):
    (tmp_path / "summary.csv.mp4").write_bytes((inputs / "bad.mp4").read_bytes())
    (tmp_path / ".hidden.mp4").write_bytes((inputs / "bad.mp4").read_bytes())
    (tmp_path / "none.txt").write_text("# nothing yet\n")
    for source, words in [("summary.csv.mp4", "the batch's own"), (".hidden.mp4", "the batch's own"),
                          ("none.txt", "no inputs")]:
        done = batch(str(tmp_path / source), "-o", str(tmp_path / "out"))
        assert done.returncode == 2 and words in done.stderr, done.stdout + done.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("option", [["--method", "nonsense"], ["--set", "lk_window=12"],
                                    ["--set", "no_such_parameter=1"],
                                    ["--ignore", "/no/such/image.png"]])
def test_bad_arguments_are_refused_before_any_input_runs(inputs, tmp_path, option):
    done = batch(str(inputs / "run" / "frames"), "-o", str(tmp_path / "out"), *option)
    assert done.returncode == 2, done.stdout + done.stderr
    assert done.stderr.startswith("movseg batch: error: ") and done.stderr.count("\n") == 1
    assert not (tmp_path / "out").exists()


# SIGTERM as a cluster's job manager sends it, SIGINT as Ctrl-C does (README).
@pytest.mark.parametrize("stop", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_an_interrupted_run_keeps_what_finished_and_says_what_did_not(inputs, tmp_path, stop):
    listed = tmp_path / "inputs.txt"
    listed.write_text("".join(f"{inputs / 'walk' / 'frames'}\n" if i == 0 else
                              f"{tmp_path / f'copy{i}'}\n" for i in range(8)))
    for i in range(1, 8):
        shutil.copytree(inputs / "run" / "frames", tmp_path / f"copy{i}")
    out = tmp_path / "out"
    run = subprocess.Popen([sys.executable, "-m", "movseg", "batch", str(listed), "-o", str(out),
                            "--workers", "1"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           text=True)
    first = run.stdout.readline()  # the first input's line: the cluster runs
    run.send_signal(stop)
    rest, errors = run.communicate(timeout=120)
    assert first.startswith("batch: [1/8]") and run.returncode == 130, first + rest + errors
    assert "Traceback" not in errors and "(interrupted)" in rest
    rows = summary(out)
    assert len(rows) == 8 and any(row["error"] == "interrupted" for row in rows.values())
    for name, row in rows.items():
        assert (row["status"] == "done") == (out / name / "summary.json").is_file(), row
    assert not [entry for entry in os.listdir(out) if entry.startswith(".")]  # no scratch left


def test_a_tool_killed_by_a_signal_is_reported_as_such():
    from movseg.batch import failure

    assert failure(subprocess.CompletedProcess(["movseg", "eval"], -9, "", "")) == \
        "movseg eval was killed by signal 9"
    assert failure(subprocess.CompletedProcess(["movseg", "segment"], 1, "",
                                               "movseg: error: bad\n")) == "movseg: error: bad"


def free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def test_runs_on_a_scheduler_and_worker_started_by_hand(inputs, tmp_path):
    address = f"tcp://127.0.0.1:{free_port()}"
    logs = open(tmp_path / "cluster.log", "w")
    scheduler = subprocess.Popen(["dask", "scheduler", "--host", "127.0.0.1", "--port",
                                  address.rsplit(":", 1)[1], "--no-dashboard"],
                                 stdout=logs, stderr=logs)
    worker = subprocess.Popen(["dask", "worker", address, "--nworkers", "1", "--nthreads", "1",
                               "--no-dashboard"], stdout=logs, stderr=logs)
    try:
        time.sleep(1)
        done = batch(str(inputs / "run/frames"), "-o", str(tmp_path / "out"),
                     "--scheduler", address)
        log = (tmp_path / "cluster.log").read_text()
        assert done.returncode == 0, done.stdout + done.stderr + log
        assert summary(tmp_path / "out")["run"]["status"] == "done"
    finally:
        for process in (worker, scheduler):
            process.terminate()
            process.wait(timeout=30)
        logs.close()
