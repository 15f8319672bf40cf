"""A command on a cold numba cache says, in one line on stderr, that it compiles the kernels
once for this machine and how long it took; on a warm cache it says nothing, and ``--json``
output stays clean either way (issue 22: a first run waited 15-60 s and nothing said why)."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest
from cli_process import ROOT

from experiments.cli.kernels import COMPILING, COMPILING_BAR, kernel_levels

PLAN = ("plan", "--level", "geometric", "--orientation", "heavy_leading", "--time", "0.05")


def _plan_json(cache) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", "from experiments.cli import main; main()", *PLAN, "--json"],
        cwd=ROOT,
        env={**os.environ, "NUMBA_CACHE_DIR": str(cache)},
        capture_output=True,
        text=True,
        timeout=600,
    )


@pytest.mark.slow  # a cold compile: ~80 s
def test_a_cold_cache_is_announced_once_and_a_warm_one_not_at_all(tmp_path):
    cold = _plan_json(tmp_path)
    assert cold.returncode == 0, cold.stderr
    notices = [line for line in cold.stderr.splitlines() if line.startswith(COMPILING)]
    assert len(notices) == 1 and notices[0].endswith(" s"), cold.stderr
    assert json.loads(cold.stdout)["runs"]  # stdout is the JSON alone
    warm = _plan_json(tmp_path)
    assert warm.returncode == 0, warm.stderr
    assert COMPILING not in warm.stderr
    assert json.loads(warm.stdout)["runs"]


def test_the_passive_rung_uses_the_dynamic_kernels():
    assert kernel_levels(["passive", "geometric"]) == ["geometric", "dynamic"]
    assert kernel_levels(["dynamic", "passive"]) == ["dynamic"]


@pytest.mark.slow
def test_on_a_terminal_a_cold_compile_is_a_bar_over_the_levels_with_its_total(tmp_path):
    """stderr a pseudo-terminal: the compile shows as a tqdm bar whose total is the number of
    levels made ready (the plan's one), ending at 1/1; the one-line notice is not printed."""
    import fcntl
    import pty
    import struct
    import termios

    main, child = pty.openpty()
    fcntl.ioctl(child, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 120, 0, 0))  # 120 columns
    proc = subprocess.Popen(
        [sys.executable, "-c", "from experiments.cli import main; main()", *PLAN, "--json"],
        cwd=ROOT,
        env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)},
        stdout=subprocess.PIPE,
        stderr=child,
        text=True,
    )
    os.close(child)
    chunks = []
    while True:
        try:
            data = os.read(main, 4096)
        except OSError:  # the child closed its end
            break
        if not data:
            break
        chunks.append(data.decode(errors="replace"))
    out, _ = proc.communicate(timeout=600)
    os.close(main)
    shown = "".join(chunks)
    assert proc.returncode == 0, shown
    assert COMPILING_BAR in shown and "1/1" in shown and "0/1" in shown, shown
    assert COMPILING not in shown
    assert json.loads(out)["runs"]
