"""A database as a full disk leaves it in the middle of a checkpoint, for the tests of the
databases that must resume from it (issue 37, item 4)."""

from __future__ import annotations

import shutil
import sqlite3
from pathlib import Path


def wal_copy(path: Path, directory: Path, rows: int) -> tuple[Path, list[tuple]]:
    """A copy in ``directory`` of the database at ``path`` (made, WAL mode, with a ``meta``
    table of two text columns) after ``rows`` rows were committed to its ``-wal`` and the
    disk filled mid-checkpoint: the main file's first page (its header counting every page)
    written, the pages after it not. Returns the copy's path and the rows of ``meta`` that
    SQLite reads from the whole database."""
    db = sqlite3.connect(path)
    db.execute("PRAGMA wal_autocheckpoint=0")
    with db:
        db.executemany(
            "INSERT INTO meta VALUES (?, ?)", [(f"k{i}", "x" * 3000) for i in range(rows)]
        )
    directory.mkdir()
    target = directory / path.name
    for suffix in ("", "-wal"):
        shutil.copyfile(str(path) + suffix, str(target) + suffix)
    db.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    expected = db.execute("SELECT key, value FROM meta ORDER BY key").fetchall()
    page = db.execute("PRAGMA page_size").fetchone()[0]
    db.close()
    target.write_bytes(path.read_bytes()[:page] + target.read_bytes()[page:])
    assert path.stat().st_size > target.stat().st_size  # the header counts pages not there
    return target, expected
