"""What the sweep asks of a device family beyond reading it (issue 24): its parameters become
the results database's ``designs`` columns, and the database keeps the family's text, from
which a report rebuilds the family (:func:`database_family`). Reading a config's ``family:``
is shared by the jobs: :mod:`experiments.family_config`.
"""

from __future__ import annotations

import re
from contextlib import closing
from pathlib import Path

from experiments.family_config import family_of_text
from experiments.sweep.results_db import connect, stored_family
from feeders.device_family import DeviceFamily

# a parameter becomes a column of the results database's ``designs`` table, unquoted
COLUMN_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
# the column names the ``designs`` table already has (SQLite compares them without case)
TAKEN_COLUMNS = {"design_id", "holdout"}


def column_problem(family: DeviceFamily) -> str | None:
    """Why the family's parameter names cannot be the ``designs`` table's columns, or None:
    each must be an identifier (letters, digits, '_') other than ``design_id`` and
    ``holdout``, and no two may differ only in case (SQLite's column names do not)."""
    names = family.vector_names
    for name in names:
        if not COLUMN_NAME.fullmatch(name) or name.lower() in TAKEN_COLUMNS:
            return (
                f"parameter '{name}' cannot name a results column; allowed: letters, digits "
                f"and '_', not starting with a digit, other than {', '.join(sorted(TAKEN_COLUMNS))}"
            )
    lowered = [n.lower() for n in names]
    if len(set(lowered)) != len(lowered):
        return f"parameters {list(names)} differ only in case; results columns must not"
    return None


def database_family(db_path: str | Path) -> tuple[DeviceFamily, str] | None:
    """The device family the sweep at ``db_path`` designs and its file's text, rebuilt from
    what its database keeps (:func:`experiments.sweep.results_db.stored_family`); None: the
    12-parameter feeder. Read-only, so a running sweep is not disturbed."""
    with closing(connect(db_path, readonly=True)) as db:
        record = stored_family(db)
    if record is None:
        return None
    return family_of_text(record["yaml"], record["name"]), str(record["yaml"])
