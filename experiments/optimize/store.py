"""The evaluations of an optimisation: one SQLite file, written by one process.

Tables (one row per ...):

- ``meta`` (key, value): ``config`` (the config as JSON; a device family's optimisation adds
  ``family_record``, :func:`experiments.family_config.family_record`, whose parameters say
  how many values a key holds), ``objective_key`` (the digest of what decides a value: a
  database belongs to one), ``created``.
- ``evaluations``: a design evaluated: ``key`` (its 12 values, or a family's, exactly, as
  JSON), the robust
  objective ``value`` (:mod:`experiments.optimize.objective`), ``both`` (trials that succeed
  from both entries) of ``trials``, successes per entry (a family's two entries in its file's
  order), ``mean_g`` (mean Eq. 10 G), ``reason``
  (why degenerate), every trial as JSON, and ``wall_time_s`` (worker time).
- ``calls``: the n-th evaluation a method run asked for (``run`` is e.g.
  ``differential-evolution/seed0``), pointing at its design's evaluation. A design asked again
  (by this run or another) is not evaluated again: the value is a function of the design.
- ``verdicts``: a design's fixed-sample verdict on fresh draws (``label``: ``optimum``,
  ``table3``, the baseline's label, ``candidate0``, ...): its seed and trials as JSON.
- ``verdict_times`` (added later): the wall time (s) of a verdict, by design key, seed and
  number of trials (what a report states as the comparison's cost).
- ``margins`` (added later): the tolerance margins of a design
  (:meth:`experiments.margins.run.MarginsReport.to_dict`), by design key and the digest of
  the margins' settings (draws, target, seed, the scene's options).

An evaluation is stored in one transaction as it finishes: a run killed at any moment loses
at most the evaluations in flight, and one restarted repeats none that were stored.
"""

from __future__ import annotations

import json
import math
import sqlite3
import time
from pathlib import Path
from typing import Any

from experiments.database_file import check_file, complete_checkpoint, open_read_only
from feeders.design import PARAMETER_NAMES

_SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS evaluations (
    key TEXT PRIMARY KEY,
    value REAL NOT NULL,
    both_entries INTEGER NOT NULL,
    trials INTEGER NOT NULL,
    heavy_leading INTEGER NOT NULL,
    heavy_trailing INTEGER NOT NULL,
    mean_g REAL,
    reason TEXT,
    trial_data TEXT NOT NULL,
    wall_time_s REAL NOT NULL
);
CREATE TABLE IF NOT EXISTS calls (
    run TEXT NOT NULL,
    n INTEGER NOT NULL,
    key TEXT NOT NULL REFERENCES evaluations(key),
    PRIMARY KEY (run, n)
);
CREATE TABLE IF NOT EXISTS verdicts (
    label TEXT PRIMARY KEY,
    key TEXT NOT NULL,
    seed INTEGER NOT NULL,
    trial_data TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS verdict_times (
    key TEXT NOT NULL,
    seed INTEGER NOT NULL,
    trials INTEGER NOT NULL,
    wall_time_s REAL NOT NULL,
    PRIMARY KEY (key, seed, trials)
);
CREATE TABLE IF NOT EXISTS margins (
    key TEXT NOT NULL,
    settings TEXT NOT NULL,
    report TEXT NOT NULL,
    PRIMARY KEY (key, settings)
);
"""
# tables an older database lacks: created when it is opened for writing, absent read-only
ADDED_LATER = ("verdict_times", "margins")


class StoreMismatch(ValueError):
    """The database holds the evaluations of another objective, or another run's calls."""


class StoreDamaged(ValueError):
    """The file is not a sound optimisation database."""


def _damaged(path: Path, problem: str) -> StoreDamaged:
    return StoreDamaged(
        f"optimisation database '{path}' {problem}; nothing was written to it: move it aside "
        "(or delete it) and run the same command again to redo the optimisation"
    )


def design_key(values: list[float]) -> str:
    """The key of a design: its values as JSON (Python's float repr round-trips exactly)."""
    return json.dumps([float(v) for v in values])


def design_of_key(key: str) -> list[float]:
    return [float(v) for v in json.loads(key)]


def _parameter_count(db: sqlite3.Connection) -> int:
    """How many values a design key holds: the family's parameters when the stored config
    names a family (its ``family_record``), else the 12 of the feeder."""
    row = db.execute("SELECT value FROM meta WHERE key = 'config'").fetchone()
    try:
        record = json.loads(row[0]).get("family_record") if row is not None else None
        return len(record["parameters"]) if record else len(PARAMETER_NAMES)
    except (ValueError, TypeError, KeyError, AttributeError):
        return len(PARAMETER_NAMES)


def _content_problem(db: sqlite3.Connection) -> str | None:
    """Rows this module never writes: a key that is not the design's finite numbers (12, or
    the stored family's count), a value that is not finite and non-negative, counts out of
    order, trial data that is not JSON."""
    count = _parameter_count(db)
    for (key,) in db.execute("SELECT key FROM evaluations"):
        try:
            values = json.loads(key)
            ok = len(values) == count and all(
                isinstance(v, float) and math.isfinite(v) for v in values
            )
        except (ValueError, TypeError):
            ok = False
        if not ok:
            return f"evaluations: a key is not a design's {count} values"
    bad = db.execute(
        """SELECT 1 FROM evaluations WHERE typeof(value) != 'real' OR NOT value >= 0
        OR typeof(trials) != 'integer' OR trials < 1
        OR both_entries NOT BETWEEN 0 AND min(heavy_leading, heavy_trailing)
        OR heavy_leading NOT BETWEEN 0 AND trials OR heavy_trailing NOT BETWEEN 0 AND trials
        OR NOT wall_time_s >= 0 LIMIT 1"""
    ).fetchone()
    if bad:
        return "evaluations: a row holds a value this program never writes"
    if db.execute("SELECT 1 FROM calls WHERE typeof(n) != 'integer' OR n < 0 LIMIT 1").fetchone():
        return "calls: a row holds a value this program never writes"
    try:
        for (data,) in db.execute(
            "SELECT trial_data FROM evaluations UNION ALL SELECT trial_data FROM verdicts"
        ):
            json.loads(data)
        if "margins" in _tables(db):
            for (data,) in db.execute("SELECT report FROM margins"):
                json.loads(data)
    except (ValueError, sqlite3.OperationalError) as exc:
        return f"trial data cannot be read ({type(exc).__name__})"
    return None


def _tables(db: sqlite3.Connection) -> set[str]:
    return {r[0] for r in db.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}


def check_store(path: str | Path) -> bool:
    """Refuse (:class:`StoreDamaged`) a file that is not a sound optimisation database
    (:func:`experiments.database_file.check_file`). Returns whether it holds our tables."""
    return check_file(
        path,
        _SCHEMA,
        _damaged,
        "optimisation database",
        added_later=ADDED_LATER,
        content_problem=_content_problem,
        trust_wal=True,  # after a full disk its rows may sit in its WAL: read through it
    )


def connect(path: str | Path, readonly: bool = False) -> sqlite3.Connection:
    """Open an optimisation database (created if missing, unless ``readonly``), after
    :func:`check_store` has found it sound; ``readonly`` writes and creates nothing
    (:func:`experiments.database_file.open_read_only`)."""
    path = Path(path)
    ours = check_store(path)
    if readonly:
        if not ours:
            raise _damaged(path, "holds no evaluations")
        db = open_read_only(path)
    else:
        path.parent.mkdir(parents=True, exist_ok=True)
        db = sqlite3.connect(path, timeout=30.0)
        db.execute("PRAGMA journal_mode=WAL")
        db.execute("PRAGMA synchronous=NORMAL")
        db.executescript(_SCHEMA)
        complete_checkpoint(db, path)
    db.row_factory = sqlite3.Row
    return db


def claim(db: sqlite3.Connection, config: dict[str, Any], objective_key: str) -> None:
    """Tie the database to an objective; one of another raises :class:`StoreMismatch`."""
    row = db.execute("SELECT value FROM meta WHERE key = 'objective_key'").fetchone()
    if row is not None and row["value"] != objective_key:
        raise StoreMismatch(
            "this directory holds an optimisation of another objective (key "
            f"{row['value']}, this config's is {objective_key}); choose another --out "
            "or remove it"
        )
    with db:
        db.execute("INSERT OR IGNORE INTO meta VALUES ('objective_key', ?)", (objective_key,))
        db.execute("INSERT OR IGNORE INTO meta VALUES ('created', ?)", (time.ctime(),))
        db.execute("INSERT OR REPLACE INTO meta VALUES ('config', ?)", (json.dumps(config),))


def evaluations(db: sqlite3.Connection) -> dict[str, dict[str, Any]]:
    """key -> the stored evaluation (:func:`experiments.optimize.objective.robust_value`'s
    fields, with ``trial_data`` and ``wall_time_s``)."""
    out = {}
    for row in db.execute("SELECT * FROM evaluations"):
        out[row["key"]] = {
            "value": row["value"],
            "both": row["both_entries"],
            "trials": row["trials"],
            "successes": [row["heavy_leading"], row["heavy_trailing"]],
            "mean_g": row["mean_g"],
            "reason": row["reason"],
            "trial_data": json.loads(row["trial_data"]),
            "wall_time_s": row["wall_time_s"],
        }
    return out


def calls(db: sqlite3.Connection, run: str | None = None) -> dict[str, list[str]]:
    """run -> the keys it asked for, in order (only ``run``'s when given)."""
    out: dict[str, list[str]] = {}
    query = "SELECT run, n, key FROM calls"
    params: tuple = ()
    if run is not None:
        query += " WHERE run = ?"
        params = (run,)
    for row in db.execute(query + " ORDER BY run, n", params):
        out.setdefault(row["run"], []).append(row["key"])
    return out


def record(db: sqlite3.Connection, key: str, result: dict[str, Any]) -> None:
    """Store one design's evaluation (once: a key already stored is kept)."""
    with db:
        db.execute(
            "INSERT OR IGNORE INTO evaluations VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
            (
                key,
                float(result["value"]),
                int(result["both"]),
                int(result["trials"]),
                int(result["successes"][0]),
                int(result["successes"][1]),
                result["mean_g"],
                result["reason"],
                json.dumps(result["trial_data"]),
                float(result["wall_time_s"]),
            ),
        )


def record_call(db: sqlite3.Connection, run: str, n: int, key: str) -> None:
    """Store that ``run`` asked for ``key`` as its ``n``-th evaluation."""
    with db:
        db.execute("INSERT OR IGNORE INTO calls VALUES (?, ?, ?)", (run, n, key))


def record_verdict(
    db: sqlite3.Connection, label: str, key: str, seed: int, trial_data: list[dict]
) -> None:
    """Store the fixed-sample verdict of design ``key`` under ``label``."""
    with db:
        db.execute(
            "INSERT OR REPLACE INTO verdicts VALUES (?, ?, ?, ?)",
            (label, key, seed, json.dumps(trial_data)),
        )


def stored_verdict(db: sqlite3.Connection, label: str) -> dict[str, Any] | None:
    """The stored verdict under ``label``: ``key``, ``seed``, ``trial_data``; None if none."""
    row = db.execute("SELECT * FROM verdicts WHERE label = ?", (label,)).fetchone()
    if row is None:
        return None
    return {"key": row["key"], "seed": row["seed"], "trial_data": json.loads(row["trial_data"])}


def find_verdict(db: sqlite3.Connection, key: str, seed: int, trials: int) -> dict[str, Any] | None:
    """A stored verdict of design ``key`` on ``trials`` trials of ``seed``, under any label
    (its trials are a function of the design and the draws): ``label``, ``key``, ``seed``,
    ``trial_data``; None if none."""
    for row in db.execute(
        "SELECT * FROM verdicts WHERE key = ? AND seed = ? ORDER BY label", (key, seed)
    ):
        data = json.loads(row["trial_data"])
        if len(data) == trials:
            return {"label": row["label"], "key": key, "seed": seed, "trial_data": data}
    return None


def record_verdict_time(
    db: sqlite3.Connection, key: str, seed: int, trials: int, wall_time_s: float
) -> None:
    """Store the wall time (s) the verdict of ``key`` on ``trials`` trials of ``seed`` took."""
    with db:
        db.execute(
            "INSERT OR REPLACE INTO verdict_times VALUES (?, ?, ?, ?)",
            (key, seed, trials, float(wall_time_s)),
        )


def verdict_time(db: sqlite3.Connection, key: str, seed: int, trials: int) -> float | None:
    """The stored wall time (s) of that verdict; None when not recorded (an older run)."""
    try:
        row = db.execute(
            "SELECT wall_time_s FROM verdict_times WHERE key = ? AND seed = ? AND trials = ?",
            (key, seed, trials),
        ).fetchone()
    except sqlite3.OperationalError:  # an older database, opened read-only
        return None
    return None if row is None else float(row["wall_time_s"])


def record_margins(db: sqlite3.Connection, key: str, settings: str, report: dict[str, Any]) -> None:
    """Store the margins ``report`` of design ``key`` measured with ``settings`` (a digest)."""
    with db:
        db.execute(
            "INSERT OR REPLACE INTO margins VALUES (?, ?, ?)", (key, settings, json.dumps(report))
        )


def stored_margins(db: sqlite3.Connection, key: str, settings: str) -> dict[str, Any] | None:
    """The stored margins of design ``key`` with ``settings``; None if not measured."""
    try:
        row = db.execute(
            "SELECT report FROM margins WHERE key = ? AND settings = ?", (key, settings)
        ).fetchone()
    except sqlite3.OperationalError:  # an older database, opened read-only
        return None
    return None if row is None else json.loads(row["report"])


def record_meta(db: sqlite3.Connection, key: str, value: Any) -> None:
    """Store ``value`` (plain data, as JSON) in the meta table under ``key``."""
    with db:
        db.execute("INSERT OR REPLACE INTO meta VALUES (?, ?)", (key, json.dumps(value)))


def stored_meta(db: sqlite3.Connection, key: str) -> Any:
    """The plain data stored under ``key`` by :func:`record_meta`; None if none."""
    row = db.execute("SELECT value FROM meta WHERE key = ?", (key,)).fetchone()
    return None if row is None else json.loads(row[0])
