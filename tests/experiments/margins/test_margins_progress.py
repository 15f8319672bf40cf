"""``partfeeder margins`` says on stderr what it works through (issue 39: progress in a log):
off a terminal, a line when the axes start, per tenth of them, and at the end; a design that
does not work at nominal ends its line saying no axis was measured; ``--json`` is quiet."""

from __future__ import annotations

from cli_process import noise, run_cli


def test_margins_writes_its_progress_as_lines_off_a_terminal():
    done = run_cli("margins", "--design", "fig7a", "--drops", "2", "--workers", "1")
    assert done.returncode == 0, done.stderr
    lines = noise(done.stderr).splitlines()
    assert "\r" not in done.stderr
    assert lines[0] == "partfeeder: margins of fig7a: started, 16"
    assert lines[-1].startswith("partfeeder: margins of fig7a: stopped at 0/16 (0%) after ")
    assert lines[-1].endswith("| no axis measured: see the verdict at nominal")
    assert "no margins" in done.stdout
