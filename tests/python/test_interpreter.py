"""`import movseg` in an interpreter that lacks what the module is built with names the one it
is built for."""
import subprocess
import sys

import movseg
from movseg._build_info import PYTHON


def test_missing_numpy_names_the_interpreter_the_module_is_built_for():
    # sys.modules["numpy"] = None makes `import numpy` fail as in a python3 without numpy.
    done = subprocess.run(
        [sys.executable, "-c", "import sys; sys.modules['numpy'] = None; import movseg"],
        capture_output=True, text=True)
    assert done.returncode != 0
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: movseg is built for " + PYTHON), done.stderr
    assert "this is " + sys.executable in last


def test_built_for_the_interpreter_that_runs_the_tests():
    assert PYTHON == sys.executable and movseg.__version__
