"""Ctrl-C stops the stress suite run in its own process (``--workers 1``): issue 23. Its
kernel warm-up started a worker in the main process, which ignores SIGINT, so the suite ran
on through every Ctrl-C. Reference: the process's own exit status and stderr."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest
from process_table import interruptible

pytestmark = pytest.mark.skipif(not os.path.isdir("/proc"), reason="reads the process table")

CLI = "from experiments.cli import main; main()"
CPU_BEFORE_SIGNAL_S = 4.0  # past the kernels' warm-up: the cases are running


def _cpu_seconds(pid: int) -> float:
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def test_ctrl_c_stops_a_stress_run_in_one_process_with_one_line() -> None:
    process = subprocess.Popen(
        [sys.executable, "-c", CLI, "stress", "--cases", "1000000", "--workers", "1", "--quiet"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
        preexec_fn=interruptible,
    )
    try:
        while _cpu_seconds(process.pid) < CPU_BEFORE_SIGNAL_S:
            assert process.poll() is None, process.communicate()[1]
            time.sleep(0.1)
        os.killpg(process.pid, signal.SIGINT)
        _, err = process.communicate(timeout=300)  # a hang guard
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
    assert process.returncode == 130, err
    assert err.count("\n") == 1 and "interrupted" in err, err
