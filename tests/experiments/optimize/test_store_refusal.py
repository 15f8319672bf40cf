"""A refused optimisation database is left exactly as it was (issue 23): its check once
opened the WAL file with SQLite's read-only mode, which still creates ``-wal`` and ``-shm``
beside it. Compared by name, bytes and modification time of every file in its directory."""

from __future__ import annotations

import os
import sqlite3
from pathlib import Path

import pytest
from file_state import directory_state

from experiments.optimize import store

KEY_VALUES = [0.25 * i for i in range(12)]
TRIAL_MARKER = "marker-inside-the-trial-data"


def evaluations_database(directory: Path) -> Path:
    """An optimisation's database as a finished run leaves it (WAL mode, no ``-wal``)."""
    directory.mkdir()
    path = directory / "evaluations.sqlite"
    db = store.connect(path)
    try:
        store.claim(db, {"name": "refusal"}, "objective-key")
        key = store.design_key(KEY_VALUES)
        store.record(
            db,
            key,
            {
                "value": 0.5,
                "both": 1,
                "trials": 2,
                "successes": [1, 2],
                "mean_g": 4.0,
                "reason": None,
                "trial_data": [{"note": TRIAL_MARKER}],
                "wall_time_s": 0.1,
            },
        )
        store.record_call(db, "powell/seed0", 0, key)
    finally:
        db.close()
    assert sorted(os.listdir(directory)) == ["evaluations.sqlite"]
    return path


def test_a_sound_finished_database_is_read_without_a_file_created_or_changed(tmp_path):
    """The control: the same reads of the undamaged database pass and touch nothing."""
    path = evaluations_database(tmp_path / "opt")
    before = directory_state(path.parent)
    assert store.check_store(path) is True
    db = store.connect(path, readonly=True)
    assert list(store.evaluations(db)) == [store.design_key(KEY_VALUES)]
    db.close()
    assert directory_state(path.parent) == before


@pytest.mark.parametrize(
    ("damage", "says"),
    [
        ("trial-bytes", "trial data cannot be read"),
        ("negative-value", "evaluations: a row holds a value"),
    ],
)
@pytest.mark.parametrize("opening", ["check", "write", "read"])
def test_a_refused_optimisation_database_is_left_byte_for_byte(
    tmp_path: Path, damage: str, says: str, opening: str
) -> None:
    path = evaluations_database(tmp_path / "opt")
    if damage == "trial-bytes":  # garbage inside a record, as a damaged disk leaves it
        data = path.read_bytes()
        where = data.index(TRIAL_MARKER.encode())
        path.write_bytes(data[:where] + b"\xff\xfe\x80\x81" + data[where + 4 :])
    else:
        db = sqlite3.connect(path)
        db.execute("UPDATE evaluations SET value = -1.0")
        db.commit()
        db.close()
    assert sorted(os.listdir(path.parent)) == ["evaluations.sqlite"]
    before = directory_state(path.parent)
    with pytest.raises(store.StoreDamaged, match=says) as refused:
        if opening == "check":
            store.check_store(path)
        else:
            store.connect(path, readonly=opening == "read")
    assert "nothing was written to it" in str(refused.value)
    assert directory_state(path.parent) == before
