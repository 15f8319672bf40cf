"""Is a file a sound SQLite database of ours? The checks every results database of partfeeder
gets before it is opened for writing (the sweep's, the optimiser's): a file damaged, truncated
or of another program is refused, with nothing written to it, instead of being extended.

Every read of such a database (the check, a report, ``optimize --from``) goes through
:func:`open_read_only`: a connection that cannot write and creates no file beside the
database, so a refused file is left byte for byte as it was and a finished sweep can be read
in a directory this process may not write.

A database kind is given by its schema (``CREATE TABLE IF NOT EXISTS`` statements), the tables
a newer version added (an older database without them is still ours: ``connect`` creates
them), and a check of the stored rows (what its writer can never have written).
"""

from __future__ import annotations

import sqlite3
import stat
from collections.abc import Callable, Collection
from pathlib import Path
from urllib.parse import quote

SQLITE_HEADER = b"SQLite format 3\x00"
FULL_CHECK_BYTES = 256 << 20  # ``integrity_check`` up to this size, ``quick_check`` above

ContentCheck = Callable[[sqlite3.Connection], "str | None"]


def read_only_uri(path: str | Path) -> str:
    """The SQLite URI that opens ``path`` for reading only, writing and creating nothing.

    SQLite's ``mode=ro`` alone is not enough for a WAL database (ours are): a reader needs
    the ``-shm`` wal-index, and SQLite creates it and an empty ``-wal`` beside the database
    when they are missing (and leaves them: a read-only connection cannot checkpoint), or, in
    a directory it may not write, fails with "attempt to write a readonly database". So:

    - no ``-wal`` beside the file: ``immutable=1`` (read the file as it is, without locks or
      wal-index). A WAL database has a ``-wal`` from the moment a connection uses it until
      the last one closes; without it no connection is using the database: nothing sits in
      a WAL to be missed, and nobody is writing, which ``immutable`` requires. This is a
      finished sweep or optimisation, a copied or archived one, a damaged file being checked.
    - a ``-wal`` beside it: a writer is running (a sweep still going) or was killed with
      commits left in its WAL: plain ``mode=ro``, which reads them through the existing
      ``-shm`` (SQLite >= 3.22 reads even when that file is read-only) and locks like any
      reader, so a report reads safely while the sweep writes.

    A writer starting after the open, while the reader still reads, is not seen (the
    immutable reader reads on as if the file did not change); :func:`check_file` detects it
    and checks again. The path is percent-quoted (a '?' or '#' in it is a file name)."""
    path = Path(path)
    uri = f"file:{quote(str(path.absolute()), safe='/')}?mode=ro"
    if not path.with_name(path.name + "-wal").exists():
        uri += "&immutable=1"
    return uri


def open_read_only(path: str | Path, timeout: float = 30.0) -> sqlite3.Connection:
    """A connection to ``path`` that cannot write and creates nothing (:func:`read_only_uri`)."""
    return sqlite3.connect(read_only_uri(path), uri=True, timeout=timeout)


def _state(path: Path) -> tuple[int, int, bool]:
    """What changes when a writer starts on ``path``: size, modification time, a ``-wal``."""
    info = path.stat()
    return info.st_size, info.st_mtime_ns, path.with_name(path.name + "-wal").exists()


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


WAL_HEADER_BYTES = 32
WAL_FRAME_HEADER_BYTES = 24


def wal_has_frames(path: str | Path) -> bool:
    """Whether a ``-wal`` beside ``path`` holds at least one frame (a page written after the
    last checkpoint): SQLite then takes the database's size and newest pages from it, not
    from the main file's header."""
    wal = Path(path).with_name(Path(path).name + "-wal")
    try:
        info = wal.stat()
    except OSError:
        return False
    if not stat.S_ISREG(info.st_mode) or info.st_size < WAL_HEADER_BYTES:
        return False
    with wal.open("rb") as handle:
        header = handle.read(WAL_HEADER_BYTES)
    if header[:4] not in (b"\x37\x7f\x06\x82", b"\x37\x7f\x06\x83"):  # WAL magic
        return False
    page = int.from_bytes(header[8:12], "big")
    return info.st_size >= WAL_HEADER_BYTES + WAL_FRAME_HEADER_BYTES + page


