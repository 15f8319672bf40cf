"""The optimisation database: tied to one objective, damaged files refused untouched."""

import pytest
from full_disk import wal_copy

from experiments.optimize import store


def test_a_database_of_another_objective_is_refused(tmp_path):
    db = store.connect(tmp_path / "e.sqlite")
    store.claim(db, {"a": 1}, "key-one")
    with pytest.raises(store.StoreMismatch, match="another objective"):
        store.claim(db, {"a": 2}, "key-two")
    db.close()


def test_evaluations_and_calls_come_back_as_stored(tmp_path):
    db = store.connect(tmp_path / "e.sqlite")
    key = store.design_key([0.1 * i for i in range(12)])
    result = {
        "value": 1.25,
        "both": 3,
        "trials": 4,
        "successes": [4, 3],
        "mean_g": 6.5,
        "reason": None,
        "trial_data": [{"index": 0}],
        "wall_time_s": 0.5,
    }
    store.record(db, key, result)
    store.record_call(db, "powell/seed0", 0, key)
    assert store.evaluations(db)[key] == result
    assert store.calls(db) == {"powell/seed0": [key]}
    assert store.design_of_key(key) == [0.1 * i for i in range(12)]
    db.close()


def test_a_file_that_is_not_ours_is_refused_and_left_alone(tmp_path):
    path = tmp_path / "e.sqlite"
    path.write_bytes(b"not a database at all" * 10)
    before = path.read_bytes()
    with pytest.raises(store.StoreDamaged, match="not an SQLite database"):
        store.connect(path)
    assert path.read_bytes() == before


def test_a_row_this_program_never_writes_is_refused(tmp_path):
    path = tmp_path / "e.sqlite"
    db = store.connect(path)
    db.execute(
        "INSERT INTO evaluations VALUES (?, -1.0, 0, 4, 0, 0, NULL, NULL, '[]', 0.1)",
        (store.design_key([0.0] * 12),),
    )
    db.commit()
    db.close()
    with pytest.raises(store.StoreDamaged, match="never writes"):
        store.connect(path)


def test_a_store_whose_rows_sit_in_its_wal_is_resumed_not_called_truncated(tmp_path):
    """Issue 37, item 4, for optimize: after a full disk the store's rows sit in its WAL;
    the check reads through it, and opening it for writing checkpoints it whole."""
    import sqlite3

    from experiments.database_file import header_problem

    source = tmp_path / "source"
    source.mkdir()
    store.connect(source / "evaluations.sqlite").close()
    path, expected = wal_copy(source / "evaluations.sqlite", tmp_path / "optimize", 40)
    with path.open("rb") as handle:
        assert "truncated" in (header_problem(handle.read(100), path.stat().st_size) or "")
    assert store.check_store(path) is True
    store.connect(path).close()  # the resumed optimisation
    with path.open("rb") as handle:
        assert header_problem(handle.read(100), path.stat().st_size) is None
    again = sqlite3.connect(path)
    got = again.execute("SELECT key, value FROM meta WHERE key LIKE 'k%' ORDER BY key")
    assert got.fetchall() == [row for row in expected if row[0].startswith("k")]
    assert again.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
    again.close()
