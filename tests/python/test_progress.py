"""`movseg segment` reports progress as README says: a bar with fps on a terminal, plain lines
otherwise, a one-line summary at the end."""
import os
import pty
import subprocess


def run_on_a_terminal(args):
    """`args` run with stdout and stderr on a pseudo-terminal; everything it wrote."""
    pid, terminal = pty.fork()
    if pid == 0:
        os.execv(args[0], args)
    output = b""
    while True:
        try:
            chunk = os.read(terminal, 4096)
        except OSError:  # the child has closed the terminal
            break
        if not chunk:
            break
        output += chunk
    _, status = os.waitpid(pid, 0)
    assert os.waitstatus_to_exitcode(status) == 0, output
    return output.decode()


def test_a_bar_on_a_terminal(cli, clip, tmp_path):
    output = run_on_a_terminal([cli, "segment", str(clip / "frames"), "-o", str(tmp_path)])
    assert "\rsegment [##############################] 8/8 frames, " in output
    assert " per second" in output
    assert output.rstrip().splitlines()[-1].startswith("segment: 8 frames in ")


def test_plain_lines_otherwise(cli, clip, tmp_path):
    done = subprocess.run([cli, "segment", str(clip / "frames"), "-o", str(tmp_path)],
                          capture_output=True, text=True, check=True)
    assert "\r" not in done.stderr and "#" not in done.stderr
    assert any(line.startswith("segment: 8 frames, ") and line.endswith(" per second")
               for line in done.stderr.splitlines())
    assert done.stdout.splitlines()[-1].startswith("segment: 8 frames in ")
