"""Bad input from the user, and the checks every subcommand shares.

A subcommand raises :class:`UsageError` with one line naming the flag and its allowed range;
:func:`experiments.cli.entry.run` prints it as ``partfeeder COMMAND: error: ...`` and exits 2.
"""

from __future__ import annotations

from pathlib import Path

TIME_RANGE_S = (0.0, 3600.0)  # a budget or a simulated time: (0, 1 h]
SEED_RANGE = (1, 2**31 - 1)  # OMPL ignores seed 0


class UsageError(Exception):
    """Bad input from the user: printed as one line, exit status 2."""


def check_time(seconds: float, flag: str = "--time") -> None:
    """A time in (0, 3600] s, or UsageError naming ``flag``."""
    if not (TIME_RANGE_S[0] < seconds <= TIME_RANGE_S[1]):
        raise UsageError(f"{flag} = {seconds} is outside the allowed range (0, 3600] s")


def out_dir(out: Path | None) -> Path | None:
    """``--out`` made (with its parents) if given; UsageError if it cannot be."""
    if out is not None:
        try:
            out.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise UsageError(f"--out: cannot create directory '{out}': {exc.strerror}") from None
    return out
