"""The results database of a sweep: one SQLite file, written by one process, read by anyone.

Tables (one row per ...):

- ``meta`` (key, value): ``config`` (the config as JSON), ``results_key`` (its digest: a
  database belongs to one config), ``created``.
- ``meta`` of a device family's sweep (issue 24) also holds ``family``: the family as JSON
  (:func:`experiments.family_config.family_record`: name, parameters, box, entries, the file's
  text), so a report rebuilds its devices from the database alone.
- ``designs``: a Halton design: ``design_id`` (index in the sequence), ``holdout`` (1 if it
  climbs every rung to measure the pruning), the 12 parameters as columns (Table 2's names;
  a family's sweep: the family's parameter names, in its order).
- ``evaluations``: a (design, level): ``rung`` (position in the ladder), ``status``
  (feasible / infeasible / unknown / degenerate: ``unknown`` is a planning level's "not found
  within budget", which proves nothing; a database written before it existed stored that as
  ``infeasible``, read as ``unknown`` by :func:`status_of`), ``reason`` (why degenerate,
  unknown or undecided), ``heavy_leading`` and ``heavy_trailing`` (1 solved, 0 not, NULL
  not run: the second entry is skipped once the first fails; a family's sweep: its first
  and second entry, named in ``meta``'s family), ``wall_time_s`` (the whole evaluation, in
  its worker), ``worker``, ``attempts``.
- ``runs``: one planner run of an evaluation: orientation, planner, run, seed, solved (goal
  reached exactly), approximate, time_s, tree_size, tree_edges, propagations,
  validity_checks, exit_time_s (the solution's duration, Eq. 10; NULL unless solved).
- ``ompl_logs``: OMPL's benchmark log of a (design, level, orientation).
- ``quarantine``: a (design, level) whose worker died ``attempts`` times, and why.
- ``verdicts``: a design's passive verdict (the ``passive`` rung): ``decision`` (works /
  fails / undecided), ``target``, ``trials``, successes per entry and of both, the mean exit
  time of each entry's successful drops (a family's: its first and second entry), the
  verdict's ``seed`` and the whole verdict as JSON
  (``experiments.drop.verdict.Verdict.to_dict``: intervals, transition matrix).

Each evaluation is stored with its runs and logs in one transaction, keyed by (design, level):
a sweep killed at any moment loses at most the evaluations in flight, and one restarted never
stores an evaluation twice. WAL mode lets a report read while the sweep writes.
"""

from __future__ import annotations

import json
import sqlite3
import stat
import time
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from experiments.database_file import (
    check_file,
    complete_checkpoint,
    header_problem,
    open_read_only,
    size_problem_in_wal,
    table_columns,
)
from feeders.design import DESIGN_SPACE, PARAMETER_NAMES, DesignSpace
from feeders.feeder import ORIENTATIONS

STATUSES = ("feasible", "infeasible", "unknown", "degenerate")
# The levels judged by sampling planners (OMPL's RRT, KPIECE1, EST): a design they do not
# solve within the budget is "unknown", never proved infeasible (issue 21).
SAMPLED_LEVELS = ("geometric", "kinematic", "dynamic")
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

_SCHEMA_STATUSES = ", ".join(f"'{status}'" for status in STATUSES)
_DESIGNS = """
CREATE TABLE IF NOT EXISTS designs (
    design_id INTEGER PRIMARY KEY,
    holdout INTEGER NOT NULL,
    {columns}
);"""
_TABLES = f"""
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
{{designs}}
CREATE TABLE IF NOT EXISTS evaluations (
    design_id INTEGER NOT NULL REFERENCES designs(design_id),
    level TEXT NOT NULL,
    rung INTEGER NOT NULL,
    status TEXT NOT NULL CHECK (status IN ({_SCHEMA_STATUSES})),
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
CREATE TABLE IF NOT EXISTS verdicts (
    design_id INTEGER PRIMARY KEY,
    decision TEXT NOT NULL,
    target REAL NOT NULL,
    trials INTEGER NOT NULL,
    heavy_leading INTEGER NOT NULL,
    heavy_trailing INTEGER NOT NULL,
    both_entries INTEGER NOT NULL,
    exit_heavy_leading_s REAL,
    exit_heavy_trailing_s REAL,
    seed INTEGER NOT NULL,
    verdict TEXT NOT NULL
);
"""


