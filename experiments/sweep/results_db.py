"""The results database of a sweep: one SQLite file, written by one process, read by anyone.

Tables (one row per ...):

- ``meta`` (key, value): ``config`` (the config as JSON), ``results_key`` (its digest: a
  database belongs to one config), ``created``.
- ``designs``: a Halton design: ``design_id`` (index in the sequence), ``holdout`` (1 if it
  climbs every rung to measure the pruning), the 12 parameters as columns (Table 2's names).
- ``evaluations``: a (design, level): ``rung`` (position in the ladder), ``status``
  (feasible / infeasible / degenerate), ``reason`` (why degenerate), ``heavy_leading`` and
  ``heavy_trailing`` (1 solved, 0 not, NULL not run: the second entry is skipped once the
  first fails), ``wall_time_s`` (the whole evaluation, in its worker), ``worker``, ``attempts``.
- ``runs``: one planner run of an evaluation: orientation, planner, run, seed, solved (goal
  reached exactly), approximate, time_s, tree_size, tree_edges, propagations,
  validity_checks, exit_time_s (the solution's duration, Eq. 10; NULL unless solved).
- ``ompl_logs``: OMPL's benchmark log of a (design, level, orientation).
- ``quarantine``: a (design, level) whose worker died ``attempts`` times, and why.

Each evaluation is stored with its runs and logs in one transaction, keyed by (design, level):
a sweep killed at any moment loses at most the evaluations in flight, and one restarted never
stores an evaluation twice. WAL mode lets a report read while the sweep writes.
"""

from __future__ import annotations

import json
import sqlite3
import stat
import time
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from feeders.design import PARAMETER_NAMES

STATUSES = ("feasible", "infeasible", "degenerate")
RUN_COLUMNS = (
    "planner",
    "run",
    "seed",
    "solved",
    "approximate",
    "time_s",
    "tree_size",
    "tree_edges",
    "propagations",
    "validity_checks",
    "exit_time_s",
)

_SCHEMA = f"""
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS designs (
    design_id INTEGER PRIMARY KEY,
    holdout INTEGER NOT NULL,
    {", ".join(f"{name} REAL NOT NULL" for name in PARAMETER_NAMES)}
);
CREATE TABLE IF NOT EXISTS evaluations (
    design_id INTEGER NOT NULL REFERENCES designs(design_id),
    level TEXT NOT NULL,
    rung INTEGER NOT NULL,
    status TEXT NOT NULL CHECK (status IN ('feasible', 'infeasible', 'degenerate')),
    reason TEXT,
    heavy_leading INTEGER,
    heavy_trailing INTEGER,
    wall_time_s REAL NOT NULL,
    worker TEXT,
    attempts INTEGER NOT NULL,
    PRIMARY KEY (design_id, level)
);
CREATE TABLE IF NOT EXISTS runs (
    design_id INTEGER NOT NULL,
    level TEXT NOT NULL,
    orientation TEXT NOT NULL,
    planner TEXT NOT NULL,
    run INTEGER NOT NULL,
    seed INTEGER NOT NULL,
    solved INTEGER NOT NULL,
    approximate INTEGER NOT NULL,
    time_s REAL,
    tree_size INTEGER,
    tree_edges INTEGER,
    propagations INTEGER,
    validity_checks INTEGER,
    exit_time_s REAL,
    PRIMARY KEY (design_id, level, orientation, planner, run)
);
CREATE TABLE IF NOT EXISTS ompl_logs (
    design_id INTEGER NOT NULL,
    level TEXT NOT NULL,
    orientation TEXT NOT NULL,
    log TEXT NOT NULL,
    PRIMARY KEY (design_id, level, orientation)
);
CREATE TABLE IF NOT EXISTS quarantine (
    design_id INTEGER NOT NULL,
    level TEXT NOT NULL,
    attempts INTEGER NOT NULL,
    reason TEXT NOT NULL,
    PRIMARY KEY (design_id, level)
);
"""


