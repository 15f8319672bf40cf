"""A command ends through :func:`experiments.cli.console.exit_now` (``os._exit``, skipping the
interpreter's exit hooks): what multiprocessing would release at exit is released first, so
an interrupted command's last line is its own, not the resource tracker's "leaked semaphore
objects" warning (seen in CI after Ctrl-C reached ``partfeeder optimize`` mid-shutdown)."""

from __future__ import annotations

import subprocess
import sys

from cli_process import ROOT

HOLDS_A_SEMAPHORE = (
    "import multiprocessing\n"
    "from experiments.cli.console import exit_now\n"
    "lock = multiprocessing.get_context('spawn').Lock()  # a named semaphore, tracked\n"
    "exit_now(130)\n"
)


def test_exit_now_leaves_no_semaphore_for_the_resource_tracker_to_report():
    done = subprocess.run(
        [sys.executable, "-c", HOLDS_A_SEMAPHORE],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 130
    assert "leaked semaphore" not in done.stderr, done.stderr
    assert done.stderr == ""