def schema(parameters: Sequence[str] = PARAMETER_NAMES) -> str:
    """The database's schema with ``parameters`` as the ``designs`` table's columns (names
    checked by :func:`experiments.sweep.family.column_problem`; quoted all the same)."""
    columns = ", ".join(f'"{name}" REAL NOT NULL' for name in parameters)
    return _TABLES.replace("{designs}", _DESIGNS.replace("{columns}", columns))


_SCHEMA = schema()
DECISIONS = ("works", "fails", "undecided")


def status_of(level: str, stored: str) -> str:
    """The status of a stored evaluation: as stored, except that a sampled level's
    ``infeasible`` is ``unknown`` (what a database written before ``unknown`` existed meant
    by it: its planners did not find a path within the budget, which proves nothing)."""
    if stored == "infeasible" and level in SAMPLED_LEVELS:
        return "unknown"
    return stored


class ResultsMismatch(ValueError):
    """The database holds the results of another config."""


class ResultsDamaged(ValueError):
    """The file is not a sound results database: damaged, truncated or of another schema."""


def damaged(path: str | Path, problem: str) -> ResultsDamaged:
    """The error for the results database at ``path`` refused for ``problem``."""
    return ResultsDamaged(
        f"results database '{path}' {problem}; nothing was written to it: move it aside "
        "(or delete it) and run the same command again to redo the sweep"
    )


MAX_META_BYTES = 4 << 20  # a stored config or family record (a family file is at most 1 MiB)


def _stored_family_problem(
    family: dict[str, Any], parameters: tuple[str, ...], entries: tuple[str, ...]
) -> str | None:
    """Why the stored family record's text is not the family the database's columns say
    (read by the one bounded reader, :func:`experiments.family_config.family_of_text`: a
    report rebuilds the family from it), or None."""
    from experiments.family_config import family_of_text
    from feeders.fields import FieldError

    text, name = family.get("yaml"), family.get("name")
    if not isinstance(text, str) or not isinstance(name, str):
        return "meta: the stored family has no text"
    try:
        rebuilt = family_of_text(text, name)
    except FieldError as exc:
        return f"meta: the stored family's text cannot be read ({str(exc)[:300]})"
    if rebuilt.vector_names != parameters or tuple(n for n, _ in rebuilt.entries) != entries:
        return "meta: the stored family's text is not the family of the stored parameters"
    return None


