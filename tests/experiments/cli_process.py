"""The ``partfeeder`` command run as a user runs it: a fresh process (so exit-time output,
such as nanobind's leak report, would be seen too)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def run_cli(*args: str, timeout: float = 600) -> subprocess.CompletedProcess:
    """``partfeeder ARGS`` from the repository root; stdout and stderr as text."""
    return subprocess.run(
        [sys.executable, "-c", "from experiments.cli import main; main()", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=timeout,
    )
