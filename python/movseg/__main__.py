"""python3 -m movseg ARGS...: runs the movseg command-line tool with ARGS.

The tool is the compiled `movseg` program itself, not a Python re-implementation, so both behave
the same by construction. It is looked up where the build or the install that made this package
put it (_build_info.py), then on PATH. `python3 -m movseg batch ...` segments many videos at once
on Dask (batch.py).
"""
import os
import shutil
import sys

from ._build_info import CLI_PATH


def cli_path():
    # CLI_PATH is absolute in a build tree and relative to this folder in an installed tree.
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), CLI_PATH)
    if os.access(path, os.X_OK):
        return os.path.normpath(path)
    return shutil.which("movseg")


def main():
    if sys.argv[1:2] == ["batch"]:
        from .batch import main as batch  # imports Dask, which nothing else needs

        sys.exit(batch(sys.argv[2:]))
    path = cli_path()
    if path is None:
        sys.exit("movseg: the movseg command-line tool was found neither with this package nor "
                 "on PATH")
    os.execv(path, [path] + sys.argv[1:])


if __name__ == "__main__":
    main()