def _content_problem(db: sqlite3.Connection) -> str | None:
    """What in the stored rows cannot have been written by this module (damage inside a data
    page that leaves the pages well-formed): text that is not UTF-8, a config that is not
    JSON, designs that are not the config's Halton points, a status, level, flag, planner or
    orientation outside their sets, a time or count that is negative, not finite or of the
    wrong type. A changed digit within a plausible number remains undetectable."""
    from experiments.names import RUNG_NAMES
    from feeders.halton import halton_points

    long = db.execute(
        "SELECT key FROM meta WHERE length(CAST(value AS BLOB)) > ? LIMIT 1", (MAX_META_BYTES,)
    ).fetchone()
    if long is not None:  # never loaded: a config or family is a few kilobytes
        return f"meta: a stored value is larger than {MAX_META_BYTES} bytes"
    db.text_factory = bytes  # decode here, to name the column
    try:
        meta = {}
        for key, value in db.execute("SELECT key, value FROM meta"):
            meta[key.decode("utf-8")] = value.decode("utf-8")
        # a run killed between creating the file and claiming it stored no config yet
        config = json.loads(meta["config"]) if "config" in meta else None
        if config is not None:
            count, seed = int(config["designs"]["count"]), int(config["designs"]["seed"])
            levels = tuple(str(rung["level"]) for rung in config["ladder"])
        family = json.loads(meta["family"]) if "family" in meta else None
        parameters, entries, space = _family_columns(family)
    except (UnicodeDecodeError, ValueError, KeyError, TypeError, AttributeError) as exc:
        return f"meta: the stored config cannot be read ({type(exc).__name__})"
    finally:
        db.text_factory = str
    if table_columns(db)["designs"][2:] != list(parameters):
        return "designs: the parameter columns are not those of the sweep's family"
    if family is not None:
        problem = _stored_family_problem(family, parameters, entries)
        if problem:
            return problem
    quoted = ", ".join(f'"{name}"' for name in parameters)
    stored = db.execute(
        f"SELECT design_id, holdout, {quoted} FROM designs ORDER BY design_id"
    ).fetchall()
    if any(
        row[1] not in (0, 1) or not all(isinstance(v, float) for v in row[2:]) for row in stored
    ):
        return "designs: a row holds a value this program never writes"
    if config is None:
        levels = RUNG_NAMES
    elif stored:
        expected = halton_points(count, seed, space)
        ids = [row[0] for row in stored]
        if ids != list(range(len(stored))) or len(stored) > count:
            return "designs: the design ids are not those of the config"
        if [list(row[2:]) for row in stored] != expected[: len(stored)].tolist():
            return "designs: the stored designs are not the config's Halton points"
    names = {
        "levels": ", ".join(f"'{lv}'" for lv in levels),
        "statuses": ", ".join(f"'{s}'" for s in STATUSES),
        "orientations": ", ".join("'{}'".format(e.replace("'", "''")) for e in entries),
    }
    checks = {
        "evaluations": f"""level NOT IN ({names["levels"]}) OR status NOT IN ({names["statuses"]})
            OR typeof(design_id) != 'integer' OR typeof(rung) != 'integer' OR rung < 0
            OR rung >= {len(levels)} OR coalesce(heavy_leading, 0) NOT IN (0, 1)
            OR coalesce(heavy_trailing, 0) NOT IN (0, 1) OR typeof(wall_time_s) != 'real'
            OR NOT wall_time_s >= 0 OR typeof(attempts) != 'integer' OR attempts < 1""",
        "runs": f"""level NOT IN ({names["levels"]}) OR orientation NOT IN ({names["orientations"]})
            OR solved NOT IN (0, 1) OR approximate NOT IN (0, 1) OR typeof(run) != 'integer'
            OR typeof(seed) != 'integer'
            OR typeof(time_s) NOT IN ('real', 'integer', 'null') OR time_s < 0
            OR typeof(exit_time_s) NOT IN ('real', 'integer', 'null') OR exit_time_s < 0
            OR typeof(tree_size) NOT IN ('integer', 'null') OR tree_size < 0
            OR typeof(propagations) NOT IN ('integer', 'null') OR propagations < 0
            OR typeof(validity_checks) NOT IN ('integer', 'null') OR validity_checks < 0""",
        "ompl_logs": f"""level NOT IN ({names["levels"]})
            OR orientation NOT IN ({names["orientations"]}) OR typeof(log) != 'text'""",
        "quarantine": f"""level NOT IN ({names["levels"]}) OR typeof(attempts) != 'integer'
            OR typeof(reason) != 'text'""",
        "verdicts": f"""decision NOT IN ({", ".join(f"'{d}'" for d in DECISIONS)})
            OR typeof(trials) != 'integer' OR trials < 1 OR typeof(target) != 'real'
            OR NOT target BETWEEN 0 AND 1 OR typeof(verdict) != 'text'
            OR heavy_leading NOT BETWEEN 0 AND trials OR heavy_trailing NOT BETWEEN 0 AND trials
            OR both_entries NOT BETWEEN 0 AND min(heavy_leading, heavy_trailing)""",
    }
    present = set(table_columns(db))
    for table, condition in checks.items():
        if table not in present:
            continue
        if db.execute(f"SELECT 1 FROM {table} WHERE {condition} LIMIT 1").fetchone():
            return f"{table}: a row holds a value this program never writes"
    bad_log = _log_problem(db)
    if bad_log:
        return bad_log
    texts = {  # every other text column
        "evaluations": "level, status, reason, worker",
        "runs": "level, orientation, planner",
        "quarantine": "level, reason",
        "verdicts": "decision, verdict",
    }
    for table, columns in texts.items():
        if table not in present:
            continue
        try:
            for _ in db.execute(f"SELECT {columns} FROM {table}"):
                pass
        except sqlite3.OperationalError as exc:  # text that is not UTF-8
            return f"{table}: {exc}"
    return None


