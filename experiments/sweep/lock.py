"""One ``partfeeder run`` per sweep directory at a time.

Two runs on one directory would both write the results database (SQLite keeps that
consistent) and both rebuild ``ompl/benchmark.db`` (one of them then dies of a
``disk I/O error``). :func:`sweep_lock` holds an exclusive ``fcntl.flock`` on ``LOCK_FILE`` in
the directory for the whole run; a second run finds it held and raises
:class:`DirectoryInUse` naming the holder (pid, host, start time, written into the lock file
by the holder). The lock file also records the job (``run``, ``optimize``) whose results the
directory holds, so one job's directory is never written by another.

The lock file is opened without following a symbolic link (a link planted there had its
target truncated and overwritten), and anything there but a regular file is refused.

The lock belongs to the open file, not to the file on disk: the operating system releases it
when the holding process ends in any way, ``kill -9`` included, so a stale lock left by a
killed run is simply taken over by the next one (its old holder line is overwritten). The
descriptor is not inherited by worker processes (close-on-exec; the executors spawn their
workers), so a worker that outlives a killed run does not keep the directory locked.
"""

from __future__ import annotations

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
    refused = DirectoryInUse(
        f"'{path}' is not a regular file (a link, a pipe or a device); "
        "remove it or give another --out"
    )
    flags = os.O_RDWR | os.O_CREAT | os.O_CLOEXEC | os.O_NOFOLLOW | os.O_NONBLOCK
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
        earlier = _recorded(fd).get("job", job)  # lock files from before jobs were recorded
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
        yield path
    finally:
        os.close(fd)  # releases the lock