class ResultsMismatch(ValueError):
    """The database holds the results of another config."""


class ResultsDamaged(ValueError):
    """The file is not a sound results database: damaged, truncated or of another schema."""


SQLITE_HEADER = b"SQLite format 3\x00"
FULL_CHECK_BYTES = 256 << 20  # ``integrity_check`` up to this size, ``quick_check`` above


def _damaged(path: Path, problem: str) -> ResultsDamaged:
    return ResultsDamaged(
        f"results database '{path}' {problem}; nothing was written to it: move it aside "
        "(or delete it) and run the same command again to redo the sweep"
    )


def _expected_columns() -> dict[str, list[str]]:
    """Table -> column names of ``_SCHEMA``, from an empty in-memory database built by it."""
    db = sqlite3.connect(":memory:")
    try:
        db.executescript(_SCHEMA)
        return _columns(db)
    finally:
        db.close()


def _columns(db: sqlite3.Connection) -> dict[str, list[str]]:
    tables = [
        r[0]
        for r in db.execute(
            "SELECT name FROM sqlite_master WHERE type = 'table' AND name NOT LIKE 'sqlite_%'"
        )
    ]
    return {t: [r[1] for r in db.execute(f'PRAGMA table_info("{t}")')] for t in tables}


def check_database(path: str | Path) -> bool:
    """Refuse (:class:`ResultsDamaged`) a file at ``path`` that is not a sound results
    database, reading only: a header that is not SQLite's, a file that SQLite finds damaged
    (``PRAGMA integrity_check``, or ``quick_check`` above ``FULL_CHECK_BYTES``: it skips
    matching indexes to tables, and is linear in the file), or tables other than ours. A
    missing or empty file passes (it becomes a new database). Damage that leaves every page
    well-formed (a changed digit inside a stored number) is not detectable: SQLite keeps no
    checksums. Returns whether it holds our tables (False: missing, empty or new)."""
    path = Path(path)
    try:
        info = path.stat()
    except FileNotFoundError:
        return False
    if not stat.S_ISREG(info.st_mode):  # a FIFO would block the read below
        raise _damaged(path, "is not a regular file")
    size = info.st_size
    if size == 0:
        return False
    with path.open("rb") as handle:
        header = handle.read(len(SQLITE_HEADER))
    if header != SQLITE_HEADER:
        raise _damaged(path, "is not an SQLite database (its header is wrong)")
    check = "integrity_check" if size <= FULL_CHECK_BYTES else "quick_check"
    columns: dict[str, list[str]] = {}
    try:
        db = sqlite3.connect(f"file:{path}?mode=ro", uri=True, timeout=30.0)
        try:
            rows = [r[0] for r in db.execute(f"PRAGMA {check}(1)")]
            if rows == ["ok"]:
                columns = _columns(db)
        finally:
            db.close()
    except sqlite3.DatabaseError as exc:
        raise _damaged(path, f"cannot be read ({exc})") from None
    if rows != ["ok"]:
        raise _damaged(path, f"is damaged (SQLite's {check}: {rows[0] if rows else 'no answer'})")
    if columns and columns != _expected_columns():
        raise _damaged(path, "has tables that are not a partfeeder results database's")
    return bool(columns)


def connect(path: str | Path, readonly: bool = False) -> sqlite3.Connection:
    """Open a results database (created if missing, unless ``readonly``), after
    :func:`check_database` has found it sound."""
    path = Path(path)
    ours = check_database(path)
    if readonly:
        if not path.exists():
            raise FileNotFoundError(f"no results database at '{path}'")
        if not ours:
            raise _damaged(path, "holds no partfeeder results (it is empty)")
        db = sqlite3.connect(f"file:{path}?mode=ro", uri=True, timeout=30.0)
    else:
        path.parent.mkdir(parents=True, exist_ok=True)
        db = sqlite3.connect(path, timeout=30.0)
        db.execute("PRAGMA journal_mode=WAL")
        db.execute("PRAGMA synchronous=NORMAL")  # durable against a killed process
        db.executescript(_SCHEMA)
    db.row_factory = sqlite3.Row
    return db


