"""The test suite passes when started in the background (issue 39): ``nohup python -m pytest
&`` starts it with SIGINT ignored, which every process it starts inherits, and the tests of
what Ctrl-C does failed there (the pool's stop test raised no KeyboardInterrupt). The tests
that signal a command start it as from a terminal (``process_table.interruptible``), those
that signal this process set SIGINT as from a terminal for their duration
(``process_table.sigint_as_from_a_terminal``). Reference: the same tests in a test run
started with SIGINT ignored, as a shell's ``&`` starts it."""

from __future__ import annotations

import signal
import subprocess
import sys

import pytest
from cli_process import ROOT

HANG_GUARD_S = 1800  # only a hang waits this long


def _in_the_background() -> None:
    """As a non-interactive shell's ``&`` starts a command: SIGINT ignored (a ``preexec_fn``)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _pytest_in_the_background(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=HANG_GUARD_S,
        preexec_fn=_in_the_background,
    )


def test_the_pools_ctrl_c_tests_pass_in_a_test_run_started_in_the_background() -> None:
    done = _pytest_in_the_background("tests/experiments/executors/test_local.py")
    assert done.returncode == 0, done.stdout[-3000:]
    assert " passed" in done.stdout and "failed" not in done.stdout


@pytest.mark.slow  # every signal test of the default suite: several minutes
def test_every_signal_test_passes_in_a_test_run_started_in_the_background() -> None:
    done = _pytest_in_the_background(
        "tests/experiments/executors",
        "tests/experiments/test_command_signals.py",
        "tests/experiments/cli/test_signals.py",
        "tests/experiments/stress/test_stress_signals.py",
        "tests/experiments/sweep/test_sweep.py",
    )
    assert done.returncode == 0, done.stdout[-3000:]
    assert " passed" in done.stdout and "failed" not in done.stdout
