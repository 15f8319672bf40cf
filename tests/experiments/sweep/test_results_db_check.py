"""What :func:`check_database` lets through: the states a sweep killed at any moment leaves
(issue 16's refusal of damaged databases must not cost the kill -9 resilience). The damaged
files it refuses are in ``tests/experiments/cli/test_bad_input.py`` and the corpus."""

from __future__ import annotations

from pathlib import Path

import pytest

from experiments.sweep import results_db


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
