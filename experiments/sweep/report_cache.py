"""A finished sweep's report is drawn again only when what it shows may have changed: the
summary and the report's state are kept in ``report-cache.json`` in the sweep directory under
a key of the results database's rows and of the code that draws it (issue 25: a finished
sweep's ``report`` took 5.0 s on 64 designs, up to 68 s in the issue, all of it figures and
nominal drops drawn again)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from experiments.report_kit.cache import code_digest, read_json, save_json


def report_key(results: Path) -> str | None:
    """SHA-256 of the rows of the results database at ``results`` (every table by name, its
    rows in rowid order, as SQLite's dump gives them: a run that finds nothing to do leaves
    them as they were, though it rewrites the file's header) and of the code that draws the
    report (:func:`experiments.report_kit.cache.code_digest`); None when the database cannot
    be read (then nothing is cached, and the summary says what is wrong)."""
    import hashlib
    import sqlite3

    from experiments.database_file import open_read_only

    digest = hashlib.sha256(CACHE_FORMAT.encode())
    try:
        db = open_read_only(results)
        try:
            for line in db.iterdump():
                digest.update(line.encode("utf-8", "surrogateescape"))
                digest.update(b"\n")
        finally:
            db.close()
    except (sqlite3.Error, OSError, UnicodeError):
        return None
    return code_digest(digest).hexdigest()


def with_baseline(key: str | None, baseline: tuple[str, list[float]]) -> str | None:
    """``key`` (:func:`report_key`) made the key of a report that compares with ``baseline``
    (``(label, 12 values)``): another baseline is another report; None stays None."""
    import hashlib

    if key is None:
        return None
    label, values = baseline
    text = json.dumps([key, str(label), [float(v) for v in values]])
    return hashlib.sha256(text.encode()).hexdigest()


CACHE = "report-cache.json"
OMPL_DATABASE = Path("ompl") / "benchmark.db"
CACHE_FORMAT = "partfeeder report cache 2"  # 2: the findings and the baseline


def load_cache(out: Path, key: str | None) -> dict[str, Any] | None:
    """The cache of ``out`` when it was written under ``key``, else None."""
    if key is None:
        return None
    cache = read_json(out / CACHE)
    if not isinstance(cache, dict) or cache.get("key") != key:
        return None
    if not isinstance(cache.get("summary"), dict):
        return None
    return cache


def save_cache(out: Path, cache: dict[str, Any]) -> None:
    """Written beside and renamed: a reader never sees half of it."""
    save_json(out / CACHE, cache)
