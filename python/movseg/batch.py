"""python3 -m movseg batch INPUT... -o OUTDIR: many videos at once, on one machine or a cluster.

Each input (a video file, a folder of frames, or a text file listing such inputs, one a line) is
one task on Dask distributed: a local cluster of one worker process per core, or the cluster of
the scheduler given with --scheduler. A task runs the compiled `movseg segment` tool, as
`python3 -m movseg` does, so its masks are the CLI's bit for bit; it writes the input's results
into a hidden folder of OUTDIR and renames it to OUTDIR/<name>/ when they are complete:

    OUTDIR/<name>/masks/00000.png, ...   the masks
    OUTDIR/<name>/stats.jsonl            the diagnostics of every frame (`movseg segment --stats`)
    OUTDIR/<name>/summary.json           the input's summary row, written last
    OUTDIR/summary.csv                   every input's row, rewritten at the end of each run

A finished input (one whose folder holds its summary.json) is skipped on a re-run unless --force;
a folder of that name that is not a batch result, or that holds the input, is never replaced: the
run is refused. A failing input is reported with its error and does not stop the others; the exit
status is 1 when any failed, 2 for bad arguments, 130 when interrupted.
"""
import argparse
import contextlib
import csv
import ctypes
import io
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import uuid

from .__main__ import cli_path

COLUMNS = ["name", "input", "status", "frames", "seconds", "fps", "J", "F", "error"]
SUMMARY = "summary.csv"  # OUTDIR's own file
# Folder names that say what a folder holds rather than which video it is: clip/frames is "clip".
LAYOUT_FOLDERS = {"frames", "input", "images"}


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="python3 -m movseg batch",
        description="Segment many videos at once on Dask distributed, one task per input.")
    parser.add_argument("inputs", nargs="+", metavar="INPUT",
                        help="video file, folder of frames, or .txt file listing such inputs")
    parser.add_argument("-o", "--output", required=True, metavar="OUTDIR",
                        help="folder of the results: OUTDIR/<name>/ per input, OUTDIR/summary.csv")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="a running Dask scheduler (tcp://host:8786); default: a local cluster")
    parser.add_argument("--workers", type=int, metavar="N",
                        help="worker processes of the local cluster (default: one per core)")
    parser.add_argument("--method", help="segmentation method (movseg segment --method)")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="a parameter by its name (movseg segment --set), repeatable")
    parser.add_argument("--ignore", metavar="IMAGE",
                        help="white where nothing moves, for every input (movseg segment "
                             "--ignore); every worker must see it at its absolute path")
    parser.add_argument("--gt", metavar="DIR",
                        help="ground truth, DIR/<name>/ per input (as movseg eval reads it): "
                             "adds J and F to the summary")
    parser.add_argument("--force", action="store_true", help="redo finished inputs too")
    args = parser.parse_args(argv)
    if args.workers is not None and (not 1 <= args.workers <= 256 or args.scheduler):
        parser.error("--workers takes a count from 1 to 256, for the local cluster only")
    return args


def read_list(path):
    """The inputs a list file names; relative paths are relative to the list's folder."""
    folder = os.path.dirname(os.path.abspath(path))
    with open(path, encoding="utf-8") as lines:
        entries = [line.strip() for line in lines]
    return [os.path.join(folder, entry) for entry in entries if entry and not entry.startswith("#")]


def expand_inputs(inputs):
    """Absolute paths, which every worker sees alike, with list files replaced by their entries."""
    expanded = []
    for source in inputs:
        if os.path.isfile(source) and source.endswith(".txt"):
            expanded += read_list(source)
        else:
            expanded.append(os.path.abspath(source))
    return expanded


def input_name(source):
    """'clips/walk.mp4' -> 'walk'; 'walk/frames' -> 'walk'."""
    path = os.path.normpath(source)
    name = os.path.basename(path)
    if os.path.isdir(path):
        return os.path.basename(os.path.dirname(path)) if name in LAYOUT_FOLDERS else name
    return os.path.splitext(name)[0]