def _family_columns(
    family: dict[str, Any] | None,
) -> tuple[tuple[str, ...], tuple[str, ...], DesignSpace]:
    """The parameter names, entry names and design box of a stored family (``meta``'s
    ``family``; None: the feeder's, with Table 2's box)."""
    if family is None:
        return PARAMETER_NAMES, ORIENTATIONS, DESIGN_SPACE
    parameters = tuple(str(name) for name in family["parameters"])
    entries = tuple(str(name) for name in family["entries"])
    box = tuple(zip(map(float, family["low"]), map(float, family["high"]), strict=True))
    if len(box) != len(parameters):
        raise ValueError("the family's box is not its parameters'")
    return parameters, entries, DesignSpace(box)


def stored_family(db: sqlite3.Connection) -> dict[str, Any] | None:
    """The device family a results database belongs to
    (:func:`experiments.family_config.family_record`), or None: the 12-parameter feeder's."""
    row = db.execute("SELECT value FROM meta WHERE key = 'family'").fetchone()
    return None if row is None else json.loads(row[0])


def parameter_names(db: sqlite3.Connection) -> tuple[str, ...]:
    """The design parameters of a results database: its ``designs`` table's columns."""
    return tuple(table_columns(db)["designs"][2:])


def _log_problem(db: sqlite3.Connection) -> str | None:
    """The first stored OMPL log that is not UTF-8 text (garbage inside its record), named
    by its design, level and entry orientation. ``ompl/benchmark.db``, what Planner Arena
    opens, is made from these logs (``export_ompl``): a report that passed over a damaged
    one would say all is well while that database cannot be made. Reading them costs about
    what ``integrity_check`` already spends on their pages."""
    db.text_factory = bytes
    try:
        rows = db.execute("SELECT design_id, level, orientation, log FROM ompl_logs")
        for design_id, level, orientation, log in rows:
            try:
                log.decode("utf-8")
            except UnicodeDecodeError:
                return (
                    f"ompl_logs: the OMPL log of design {design_id}, level "
                    f"{level.decode('utf-8', 'replace')}, "
                    f"{orientation.decode('utf-8', 'replace')} is not UTF-8 text"
                )
    finally:
        db.text_factory = str
    return None


def check_database(path: str | Path) -> bool:
    """Refuse (:class:`ResultsDamaged`) a file at ``path`` that is not a sound results
    database (:func:`experiments.database_file.check_file`; the rows checked by
    :func:`_content_problem`). Returns whether it holds our tables (False: missing, empty or
    new)."""
    return check_file(
        path,
        schema(_stored_parameters(Path(path))),
        damaged,
        "results database",
        added_later={"verdicts"},
        content_problem=_content_problem,
        trust_wal=True,  # after a full disk its rows may sit in its WAL: read through it
    )


