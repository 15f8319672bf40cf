"""Is a file a sound SQLite database of ours? The checks every results database of partfeeder
gets before it is opened for writing (the sweep's, the optimiser's): a file damaged, truncated
or of another program is refused, with nothing written to it, instead of being extended.

A database kind is given by its schema (``CREATE TABLE IF NOT EXISTS`` statements), the tables
a newer version added (an older database without them is still ours: ``connect`` creates
them), and a check of the stored rows (what its writer can never have written).
"""

from __future__ import annotations

import sqlite3
import stat
from collections.abc import Callable, Collection
from pathlib import Path

SQLITE_HEADER = b"SQLite format 3\x00"
FULL_CHECK_BYTES = 256 << 20  # ``integrity_check`` up to this size, ``quick_check`` above

ContentCheck = Callable[[sqlite3.Connection], "str | None"]


def table_columns(db: sqlite3.Connection) -> dict[str, list[str]]:
    """Table -> its column names, for every table of ``db``."""
    tables = [
        r[0]
        for r in db.execute(
            "SELECT name FROM sqlite_master WHERE type = 'table' AND name NOT LIKE 'sqlite_%'"
        )
    ]
    return {t: [r[1] for r in db.execute(f'PRAGMA table_info("{t}")')] for t in tables}


def schema_columns(schema: str) -> dict[str, list[str]]:
    """Table -> column names of ``schema``, from an empty in-memory database built by it."""
    db = sqlite3.connect(":memory:")
    try:
        db.executescript(schema)
        return table_columns(db)
    finally:
        db.close()


def is_ours(columns: dict[str, list[str]], schema: str, added_later: Collection[str] = ()) -> bool:
    """Whether tables with ``columns`` are ``schema``'s: each as the schema makes it, and only
    the tables in ``added_later`` may be missing."""
    expected = schema_columns(schema)
    return all(expected.get(t) == c for t, c in columns.items()) and set(expected) - set(
        columns
    ) <= set(added_later)


def header_problem(header: bytes, size: int) -> str | None:
    """What SQLite's 100-byte file header says is wrong with a file of ``size`` bytes: not
    SQLite's magic, a page size that is not a power of two in [512, 65536], a size that is not
    a whole number of pages, or fewer pages than the header counts (a truncated file, whose
    missing pages SQLite would read as zeros)."""
    if len(header) < 100 or not header.startswith(SQLITE_HEADER):
        return "is not an SQLite database (its header is wrong)"
    page = int.from_bytes(header[16:18], "big")
    page = 65536 if page == 1 else page
    if page < 512 or page & (page - 1):
        return f"has a damaged header (page size {page})"
    if size % page:
        return f"is truncated or damaged ({size} bytes is not a whole number of {page}-byte pages)"
    counted = int.from_bytes(header[28:32], "big")
    valid = header[92:96] == header[24:28]  # the count is current (SQLite >= 3.7.0)
    if valid and counted * page > size:
        return f"is truncated (its header counts {counted} pages, the file holds {size // page})"
    return None


def check_file(
    path: str | Path,
    schema: str,
    damaged: Callable[[Path, str], Exception],
    what: str,
    added_later: Collection[str] = (),
    content_problem: ContentCheck | None = None,
) -> bool:
    """Refuse (``damaged(path, problem)``) a file at ``path`` that is not a sound database of
    ``schema``, reading only: a header that is not SQLite's, a file that SQLite finds damaged
    (``PRAGMA integrity_check``, or ``quick_check`` above ``FULL_CHECK_BYTES``: it skips
    matching indexes to tables, and is linear in the file), tables other than the schema's
    (``what`` names the kind in the message), or rows ``content_problem`` says its writer cannot
    have written. A missing or empty file passes (it becomes a new database). Damage that
    leaves every page and value well-formed (a changed digit inside a plausible number) is not
    detectable: SQLite keeps no checksums. Returns whether it holds our tables (False: missing,
    empty or new)."""
    path = Path(path)
    try:
        info = path.stat()
    except FileNotFoundError:
        return False
    if not stat.S_ISREG(info.st_mode):  # a FIFO would block the read below
        raise damaged(path, "is not a regular file")
    size = info.st_size
    if size == 0:
        return False
    with path.open("rb") as handle:
        header = handle.read(100)
    problem = header_problem(header, size)
    if problem:
        raise damaged(path, problem)
    check = "integrity_check" if size <= FULL_CHECK_BYTES else "quick_check"
    columns: dict[str, list[str]] = {}
    try:
        db = sqlite3.connect(f"file:{path}?mode=ro", uri=True, timeout=30.0)
        try:
            rows = [r[0] for r in db.execute(f"PRAGMA {check}(1)")]
            if rows == ["ok"]:
                columns = table_columns(db)
                if is_ours(columns, schema, added_later) and content_problem is not None:
                    content = content_problem(db)
                    if content:
                        rows = [content]
        finally:
            db.close()
    except sqlite3.DatabaseError as exc:
        raise damaged(path, f"cannot be read ({exc})") from None
    if rows != ["ok"]:
        raise damaged(path, f"is damaged (SQLite's {check}: {rows[0] if rows else 'no answer'})")
    if columns and not is_ours(columns, schema, added_later):
        raise damaged(path, f"has tables that are not a partfeeder {what}'s")
    return bool(columns)