def named_inputs(sources):
    if not sources:
        raise ValueError("no inputs: the list files name none")
    named = {}
    for source in sources:
        name = input_name(source)
        if name == SUMMARY or name.startswith("."):
            raise ValueError(f"'{source}' would write OUTDIR/{name}/: the summary and hidden "
                             "names are the batch's own; rename it")
        if name in named:
            raise ValueError(f"'{named[name]}' and '{source}' would both write OUTDIR/{name}/: "
                             "rename one")
        named[name] = source
    return named


def is_inside(path, folder):
    """Whether `path` is `folder` or lies below it, links resolved."""
    path, folder = os.path.realpath(path), os.path.realpath(folder)
    return os.path.commonpath([path, folder]) == folder


def is_batch_result(folder):
    return os.path.isfile(os.path.join(folder, "summary.json"))


def refuse_replacing_what_is_not_ours(named, output, read):
    """OUTDIR/<name>/ is replaced whole when an input is redone: it must be an earlier result of
    a batch, never a folder of the user's; no input, nor any other file the run reads (`read`:
    --ignore, --gt), may lie in one, and OUTDIR in no input."""
    folders = [os.path.join(output, name) for name in named]
    for path in [*named.values(), *read]:
        for folder in folders:
            if is_inside(path, folder):
                raise ValueError(f"'{path}' lies in {folder}, which the batch replaces: choose "
                                 "another OUTDIR")
    for source in named.values():
        if is_inside(output, source):
            raise ValueError(f"OUTDIR {output} lies in the input '{source}'")
    for folder in folders:
        if os.path.lexists(folder) and not is_batch_result(folder):
            raise ValueError(f"{folder} exists and is no batch result (no summary.json): "
                             "move it or choose another OUTDIR")


def refuse_bad_segment_options(options):
    """The tool checks its options before it opens an input (exit 2 for a bad one), so a path
    that does not exist finds a bad --method or --set here rather than once per input."""
    if cli_path() is None:
        raise ValueError("the movseg command-line tool was found neither with this package nor "
                         "on PATH")
    with tempfile.TemporaryDirectory() as scratch:
        missing = os.path.join(scratch, "none")
        done = run_tool("segment", missing, "-o", missing, "-q", *options)
    if done.returncode == 2:
        raise ValueError(failure(done).removeprefix("movseg: error: "))


def failure(done):
    """What a run of the tool that failed says: its last line, or the signal that ended it."""
    if done.returncode < 0:
        return f"movseg {done.args[1]} was killed by signal {-done.returncode}"
    lines = done.stderr.strip().splitlines()
    return lines[-1] if lines else f"movseg exited with {done.returncode} and no message"


def scores(masks, truth, scratch):
    """J and F of the masks against the ground truth, by `movseg eval`."""
    report = os.path.join(scratch, "eval.json")
    done = run_tool("eval", masks, truth, "--json", report)
    if done.returncode != 0:
        raise RuntimeError(failure(done))
    with open(report, encoding="utf-8") as text:
        mean = json.load(text)["mean"]
    os.remove(report)
    return {"J": round(mean["J"], 4), "F": round(mean["F"], 4)}


def publish(scratch, folder):
    """Puts the finished scratch folder in place of OUTDIR/<name>/ in one rename (a previous
    result, when --force redoes one, goes only once the new one is complete)."""
    old = None
    if os.path.lexists(folder):
        if not is_batch_result(folder):  # made since the run was checked
            raise RuntimeError(f"{folder} exists and is no batch result: left as it is")
        old = scratch + ".old"
        os.rename(folder, old)
    os.rename(scratch, folder)
    if old:
        shutil.rmtree(old)


_PRCTL = ctypes.CDLL(None, use_errno=True).prctl  # looked up here, not in a forked child
_PR_SET_PDEATHSIG = 1


