"""One ``partfeeder run`` per sweep directory at a time.

Two runs on one directory would both write the results database (SQLite keeps that
consistent) and both rebuild ``ompl/benchmark.db`` (one of them then dies of a
``disk I/O error``). :func:`sweep_lock` holds an exclusive ``fcntl.flock`` on ``LOCK_FILE`` in
the directory for the whole run; a second run finds it held and raises
:class:`DirectoryInUse` naming the holder (pid, host, start time, written into the lock file
by the holder). A directory holding another job's database (``results.sqlite`` of ``run``,
``evaluations.sqlite`` of ``optimize``; or a lock file left by an older version naming
another job) is refused, so one job's directory is never written by another.

The lock file is removed when the job ends (issue 37: it stayed after a clean exit), while
the lock is still held; a process that opened the file just before and locks it after finds
that the path no longer names the file it locked, and starts again with a new one, so two
processes never both hold the directory.

The lock file is opened without following a symbolic link (a link planted there had its
target truncated and overwritten), and anything there but a regular file is refused.

The lock belongs to the open file, not to the file on disk: the operating system releases it
when the holding process ends in any way, ``kill -9`` included, so a stale lock left by a
killed run is simply taken over by the next one (its old holder line is overwritten). The
descriptor is not inherited by worker processes (close-on-exec; the executors spawn their
workers), so a worker that outlives a killed run does not keep the directory locked.
"""

from __future__ import annotations

import contextlib
import errno
import fcntl
import json
import os
import socket
import stat
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

LOCK_FILE = "partfeeder.lock"
JOB_DATABASES = {"run": "results.sqlite", "optimize": "evaluations.sqlite"}


class DirectoryInUse(ValueError):
    """The sweep directory is locked by a running ``partfeeder run``."""


def _recorded(fd: int) -> dict:
    """What the lock file says of its last holder (empty when it says nothing we wrote)."""
    try:
        info = json.loads(os.pread(fd, 4096, 0).decode("utf-8"))
    except (OSError, ValueError):  # being written, or not ours
        return {}
    return info if isinstance(info, dict) else {}


def _holder_text(fd: int) -> str:
    """The holder as the lock file describes it: 'pid P on host H since T'."""
    info = _recorded(fd)
    try:
        return f"pid {info['pid']} on host {info['host']} since {info['started']}"
    except KeyError:
        return "a process that has not said who it is yet"


@contextmanager
def sweep_lock(directory: str | Path, job: str = "run") -> Iterator[Path]:
    """Hold the lock of the existing output directory ``directory`` of a ``partfeeder
    job`` (run, optimize) while inside; raises :class:`DirectoryInUse` at once (no waiting)
    if another process holds it, or if the directory holds another job's results (the lock
    file records its job). Yields the lock file's path."""
    path = Path(directory) / LOCK_FILE
    for other, database in JOB_DATABASES.items():
        if other != job and (Path(directory) / database).exists():
            raise DirectoryInUse(
                f"'{directory}' holds the results of partfeeder {other}, not {job}; "
                "give another --out"
            )
    fd = _locked(path, directory)
    try:
        earlier = _recorded(fd).get("job", job)  # a lock file an older version left behind
        if earlier != job:
            raise DirectoryInUse(
                f"'{directory}' holds the results of partfeeder {earlier}, not {job}; "
                "give another --out"
            )
        holder = {
            "pid": os.getpid(),
            "host": socket.gethostname(),
            "started": time.strftime("%Y-%m-%d %H:%M:%S %z"),
            "job": job,
        }
        os.ftruncate(fd, 0)
        os.pwrite(fd, json.dumps(holder).encode("utf-8"), 0)
        try:
            yield path
        finally:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(path)  # still held: whoever opened it meanwhile starts again
    finally:
        os.close(fd)  # releases the lock


def _locked(path: Path, directory: str | Path) -> int:
    """A descriptor of the lock file at ``path`` holding its exclusive lock, the file still
    the one the path names (a holder that ended removed it: then a new one is made)."""
    refused = DirectoryInUse(
        f"'{path}' is not a regular file (a link, a pipe or a device); "
        "remove it or give another --out"
    )
    flags = os.O_RDWR | os.O_CREAT | os.O_CLOEXEC | os.O_NOFOLLOW | os.O_NONBLOCK
    while True:
        try:
            fd = os.open(path, flags, 0o644)  # never through a link; never blocks on a pipe
        except OSError as exc:
            if exc.errno in (errno.ELOOP, errno.ENXIO):
                raise refused from None
            raise
        try:
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                raise refused
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                held_by = _recorded(fd).get("job", "run")
                raise DirectoryInUse(
                    f"'{directory}' is in use by another partfeeder {held_by} "
                    f"({_holder_text(fd)}); wait for it to finish, or give another --out"
                ) from None
            mine = os.fstat(fd)
            try:
                named = os.stat(path, follow_symlinks=False)
            except FileNotFoundError:
                named = None
            if named is not None and (named.st_ino, named.st_dev) == (mine.st_ino, mine.st_dev):
                return fd
        except BaseException:
            os.close(fd)
            raise
        os.close(fd)  # the file it locked was removed by its last holder: again
