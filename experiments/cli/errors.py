"""Which exceptions are the user's bad input, and the one line each becomes.

:func:`experiments.cli.entry.run` prints :class:`~experiments.cli.usage.UsageError` as one
line and exits 2. Some bad input is found below the CLI, by readers and jobs that know nothing
of it: a file's field (``FieldError`` and the design, part and shape errors), a results
database that is damaged or of another config, a sweep directory in use, a scheduler nobody
answers at, a path the system refuses (an ``OSError`` naming a file), SQLite refusing a file.
:func:`input_error_line` turns those into the same one line. Anything else (a ``KeyError``, a
``TypeError``, a ``ValueError`` of our own code) is a bug and keeps its traceback.

The classes are looked up among the modules already imported, so building the parser loads
none of them (``partfeeder --help`` stays fast): an exception of a class whose module was never
imported cannot have been raised.
"""

from __future__ import annotations

import errno
import sqlite3
import sys

from feeders.fields import shown

MAX_LINE = 1000  # characters of an error line before it is shortened

# (module, class): ValueErrors raised on bad input, each with a message naming what is wrong.
INPUT_ERRORS = (
    ("feeders.fields", "FieldError"),  # SceneError, ConfigError, stress CaseError
    ("feeders.design", "DesignError"),
    ("feeders.part", "PartError"),
    ("feeders.shapes", "ShapeError"),
    ("experiments.sweep.results_db", "ResultsMismatch"),
    ("experiments.sweep.results_db", "ResultsDamaged"),
    ("experiments.sweep.lock", "DirectoryInUse"),
    ("experiments.executors.cluster", "SchedulerUnreachable"),
)

# errno of an OSError about a path the user gave or the machine it runs on, not our code.
PATH_ERRNOS = frozenset(
    {
        errno.EACCES,
        errno.EPERM,
        errno.ENOENT,
        errno.ENOTDIR,
        errno.EISDIR,
        errno.EEXIST,
        errno.ENAMETOOLONG,
        errno.EROFS,
        errno.ENOSPC,
        errno.EDQUOT,
        errno.ELOOP,
        errno.EFBIG,
    }
)

# SQLite's errors about the file it was given (damaged, locked, not a database, disk full),
# not ProgrammingError and the like, which are ours.
DATABASE_ERRORS = (sqlite3.OperationalError, sqlite3.DataError)


def _input_classes() -> tuple[type[BaseException], ...]:
    classes = []
    for module_name, class_name in INPUT_ERRORS:
        module = sys.modules.get(module_name)
        if module is not None and hasattr(module, class_name):
            classes.append(getattr(module, class_name))
    return tuple(classes)


def one_line(text: str) -> str:
    """``text`` as one line of at most about ``MAX_LINE`` characters (a 5,000-character value
    quoted in a message is shortened to its ends)."""
    text = " ".join(text.splitlines())
    return text if len(text) <= MAX_LINE else shown(text)


def disk_full(exc: BaseException) -> bool:
    """Whether ``exc`` says the disk (or the user's quota) is full: a file's write, or
    SQLite's "database or disk is full"."""
    if isinstance(exc, OSError) and exc.errno in (errno.ENOSPC, errno.EDQUOT):
        return True
    return isinstance(exc, sqlite3.OperationalError) and "disk is full" in str(exc)


def input_error_line(exc: BaseException) -> str | None:
    """The line to print for ``exc`` if it is bad input, else None (a bug: re-raise)."""
    if isinstance(exc, _input_classes()):
        return str(exc)
    if disk_full(exc):
        return (
            f"the disk is full ({one_line(str(exc))}): free space and run the same command "
            "again; what was stored so far is kept and the job goes on from there"
        )
    if isinstance(exc, OSError) and exc.errno in PATH_ERRNOS:
        where = f"'{shown(exc.filename)}'" if exc.filename is not None else "a file"
        return f"cannot use {where}: {exc.strerror or errno.errorcode.get(exc.errno or 0)}"
    if type(exc) is sqlite3.DatabaseError or isinstance(exc, DATABASE_ERRORS):
        return (
            f"the results database cannot be used ({exc}); if it is damaged, move it aside "
            "and run the same command again"
        )
    return None