def _stored_parameters(path: Path) -> tuple[str, ...]:
    """The parameter columns of the ``designs`` table of the file at ``path`` (a family's
    sweep has its own), read only; the feeder's when none can be read (a missing, damaged
    or foreign file: :func:`check_database` then says what is wrong with it)."""
    try:
        info = path.stat()
        if not stat.S_ISREG(info.st_mode) or info.st_size == 0:
            return PARAMETER_NAMES
        with path.open("rb") as handle:
            problem = header_problem(handle.read(100), info.st_size)
        if problem and not size_problem_in_wal(path, problem):
            return PARAMETER_NAMES
        db = open_read_only(path)
        try:
            columns = table_columns(db).get("designs") or []
        finally:
            db.close()
    except (OSError, sqlite3.DatabaseError):
        return PARAMETER_NAMES
    if columns[:2] == ["design_id", "holdout"] and len(columns) > 2:
        return tuple(columns[2:])
    return PARAMETER_NAMES


def connect(
    path: str | Path, readonly: bool = False, parameters: Sequence[str] = PARAMETER_NAMES
) -> sqlite3.Connection:
    """Open a results database (created if missing, unless ``readonly``), after
    :func:`check_database` has found it sound. ``readonly`` opens it with
    :func:`experiments.database_file.open_read_only`: nothing is written or created beside
    it, so a finished sweep is read in a directory this process may not write. A database
    created here gets ``parameters`` as its design columns (a family's sweep: the family's;
    :func:`claim` refuses one of other parameters)."""
    path = Path(path)
    ours = check_database(path)
    if readonly:
        if not path.exists():
            raise FileNotFoundError(f"no results database at '{path}'")
        if not ours:
            raise damaged(path, "holds no partfeeder results (it is empty)")
        db = open_read_only(path)
    else:
        path.parent.mkdir(parents=True, exist_ok=True)
        db = sqlite3.connect(path, timeout=30.0)
        db.execute("PRAGMA journal_mode=WAL")
        db.execute("PRAGMA synchronous=NORMAL")  # durable against a killed process
        db.executescript(schema(parameters))
        _allow_every_status(db)
        complete_checkpoint(db, path)
    db.row_factory = sqlite3.Row
    return db


def _allow_every_status(db: sqlite3.Connection) -> None:
    """Make an ``evaluations`` table created before ``unknown`` existed accept it: SQLite
    cannot change a CHECK in place, so the table is made again with this schema's and its
    rows copied, in one transaction (a resumed older sweep then stores new statuses)."""
    row = db.execute(
        "SELECT sql FROM sqlite_master WHERE type = 'table' AND name = 'evaluations'"
    ).fetchone()
    if row is None or all(f"'{status}'" in row[0] for status in STATUSES):
        return
    create = next(
        statement
        for statement in _SCHEMA.split(";")
        if "TABLE IF NOT EXISTS evaluations" in statement
    )
    db.execute("BEGIN IMMEDIATE")  # DDL opens no implicit transaction in sqlite3
    try:
        db.execute("ALTER TABLE evaluations RENAME TO evaluations_before")
        db.execute(create)
        db.execute("INSERT INTO evaluations SELECT * FROM evaluations_before")
        db.execute("DROP TABLE evaluations_before")
    except BaseException:
        db.rollback()
        raise
    db.commit()


def claim(
    db: sqlite3.Connection,
    config: dict[str, Any],
    results_key: str,
    family: dict[str, Any] | None = None,
) -> None:
    """Tie the database to a config and its device family (``family``:
    :func:`experiments.family_config.family_record`; None: the 12-parameter feeder); a
    database of another config raises :class:`ResultsMismatch` (its results are not mixed
    with this config's), naming the field when it is the family or its parameters."""
    row = db.execute("SELECT value FROM meta WHERE key = 'results_key'").fetchone()
    problem = _family_mismatch(db, family, claimed=row is not None)
    if problem:
        raise ResultsMismatch(f"{problem}; choose another --out or remove it")
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
        if family is not None:
            db.execute("INSERT OR IGNORE INTO meta VALUES ('family', ?)", (json.dumps(family),))


