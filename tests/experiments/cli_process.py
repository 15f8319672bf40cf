"""The ``partfeeder`` command run as a user runs it: a fresh process (so exit-time output,
such as nanobind's leak report, would be seen too)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
# On a cold numba cache (a fresh install, an edited kernel) a command first says on stderr that
# it compiles the kernels once, and how long it took (experiments/cli/kernels.py): not noise.
COMPILE_NOTICE = re.compile(r"^partfeeder: compiling the numba kernels[^\n]*\n", re.MULTILINE)


def noise(stderr: str) -> str:
    """``stderr`` without the cold-cache compile notice: what a clean run leaves empty, on a
    warm cache or a cold one."""
    return COMPILE_NOTICE.sub("", stderr)


def run_cli(*args: str, timeout: float = 600) -> subprocess.CompletedProcess:
    """``partfeeder ARGS`` from the repository root; stdout and stderr as text."""
    return subprocess.run(
        [sys.executable, "-c", "from experiments.cli import main; main()", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=timeout,
    )