def run_tool(*args):
    """The tool run with `args` (output captured). It dies with the process that started it (a
    worker killed mid-task would leave it writing into OUTDIR for nobody); the child does no
    more than two system calls between fork and exec, as a child of a threaded process must."""
    parent = os.getpid()

    def die_with_parent():
        _PRCTL(_PR_SET_PDEATHSIG, signal.SIGKILL)
        if os.getppid() != parent:  # the parent died before the call above
            os._exit(1)

    return subprocess.run([cli_path(), *args], capture_output=True, text=True,
                          preexec_fn=die_with_parent)


def segment_input(name, source, output, options, truth):
    """One task: segments `source` into output/name/ and returns its summary row. Runs on a
    worker; a failure is returned as a row, so that it never stops the other inputs."""
    row = {"name": name, "input": source, "status": "failed"}
    # Not mkdtemp's: its folders are private (0700), where the results take the umask's mode.
    scratch = os.path.join(output, f".{name}.{uuid.uuid4().hex}.partial")
    os.mkdir(scratch)
    try:
        if truth and not os.path.isdir(truth):
            raise RuntimeError(f"no ground truth '{truth}'")
        masks, stats = os.path.join(scratch, "masks"), os.path.join(scratch, "stats.jsonl")
        start = time.monotonic()
        done = run_tool("segment", source, "-o", masks, "--stats", stats, "-q", *options)
        if done.returncode != 0:
            raise RuntimeError(failure(done))
        seconds = time.monotonic() - start
        with open(stats, encoding="utf-8") as lines:
            frames = sum(1 for _ in lines)
        row.update(status="done", frames=frames, seconds=round(seconds, 3),
                   fps=round(frames / seconds, 1))
        if truth:
            row.update(scores(masks, truth, scratch))
        with open(os.path.join(scratch, "summary.json"), "w", encoding="utf-8") as summary:
            json.dump(row, summary)
        publish(scratch, os.path.join(output, name))
    except (OSError, RuntimeError) as error:
        row["error"] = str(error)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    return row


def failed_row(name, source, error):
    return {"name": name, "input": source, "status": "failed", "error": error}


def finished_row(output, name, status):
    """The summary row of a finished input, with `status`; None when it has none."""
    try:
        with open(os.path.join(output, name, "summary.json"), encoding="utf-8") as summary:
            return {**json.load(summary), "status": status}
    except (OSError, ValueError):
        return None


def write_csv(path, rows):
    text = io.StringIO()
    writer = csv.DictWriter(text, COLUMNS, extrasaction="ignore")
    writer.writeheader()
    writer.writerows(rows)
    scratch = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".partial")
    with open(scratch, "w", encoding="utf-8") as out:
        out.write(text.getvalue())
    os.replace(scratch, path)


def describe(row):
    if row["status"] == "failed":
        return f"failed: {row['error']}"
    text = f"{row['status']}: {row['frames']} frames, {row['fps']} fps"
    if "J" in row:
        text += f", J {row['J']:.3f}, F {row['F']:.3f}"
    return text + (" (finished before; --force redoes it)" if row["status"] == "skipped" else "")


@contextlib.contextmanager
def dask_client(args):
    """A client of the scheduler at --scheduler, else of a local cluster closed with it."""
    from dask.distributed import Client, LocalCluster  # the rest of the package needs no Dask

    if args.scheduler:
        with Client(args.scheduler) as client:
            yield client
        return
    # The worker processes inherit SIGINT ignored (Python leaves it so), so that a Ctrl-C
    # reaches this process, which closes them, and the tools their tasks run, rather than every
    # worker's event loop, which would print a traceback each. One while they start is lost.
    handler = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        cluster = LocalCluster(n_workers=args.workers or os.cpu_count(), threads_per_worker=1,
                               processes=True, dashboard_address=None)
    finally:
        signal.signal(signal.SIGINT, handler)
    with cluster, Client(cluster) as client:
        yield client


