"""The command line's terminal progress line, read through a pseudo-terminal as a user sees it."""

import os
import pty
import re
import subprocess

from conftest import EXAMPLE


def test_the_progress_line_shows_step_stage_and_times(tmp_path, cli):
    leader, follower = pty.openpty()
    # Smoothing ten times as long as by default: a stage that lasts past the line's first second on any machine.
    run = subprocess.Popen([cli, str(EXAMPLE), "-o", str(tmp_path / "out"), "--smooth-iterations", "1500"],
                           stdout=subprocess.DEVNULL, stderr=follower)
    os.close(follower)
    seen = b""
    while True:
        try:
            chunk = os.read(leader, 4096)
        except OSError:  # the run closed its end
            break
        if not chunk:
            break
        seen += chunk
    assert run.wait() == 0
    lines = [line for line in seen.decode().replace("\x1b[K", "").split("\r") if line.startswith("scansurf: [")]
    shown = [re.fullmatch(r"scansurf: \[(\d+)/(\d+)\] ([a-z ]+?)(?: \(layer \d+ of \d+\))? ([0-9.]+) s "
                          r"\(([0-9.]+) s since the start\)", line) for line in lines]
    assert lines and all(shown), lines
    steps = [(int(m.group(1)), int(m.group(2))) for m in shown]
    assert all(k <= n for k, n in steps) and steps == sorted(steps)  # the step only goes forward
    stages = [m.group(3) for m in shown]
    assert "smoothing" in stages  # redrawn during a stage, not only between them
    assert all(float(m.group(4)) <= float(m.group(5)) for m in shown)
    assert seen.decode().rstrip("\r\n").endswith("\x1b[K") or "\r\x1b[K" in seen.decode()  # the line is cleared at the end
