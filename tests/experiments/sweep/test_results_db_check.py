"""What :func:`check_database` lets through: the states a sweep killed at any moment leaves
(issue 16's refusal of damaged databases must not cost the kill -9 resilience). The damaged
files it refuses are in ``tests/experiments/cli/test_bad_input.py`` and the corpus."""

from __future__ import annotations

import os
import sqlite3
from pathlib import Path

import pytest
from file_state import directory_state
from full_disk import wal_copy
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


FIG1 = Path(__file__).resolve().parents[3] / "feeders" / "families" / "fig1.yaml"


def _family_database(directory: Path, text: str) -> Path:
    """A family sweep's database whose stored family text is ``text``."""
    from experiments.family_config import family_record
    from feeders.device_family import load_family

    family = load_family(FIG1)
    directory.mkdir()
    path = directory / "results.sqlite"
    db = results_db.connect(path, parameters=family.vector_names)
    try:
        config = {"designs": {"count": 1, "seed": 1}, "ladder": []}
        results_db.claim(db, config, "k", family_record(family, text))
    finally:
        db.close()
    return path


@pytest.mark.parametrize(
    "kind",
    ["repeated key", "alias bomb", "deep nesting", "oversized", "another family"],
)
def test_a_database_storing_a_family_text_the_reader_refuses_is_refused(
    tmp_path: Path, kind: str, capsys
) -> None:
    """Issue 37, item 3: the stored text was rebuilt with an unbounded loader (an alias bomb
    took ``report`` to 2.49 GB and a MemoryError). The check reads it with the bounded
    reader, and a text that is not the stored parameters' family is refused too."""
    import time

    text = FIG1.read_text()
    hostile = {
        "repeated key": text + "name: again\n",
        "alias bomb": "a: &a [x, x, x, x, x, x, x, x, x]\n"
        + "".join(
            f"{c}: &{c} [{', '.join(['*' + p] * 9)}]\n" for p, c in zip("ab", "bc", strict=True)
        )
        + "name: *c\n",
        "deep nesting": "parameters: " + "[" * 3000 + "]" * 3000 + "\n",
        "oversized": text + "#" * (2 << 20) + "\n",
        "another family": text.replace("pin_r", "pin_radius"),
    }[kind]
    path = _family_database(tmp_path / "sweep", hostile)
    before = directory_state(path.parent)
    start = time.perf_counter()
    with pytest.raises(results_db.ResultsDamaged, match="meta: the stored family"):
        results_db.check_database(path)
    assert run(["report", str(path.parent)]) == 2
    assert time.perf_counter() - start < 60  # seconds; it was 142 s (generous: loaded machine)
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err, err
    assert f"results database '{path}'" in err and "meta: the stored family" in err
    assert directory_state(path.parent) == before


def test_a_database_whose_rows_sit_in_its_wal_is_resumed_not_called_truncated(
    tmp_path: Path,
) -> None:
    """Issue 37, item 4: after a full disk the check compared the main file's size with its
    header, ignoring the WAL, and told the user to delete a database SQLite could read
    whole. Read through the WAL, it passes; opened for writing it is checkpointed whole."""
    from experiments.database_file import header_problem

    path, expected = wal_copy(sweep_database(tmp_path / "source"), tmp_path / "sweep", 40)
    with path.open("rb") as handle:
        assert "truncated" in (header_problem(handle.read(100), path.stat().st_size) or "")
    assert results_db.check_database(path) is True
    db = results_db.connect(path, readonly=True)
    got = db.execute("SELECT key, value FROM meta ORDER BY key").fetchall()
    assert [tuple(row) for row in got] == expected
    db.close()
    db = results_db.connect(path)  # the resumed run: checkpointed, the file whole again
    db.close()
    with path.open("rb") as handle:
        assert header_problem(handle.read(100), path.stat().st_size) is None
    again = sqlite3.connect(path)
    assert again.execute("SELECT key, value FROM meta ORDER BY key").fetchall() == expected
    assert again.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
    again.close()
