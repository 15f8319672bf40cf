"""A full disk is said as a full disk: free space and run the same command again, nothing
stored is lost (issue 37, found by tests/experiments/sweep/test_full_disk_resume.py: the line
said to move the database aside, the very advice issue 37 item 4 complained of; and a disk
filled during OMPL's export ended in a traceback)."""

from __future__ import annotations

import errno
import sqlite3

import pytest

from experiments.cli.errors import input_error_line


@pytest.mark.parametrize(
    "exc",
    [
        sqlite3.OperationalError("database or disk is full"),
        OSError(errno.ENOSPC, "No space left on device", "sweep/ompl/logs/x.log"),
        OSError(errno.EDQUOT, "Disk quota exceeded", "sweep/results.sqlite"),
    ],
    ids=["sqlite", "ENOSPC", "EDQUOT"],
)
def test_a_full_disk_says_free_space_and_run_again_never_move_it_aside(exc) -> None:
    line = input_error_line(exc)
    assert line is not None and "\n" not in line
    assert "full" in line and "free space" in line and "run the same command again" in line
    assert "move it aside" not in line and "delete" not in line


def test_a_full_disk_during_ompls_export_is_the_full_disk_not_a_reader_failure(
    tmp_path, monkeypatch
) -> None:
    from experiments.sweep import ladder

    def full(target, paths):
        raise sqlite3.OperationalError("database or disk is full")

    monkeypatch.setattr(ladder, "_read_logs", full)
    monkeypatch.setattr(ladder.results_db, "connect", _NoLogs)
    with pytest.raises(sqlite3.OperationalError, match="disk is full"):
        ladder.export_ompl(tmp_path / "results.sqlite", tmp_path / "ompl")


class _NoLogs:
    """A results database with no OMPL log (what export reads)."""

    def __init__(self, *args, **kwargs):
        pass

    def execute(self, *args):
        return []

    def close(self):
        pass
