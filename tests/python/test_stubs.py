"""The type stubs (__init__.pyi, generated from the field tables): mypy takes right uses of the
package and flags wrong ones."""
import keyword
import os
import re
import subprocess
import sys
import textwrap

import movseg

USER_CODE = textwrap.dedent("""\
    from typing import Optional

    import numpy as np
    import movseg

    params = movseg.Params(lambda_=400.0, method="diff", static_camera=True)
    params.motion_model = "homography"
    window: int = params.lk_window
    result = movseg.Segmenter(params).process(np.zeros((8, 8, 3), np.uint8), rgb=True)
    mask: np.ndarray = result.mask
    total: float = result.diagnostics.total_ms
    model = result.diagnostics.model
    subtractor = movseg.createMovingCameraSubtractor(params, ignored_region=np.ones((8, 8)))
    subtractor.clear()
    stream = movseg.StreamSegmenter(params, threads=2)
    previous: Optional[movseg.Result] = stream.push(np.zeros((8, 8, 3), np.uint8))
    movseg.Params(method="nope")
    params.lk_window = "11"
    total_text: str = result.diagnostics.total_ms
""")


def test_mypy_checks_user_code_against_the_stubs(tmp_path):
    # Not skipped without mypy (scripts/install-deps.sh installs it): its absence fails below.
    (tmp_path / "user.py").write_text(USER_CODE)
    package_dir = os.path.dirname(os.path.dirname(movseg.__file__))
    done = subprocess.run(
        [sys.executable, "-m", "mypy", "--ignore-missing-imports", "--no-error-summary",
         "--cache-dir", str(tmp_path / "cache"), str(tmp_path / "user.py")],
        capture_output=True, text=True, env={**os.environ, "MYPYPATH": package_dir})
    errors = [line for line in done.stdout.splitlines() if ": error:" in line]
    flagged = sorted(int(line.split(":")[1]) for line in errors)
    assert flagged == [17, 18, 19], done.stdout + done.stderr


def class_body(stubs, name):
    """The lines of `class name:` in the stubs, up to the next top-level line."""
    body = stubs.split(f"\nclass {name}:", 1)[1]
    return re.split(r"\n(?=\S)", body, maxsplit=1)[0]


def test_stubs_list_every_field():
    stubs = open(os.path.join(os.path.dirname(movseg.__file__), "__init__.pyi")).read()
    # Declared in their class — an attribute of Params, a property of Diagnostics — under the
    # name Python gives them (`lambda_`): a name that only a comment mentions is not declared.
    for cls, fields in (("Params", movseg._movseg._param_fields()),
                        ("Diagnostics", movseg._movseg._diagnostic_fields())):
        body = class_body(stubs, cls)
        for field in fields:
            name = field["name"] + ("_" if keyword.iskeyword(field["name"]) else "")
            assert re.search(rf"^    (def )?{name}\b", body, re.M), (cls, name)
    assert 'method: Literal["paper", "diff", "mog2", "mog2-comp", "dense"]' in stubs
    # Every public name of the stubs is the module's (a stub-only alias misled users).
    names = {line.split()[1].split("(")[0].rstrip(":") if line.startswith(("class ", "def "))
             else line.split()[0].rstrip(":") for line in stubs.splitlines()
             if line[:1].isalpha() and not line.startswith(("from ", "import "))}
    assert names and all(hasattr(movseg, name) for name in names if not name.startswith("_")), \
        sorted(name for name in names if not hasattr(movseg, name))