def published_since(output, name, started):
    """The row of OUTDIR/<name>/ as done, when this run published it (after `started`)."""
    try:
        published = os.stat(os.path.join(output, name, "summary.json")).st_mtime
    except OSError:
        return None
    return finished_row(output, name, "done") if published >= started else None


def run(args):
    started = time.time()
    output = os.path.abspath(args.output)
    named = named_inputs(expand_inputs(args.inputs))
    refuse_replacing_what_is_not_ours(named, output, [p for p in (args.ignore, args.gt) if p])
    if args.ignore and not os.path.isfile(args.ignore):
        raise ValueError(f"--ignore: no file '{args.ignore}'")
    options = (["--method", args.method] if args.method else []) + \
        [item for value in args.set for item in ("--set", value)] + \
        (["--ignore", os.path.abspath(args.ignore)] if args.ignore else [])
    refuse_bad_segment_options(options)
    os.makedirs(output, exist_ok=True)
    rows, todo = {}, []
    for name, source in named.items():
        finished = None if args.force else finished_row(output, name, "skipped")
        if finished:
            rows[name] = finished
        else:
            todo.append(name)
    count = len(named)
    for index, name in enumerate(rows, 1):
        print(f"batch: [{index}/{count}] {name} {describe(rows[name])}", flush=True)
    interrupted = False
    try:
        if todo:
            segment_on_dask(args, named, todo, output, options, rows)
    except KeyboardInterrupt:  # SIGINT, or SIGTERM (main): the finished inputs are kept
        interrupted = True
    finally:
        remove_scratch_folders(output, todo)
    # An input whose task published its folder as the run was interrupted is done all the same
    # (a folder of an earlier run, which --force was redoing, is not).
    ordered = [rows.get(name) or published_since(output, name, started) or
               failed_row(name, named[name], "interrupted") for name in named]
    write_csv(os.path.join(output, SUMMARY), ordered)
    failed = sum(row["status"] == "failed" for row in ordered)
    print(f"batch: {count - failed} of {count} inputs segmented, {failed} failed"
          f"{' (interrupted)' if interrupted else ''}; "
          f"summary in {os.path.join(output, SUMMARY)}", flush=True)
    return 130 if interrupted else 1 if failed else 0


def remove_scratch_folders(output, names):
    """What a task killed with its worker (or interrupted) left: its hidden scratch folder,
    .<name>.<32 hex digits>.partial (and .old, as publish() names the one it replaces)."""
    for name in names:
        own = re.compile(rf"\.{re.escape(name)}\.[0-9a-f]{{32}}\.partial(\.old)?")
        for entry in os.listdir(output):
            if own.fullmatch(entry):
                shutil.rmtree(os.path.join(output, entry), ignore_errors=True)


def segment_on_dask(args, named, todo, output, options, rows):
    """Runs the inputs named in `todo` as Dask tasks, adding each one's row to `rows`."""
    from dask.distributed import as_completed

    count = len(named)
    with dask_client(args) as client:
        futures = {client.submit(segment_input, name, named[name], output, options,
                                 args.gt and os.path.join(os.path.abspath(args.gt), name),
                                 pure=False): name for name in todo}
        for future in as_completed(futures):
            name = futures[future]
            try:
                rows[name] = future.result()
            except Exception as error:  # the worker itself failed (killed, lost)
                rows[name] = failed_row(name, named[name], f"{type(error).__name__}: {error}")
            print(f"batch: [{len(rows)}/{count}] {name} {describe(rows[name])}", flush=True)


def interrupt(signum, frame):
    raise KeyboardInterrupt


def main(argv):
    args = parse_arguments(argv)
    signal.signal(signal.SIGTERM, interrupt)
    try:
        return run(args)
    except (OSError, ValueError) as error:
        print(f"movseg batch: error: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # before the inputs ran (run() reports one while they do)
        print("movseg batch: interrupted", file=sys.stderr)
        return 130