def claim(db: sqlite3.Connection, config: dict[str, Any], results_key: str) -> None:
    """Tie the database to a config; a database of another config raises
    :class:`ResultsMismatch` (its results are not mixed with this config's)."""
    row = db.execute("SELECT value FROM meta WHERE key = 'results_key'").fetchone()
    if row is not None and row["value"] != results_key:
        raise ResultsMismatch(
            "this directory holds a sweep of another config (results key "
            f"{row['value']}, this config's is {results_key}); choose another --out "
            "or remove it"
        )
    with db:
        db.execute("INSERT OR IGNORE INTO meta VALUES ('results_key', ?)", (results_key,))
        db.execute("INSERT OR IGNORE INTO meta VALUES ('created', ?)", (time.ctime(),))
        db.execute("INSERT OR REPLACE INTO meta VALUES ('config', ?)", (json.dumps(config),))


def add_designs(db: sqlite3.Connection, rows: Iterable[tuple[int, bool, list[float]]]) -> None:
    """Store designs (design_id, holdout, 12 values); ones already stored are kept."""
    marks = ", ".join("?" * (2 + len(PARAMETER_NAMES)))
    with db:
        db.executemany(
            f"INSERT OR IGNORE INTO designs VALUES ({marks})",
            [(i, int(h), *map(float, values)) for i, h, values in rows],
        )


def finished(db: sqlite3.Connection) -> dict[tuple[int, str], str]:
    """(design_id, level) -> status of every evaluation stored, 'quarantined' included."""
    done = {
        (r["design_id"], r["level"]): r["status"]
        for r in db.execute("SELECT design_id, level, status FROM evaluations")
    }
    for r in db.execute("SELECT design_id, level FROM quarantine"):
        done[(r["design_id"], r["level"])] = "quarantined"
    return done


def record(db: sqlite3.Connection, result: dict[str, Any], rung: int, attempts: int) -> bool:
    """Store one evaluation with its runs and logs, atomically. Returns False (and stores
    nothing) if that (design, level) is already stored."""
    key = (int(result["design_id"]), str(result["level"]))
    orientations = result["orientations"]
    with db:
        cursor = db.execute(
            "INSERT OR IGNORE INTO evaluations VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
            (
                *key,
                rung,
                result["status"],
                result.get("reason"),
                _flag(orientations.get("heavy_leading")),
                _flag(orientations.get("heavy_trailing")),
                float(result["wall_time_s"]),
                result.get("worker"),
                attempts,
            ),
        )
        if cursor.rowcount == 0:
            return False
        db.executemany(
            f"INSERT INTO runs VALUES (?, ?, ?, {', '.join('?' * len(RUN_COLUMNS))})",
            [
                (*key, run["orientation"], *(_cell(run[c]) for c in RUN_COLUMNS))
                for run in result["runs"]
            ],
        )
        db.executemany(
            "INSERT INTO ompl_logs VALUES (?, ?, ?, ?)",
            [(*key, orientation, log) for orientation, log in result["logs"].items()],
        )
    return True


def quarantine(
    db: sqlite3.Connection, design_id: int, level: str, attempts: int, reason: str
) -> None:
    with db:
        db.execute(
            "INSERT OR IGNORE INTO quarantine VALUES (?, ?, ?, ?)",
            (design_id, level, attempts, reason),
        )


def _flag(value: bool | None) -> int | None:
    return None if value is None else int(bool(value))


def _cell(value: Any) -> Any:
    if isinstance(value, bool):
        return int(value)
    if isinstance(value, float) and value != value:  # NaN -> NULL
        return None
    return value