def _family_mismatch(
    db: sqlite3.Connection, family: dict[str, Any] | None, claimed: bool
) -> str | None:
    """Why the database cannot hold the sweep of ``family`` (None: the feeder), or None: it
    belongs to another family (``family``), or its design columns are not the family's
    parameters (``parameters``)."""

    def called(f: dict[str, Any] | None) -> str:
        return "the 12-parameter feeder" if f is None else f"family '{f['name']}'"

    stored = stored_family(db)
    if (claimed and (stored is None) != (family is None)) or (
        stored is not None and family is not None and stored["name"] != family["name"]
    ):
        return (
            f"family: this directory holds a sweep of {called(stored)}, this config's is "
            f"{called(family)}"
        )
    expected = list(PARAMETER_NAMES if family is None else family["parameters"])
    columns = list(parameter_names(db))
    if columns != expected:
        return (
            f"parameters: this directory holds a sweep of parameters {columns}, "
            f"{called(family)} has {expected}"
        )
    return None


def add_designs(db: sqlite3.Connection, rows: Iterable[tuple[int, bool, list[float]]]) -> None:
    """Store designs (design_id, holdout, values: one per parameter column); ones already
    stored are kept."""
    marks = ", ".join("?" * (2 + len(parameter_names(db))))
    with db:
        db.executemany(
            f"INSERT OR IGNORE INTO designs VALUES ({marks})",
            [(i, int(h), *map(float, values)) for i, h, values in rows],
        )


def finished(db: sqlite3.Connection) -> dict[tuple[int, str], str]:
    """(design_id, level) -> status of every evaluation stored (:func:`status_of`),
    'quarantined' included."""
    done = {
        (r["design_id"], r["level"]): status_of(r["level"], r["status"])
        for r in db.execute("SELECT design_id, level, status FROM evaluations")
    }
    for r in db.execute("SELECT design_id, level FROM quarantine"):
        done[(r["design_id"], r["level"])] = "quarantined"
    return done


def record(db: sqlite3.Connection, result: dict[str, Any], rung: int, attempts: int) -> bool:
    """Store one evaluation with its runs and logs, atomically. Returns False (and stores
    nothing) if that (design, level) is already stored."""
    key = (int(result["design_id"]), str(result["level"]))
    first, second = _two_entries(result["orientations"])
    with db:
        cursor = db.execute(
            "INSERT OR IGNORE INTO evaluations VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
            (
                *key,
                rung,
                result["status"],
                result.get("reason"),
                _flag(first),
                _flag(second),
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
        if "verdict" in result:
            _record_verdict(db, key[0], result["verdict"], int(result["verdict_seed"]))
    return True


def _two_entries(per_entry: dict[str, Any]) -> tuple[Any, Any]:
    """The feeder's entries' values by name (heavy leading, heavy trailing), else a family's
    first and second entry's, in its file's order (the columns named after the feeder's)."""
    if set(per_entry) <= set(ORIENTATIONS):
        return per_entry.get(ORIENTATIONS[0]), per_entry.get(ORIENTATIONS[1])
    values = [*per_entry.values(), None, None]
    return values[0], values[1]


def _record_verdict(db: sqlite3.Connection, design_id: int, verdict: dict, seed: int) -> None:
    first, second = _two_entries(verdict["orientations"])
    db.execute(
        "INSERT INTO verdicts VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
        (
            design_id,
            verdict["decision"],
            float(verdict["target"]),
            int(verdict["drops"]),
            int(first["successes"]),
            int(second["successes"]),
            int(verdict["both"]["successes"]),
            first["mean_exit_time_s"],
            second["mean_exit_time_s"],
            seed,
            json.dumps(verdict),
        ),
    )


def verdicts(db: sqlite3.Connection) -> dict[int, dict[str, Any]]:
    """design_id -> its stored passive verdict (``Verdict.to_dict()``, with ``seed``); none
    in a database made before the ``verdicts`` table (opened read-only, it lacks it)."""
    if "verdicts" not in table_columns(db):
        return {}
    return {
        int(r["design_id"]): {**json.loads(r["verdict"]), "seed": int(r["seed"])}
        for r in db.execute("SELECT design_id, seed, verdict FROM verdicts")
    }


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
