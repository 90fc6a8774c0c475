"""python3 -m movseg ARGS...: runs the movseg command-line tool with ARGS.

The tool is the compiled `movseg` program itself, not a Python re-implementation, so both behave
the same by construction. It is looked up where the build that made this package put it
(recorded in _cli.py), then on PATH.
"""
import os
import shutil
import sys


def cli_path():
    try:
        from ._cli import CLI_PATH
    except ImportError:
        CLI_PATH = ""
    if CLI_PATH and os.access(CLI_PATH, os.X_OK):
        return CLI_PATH
    return shutil.which("movseg")


def main():
    path = cli_path()
    if path is None:
        sys.exit("movseg: the movseg command-line tool was found neither next to this build nor on PATH")
    os.execv(path, [path] + sys.argv[1:])


if __name__ == "__main__":
    main()
