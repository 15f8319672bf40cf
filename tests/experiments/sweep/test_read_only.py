"""A finished sweep in a directory this process may not write (issue 23): ``optimize --from``
reads it (it only reads), ``report`` (which writes ``report.html`` and ``summary.json`` there)
says in one line that the directory is not writable. Both once failed: SQLite's read-only
mode wants to create the WAL database's ``-shm`` and ``-wal`` files beside it (SQLite's
"attempt to write a readonly database", shown as a damaged database), and the report's first
write was a traceback.

The directory is made unwritable for this process: ``chmod -R a-w`` for a user; root writes
through permission bits, so as root the files and directory get the immutable attribute
(``chattr +i``), which stops root too; where that is not possible the test is skipped. The
test that needs neither checks what the read path does everywhere: it opens the database with
a connection that cannot write, and leaves every file in the directory as it was, creating
none."""

from __future__ import annotations

import os
import shutil
import stat
import subprocess
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest
from file_state import directory_state
from sweep_fixtures import TINY, fake_result, fake_verdict

from experiments.cli import run
from experiments.cli.optimize import sweep_best_designs
from experiments.sweep import results_db
from experiments.sweep.config import config_from_dict
from feeders.halton import halton_points


def finished_sweep(directory: Path) -> Path:
    """A finished sweep's directory (WAL database, no ``-wal`` or ``-shm`` beside it): two
    designs with a passive verdict, design 1 working."""
    config = config_from_dict(
        {
            **TINY,
            "designs": {"count": 2, "seed": 1},
            "ladder": [{"level": "passive"}],
            "holdout": {"fraction": 0.0, "seed": 7},
        }
    )
    directory.mkdir()
    db = results_db.connect(directory / "results.sqlite")
    try:
        results_db.claim(db, config.to_dict(), config.results_key())
        points = halton_points(2, 1)
        results_db.add_designs(db, ((i, False, list(points[i])) for i in range(2)))
        failing = fake_result(0, "passive", "infeasible", 0.1, fake_verdict("fails", 0, 9, None))
        working = fake_result(1, "passive", "feasible", 0.1, fake_verdict("works", 40, 40, 2.0))
        results_db.record(db, failing, 0, 1)
        results_db.record(db, working, 0, 1)
    finally:
        db.close()
    assert sorted(os.listdir(directory)) == ["results.sqlite"]
    return directory


def _chattr(flag: str, paths: list[Path]) -> bool:
    chattr = shutil.which("chattr")
    if chattr is None:
        return False
    done = subprocess.run([chattr, flag, *map(str, paths)], capture_output=True)
    return done.returncode == 0


@contextmanager
def unwritable(directory: Path) -> Iterator[None]:
    """``directory`` and everything in it unwritable for this process, restored after."""
    paths = [*sorted(directory.rglob("*"), reverse=True), directory]
    if os.geteuid() != 0:
        modes = {p: p.stat().st_mode for p in paths}
        for p in paths:
            p.chmod(stat.S_IMODE(modes[p]) & ~0o222)
        try:
            yield
        finally:
            for p in reversed(paths):
                p.chmod(stat.S_IMODE(modes[p]))
        return
    if not _chattr("+i", paths):
        _chattr("-i", paths)
        pytest.skip("running as root where chattr +i is not possible: root writes anywhere")
    try:
        assert not os.access(directory, os.W_OK)
        yield
    finally:
        _chattr("-i", paths)


def test_the_read_path_opens_the_database_unable_to_write_and_creates_nothing(tmp_path):
    sweep = finished_sweep(tmp_path / "sweep")
    before = directory_state(sweep)
    db = results_db.connect(sweep / "results.sqlite", readonly=True)
    try:
        assert db.execute("SELECT count(*) FROM designs").fetchone()[0] == 2
        with pytest.raises(results_db.sqlite3.OperationalError, match="readonly"):
            db.execute("CREATE TABLE written (x INTEGER)")
    finally:
        db.close()
    assert [b["design_id"] for b in sweep_best_designs(sweep)] == [1]
    assert directory_state(sweep) == before


def test_optimize_from_reads_a_sweep_in_a_directory_it_cannot_write(tmp_path):
    sweep = finished_sweep(tmp_path / "sweep")
    before = directory_state(sweep)
    with unwritable(sweep):
        best = sweep_best_designs(sweep)
    assert [b["design_id"] for b in best] == [1]
    assert directory_state(sweep) == before


def test_report_of_a_directory_it_cannot_write_is_one_line(tmp_path, capsys):
    sweep = finished_sweep(tmp_path / "sweep")
    before = directory_state(sweep)
    with unwritable(sweep):
        status = run(["report", str(sweep)])
    err = capsys.readouterr().err
    assert status == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    assert f"'{sweep}' is not writable" in lines[0]
    assert directory_state(sweep) == before
