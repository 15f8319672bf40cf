"""Bad input from the user, and the checks every subcommand shares.

A subcommand raises :class:`UsageError` with one line naming the flag and its allowed range;
:func:`experiments.cli.entry.run` prints it as ``partfeeder COMMAND: error: ...`` and exits 2.

Output paths are checked before anything is written: an ``--out`` directory that is an
existing file (the config itself, say), lies under a file, under ``/proc`` or on a read-only
file system, or has a name longer than the file system allows is one line, and nothing is
created.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterable
from pathlib import Path

from feeders.fields import shown

TIME_RANGE_S = (0.0, 3600.0)  # a budget or a simulated time: (0, 1 h]
SEED_RANGE = (1, 2**31 - 1)  # OMPL ignores seed 0
NAME_MAX = 255  # bytes of one path component (Linux, macOS)
PATH_MAX = 4096  # bytes of a whole path (Linux)
PICTURE_SUFFIXES = (".png", ".pdf", ".svg")


class UsageError(Exception):
    """Bad input from the user: printed as one line, exit status 2."""


def check_time(seconds: float, flag: str = "--time") -> None:
    """A time in (0, 3600] s, or UsageError naming ``flag``."""
    if not (TIME_RANGE_S[0] < seconds <= TIME_RANGE_S[1]):
        raise UsageError(f"{flag} = {seconds} is outside the allowed range (0, 3600] s")


def check_seed(seed: int, flag: str = "--seed") -> None:
    """A seed in ``SEED_RANGE``, or UsageError naming ``flag``."""
    if not (SEED_RANGE[0] <= seed <= SEED_RANGE[1]):
        raise UsageError(
            f"{flag} = {seed} is outside the allowed range [{SEED_RANGE[0]}, {SEED_RANGE[1]}]"
        )


def check_count(value: int, flag: str, high: int, low: int = 1) -> None:
    """A count in [low, high], or UsageError naming ``flag``."""
    if not (low <= value <= high):
        raise UsageError(f"{flag} = {value} is outside the allowed range [{low}, {high}]")


def _same_file(a: Path, b: Path) -> bool:
    try:
        return a.exists() and b.exists() and os.path.samefile(a, b)
    except (OSError, ValueError):
        return False


def _name_problem(path: Path) -> str | None:
    """What makes ``path`` unusable as a name on this system, or None."""
    text = os.fsencode(path)
    if b"\0" in text:
        return "holds a NUL character"
    if len(text) > PATH_MAX:
        return f"is {len(text)} bytes long; a path has at most {PATH_MAX}"
    longest = max((len(os.fsencode(part)) for part in path.parts), default=0)
    if longest > NAME_MAX:
        return f"has a name of {longest} bytes; a file name has at most {NAME_MAX}"
    return None


def _existing_ancestor(path: Path) -> Path:
    """The nearest of ``path`` and its parents that exists (``.`` for a relative path)."""
    current = path
    while not os.path.lexists(current):
        if current.parent == current:
            break
        current = current.parent
    return current


def _writable_problem(directory: Path) -> str | None:
    """Why nothing can be written in the existing directory ``directory``, or None: tried
    with an unnamed temporary file (removed at once), since permission bits do not tell
    ``/proc`` or a read-only mount from a writable directory, for root least of all."""
    try:
        with tempfile.TemporaryFile(dir=directory):
            pass
    except OSError as exc:
        return exc.strerror or type(exc).__name__
    return None


def check_out_dir(out: Path, flag: str = "--out", inputs: Iterable[Path] = ()) -> None:
    """UsageError naming ``flag`` unless ``out`` can be (or is) a directory we can write in:
    not an existing file (nor one of ``inputs``), a usable name, under a writable directory.
    Writes nothing."""
    where = f"{flag} '{shown(out)}'"
    problem = _name_problem(out)
    if problem:
        raise UsageError(f"{where} {problem}")
    for given in inputs:
        if _same_file(out, Path(given)):
            raise UsageError(f"{where} is the input file '{shown(given)}' itself; give a directory")
    if os.path.lexists(out) and not out.is_dir():
        raise UsageError(f"{where} is an existing file, not a directory; give a directory")
    base = _existing_ancestor(out)
    if not base.is_dir():
        raise UsageError(f"{where}: '{shown(base)}' is a file, not a directory")
    problem = _writable_problem(base)
    if problem:
        raise UsageError(f"{where}: cannot write in '{shown(base)}': {problem}")


def out_dir(out: Path | None, flag: str = "--out", inputs: Iterable[Path] = ()) -> Path | None:
    """``--out`` checked (:func:`check_out_dir`) and made with its parents, if given."""
    if out is None:
        return None
    check_out_dir(out, flag, inputs)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        reason = os.strerror(exc.errno) if exc.errno else str(exc)
        raise UsageError(f"{flag}: cannot create directory '{shown(out)}': {reason}") from None
    return out


def out_file(path: Path, flag: str = "--out", inputs: Iterable[Path] = ()) -> Path:
    """A picture file to write: a suffix we draw (.png, .pdf, .svg), not a directory, not one
    of ``inputs``; its directory checked and made as :func:`out_dir`."""
    where = f"{flag} '{shown(path)}'"
    for given in inputs:
        if _same_file(path, Path(given)):
            raise UsageError(f"{where} is the input file '{shown(given)}' itself")
    if path.suffix.lower() not in PICTURE_SUFFIXES:
        raise UsageError(f"{where}: the file name must end in {', '.join(PICTURE_SUFFIXES)}")
    if path.is_dir():
        raise UsageError(f"{where} is a directory; give a file name")
    problem = _name_problem(path)
    if problem:
        raise UsageError(f"{where} {problem}")
    out_dir(path.parent, flag)
    return path