def size_problem_in_wal(path: str | Path, problem: str | None) -> bool:
    """Whether :func:`header_problem`'s ``problem`` is only the main file being shorter than
    its header says while a ``-wal`` holds frames: the state a full disk leaves in the middle
    of a checkpoint (page 1 written, the pages after it not), every page still in the WAL.
    SQLite reads such a database whole through its WAL; the next checkpoint completes it."""
    return problem is not None and "truncated" in problem and wal_has_frames(path)


def complete_checkpoint(db: sqlite3.Connection, path: Path) -> None:
    """A database left by a full disk in the middle of a checkpoint (its main file shorter
    than its header says, every page in its WAL) is checkpointed now, through ``db`` (open
    for writing), so the main file is whole again before a job goes on."""
    with path.open("rb") as handle:
        problem = header_problem(handle.read(100), path.stat().st_size)
    if problem:
        db.execute("PRAGMA wal_checkpoint(TRUNCATE)")


def check_file(
    path: str | Path,
    schema: str,
    damaged: Callable[[Path, str], Exception],
    what: str,
    added_later: Collection[str] = (),
    content_problem: ContentCheck | None = None,
    trust_wal: bool = False,
) -> bool:
    """Refuse (``damaged(path, problem)``) a file at ``path`` that is not a sound database of
    ``schema``, reading only: a header that is not SQLite's, a file that SQLite finds damaged
    (``PRAGMA integrity_check``, or ``quick_check`` above ``FULL_CHECK_BYTES``: it skips
    matching indexes to tables, and is linear in the file), tables other than the schema's
    (``what`` names the kind in the message), or rows ``content_problem`` says its writer cannot
    have written. A missing or empty file passes (it becomes a new database). Damage that
    leaves every page and value well-formed (a changed digit inside a plausible number) is not
    detectable: SQLite keeps no checksums. With ``trust_wal``, a main file shorter than its
    header says while its ``-wal`` holds frames (:func:`size_problem_in_wal`) is checked
    through the WAL by SQLite instead of refused by the header's count. Returns whether it
    holds our tables (False: missing, empty or new)."""
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
    if problem and not (trust_wal and size_problem_in_wal(path, problem)):
        raise damaged(path, problem)
    check = "integrity_check" if size <= FULL_CHECK_BYTES else "quick_check"
    found: tuple[list[str], dict[str, list[str]]] | sqlite3.DatabaseError
    for _ in range(2):
        before = _state(path)
        try:
            found = _read_check(path, check, schema, added_later, content_problem)
        except sqlite3.DatabaseError as exc:
            found = exc
        if before[2] or _state(path) == before:
            break
        # read as immutable, but a writer started meanwhile: check again, through its WAL
    if isinstance(found, sqlite3.DatabaseError):
        raise damaged(path, f"cannot be read ({found})")
    rows, columns = found
    if rows != ["ok"]:
        raise damaged(path, f"is damaged ({rows[0] if rows else 'no answer'})")
    if columns and not is_ours(columns, schema, added_later):
        raise damaged(path, f"has tables that are not a partfeeder {what}'s")
    return bool(columns)


def _read_check(
    path: Path,
    check: str,
    schema: str,
    added_later: Collection[str],
    content_problem: ContentCheck | None,
) -> tuple[list[str], dict[str, list[str]]]:
    """SQLite's ``check`` of ``path`` (its rows, prefixed with the check's name unless
    ``["ok"]``), then, if it is sound and ours, ``content_problem``'s answer in its place;
    and the tables' columns. Read through :func:`open_read_only`."""
    columns: dict[str, list[str]] = {}
    db = open_read_only(path)
    try:
        rows = [r[0] for r in db.execute(f"PRAGMA {check}(1)")]
        if rows != ["ok"]:
            return [f"SQLite's {check}: {rows[0] if rows else 'no answer'}"], columns
        columns = table_columns(db)
        if is_ours(columns, schema, added_later) and content_problem is not None:
            content = content_problem(db)
            if content:
                rows = [content]
    finally:
        db.close()
    return rows, columns
