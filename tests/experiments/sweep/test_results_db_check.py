"""What :func:`check_database` lets through: the states a sweep killed at any moment leaves
(issue 16's refusal of damaged databases must not cost the kill -9 resilience). The damaged
files it refuses are in ``tests/experiments/cli/test_bad_input.py`` and the corpus."""

from __future__ import annotations

import os
import sqlite3
from pathlib import Path

import pytest
from file_state import directory_state
from sweep_fixtures import fake_result, tiny_config

from experiments.cli import run
from experiments.sweep import results_db
from feeders.halton import halton_points


def test_a_missing_or_empty_file_is_a_new_database(tmp_path: Path) -> None:
    assert results_db.check_database(tmp_path / "missing.sqlite") is False
    empty = tmp_path / "empty.sqlite"
    empty.touch()
    assert results_db.check_database(empty) is False
    with pytest.raises(results_db.ResultsDamaged, match="holds no partfeeder results"):
        results_db.connect(empty, readonly=True)


def test_a_database_killed_before_it_was_claimed_is_resumed(tmp_path: Path) -> None:
    """connect() creates the tables; a run killed before claim() leaves no config in meta."""
    path = tmp_path / "results.sqlite"
    results_db.connect(path).close()
    assert results_db.check_database(path) is True
    db = results_db.connect(path)
    results_db.claim(db, {"designs": {"count": 1, "seed": 1}, "ladder": []}, "k")
    db.close()
    assert results_db.check_database(path) is True


# -- a refused database is left exactly as it was (issue 23) ------------------------------
# The check once opened the file with SQLite's read-only mode, which for a WAL database still
# creates ``-wal`` and ``-shm`` files beside it (and leaves them): a refused database's
# directory changed. Compared here by name, bytes and modification time of every file.

MARKER = "marker-of-the-stored-config"
LOG_MARKER = "marker-inside-the-stored-log"
LOG = f"OMPL version 2.0.1\nExperiment {LOG_MARKER}\n1 planners\n.\n"


def overwrite(path: Path, marker: str, garbage: bytes) -> None:
    """Garbage inside a record: the bytes of ``marker`` in the file overwritten in place."""
    data = path.read_bytes()
    where = data.index(marker.encode())
    path.write_bytes(data[:where] + garbage + data[where + len(garbage) :])


def sweep_database(directory: Path) -> Path:
    """A sweep's database as a finished sweep leaves it (WAL mode, no ``-wal`` beside it):
    three designs of the tiny config, design 1's geometric evaluation with an OMPL log."""
    directory.mkdir()
    path = directory / "results.sqlite"
    config = tiny_config(name=MARKER, designs={"count": 3, "seed": 1})
    db = results_db.connect(path)
    try:
        results_db.claim(db, config.to_dict(), config.results_key())
        points = halton_points(3, 1)
        results_db.add_designs(db, ((i, False, list(points[i])) for i in range(3)))
        result = fake_result(1, "geometric", "feasible", 0.1)
        result["logs"] = {"heavy_leading": LOG}
        assert results_db.record(db, result, 0, 1)
    finally:
        db.close()
    assert sorted(os.listdir(directory)) == ["results.sqlite"]
    return path


def test_a_sound_finished_sweep_is_read_without_a_file_created_or_changed(tmp_path: Path):
    """The control: the same reads of the undamaged database pass and touch nothing."""
    path = sweep_database(tmp_path / "sweep")
    before = directory_state(path.parent)
    assert results_db.check_database(path) is True
    db = results_db.connect(path, readonly=True)
    assert db.execute("SELECT count(*) FROM designs").fetchone()[0] == 3
    db.close()
    assert directory_state(path.parent) == before


@pytest.mark.parametrize(
    ("damage", "says"),
    [
        ("config-bytes", "meta: the stored config cannot be read"),
        ("holdout-value", "designs: a row holds a value"),
        ("log-bytes", "ompl_logs: the OMPL log of design 1, level geometric, heavy_leading"),
    ],
)
@pytest.mark.parametrize("opening", ["check", "write", "read"])
def test_a_refused_results_database_is_left_byte_for_byte(
    tmp_path: Path, damage: str, says: str, opening: str
) -> None:
    path = sweep_database(tmp_path / "sweep")
    if damage == "config-bytes":
        overwrite(path, MARKER, b"\xff\xfe\x00\x80")
    elif damage == "log-bytes":
        overwrite(path, LOG_MARKER, b"\xc3\x28\xa0\xa1\xe2\x28\xa1")
    else:
        db = sqlite3.connect(path)
        db.execute("UPDATE designs SET holdout = 7 WHERE design_id = 2")
        db.commit()
        db.close()
    assert sorted(os.listdir(path.parent)) == ["results.sqlite"]
    before = directory_state(path.parent)
    with pytest.raises(results_db.ResultsDamaged, match=says) as refused:
        if opening == "check":
            results_db.check_database(path)
        else:
            results_db.connect(path, readonly=opening == "read")
    assert "nothing was written to it" in str(refused.value)
    assert directory_state(path.parent) == before


def test_report_refuses_a_sweep_whose_stored_ompl_log_is_not_text(tmp_path: Path, capsys):
    """``report`` read the logs nowhere and exited 0 (issue 23); Planner Arena's database is
    made from them, so a log with garbage inside is refused like any other row this program
    cannot have written: one line naming the database and the log's design, level and entry
    orientation, exit 2, and the directory as it was (no report, no summary)."""
    path = sweep_database(tmp_path / "sweep")
    overwrite(path, LOG_MARKER, b"\xc3\x28\xa0\xa1\xe2\x28\xa1")
    before = directory_state(path.parent)
    assert run(["report", str(path.parent)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err, err
    assert f"results database '{path}'" in err
    assert "design 1, level geometric, heavy_leading" in err
    assert directory_state(path.parent) == before
