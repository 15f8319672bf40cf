"""What the sweep asks of a device family beyond reading it (issue 24): its parameters become
the results database's ``designs`` columns, and the database keeps the family's text, from
which a report rebuilds the family (:func:`database_family`). Reading a config's ``family:``
is shared by the jobs: :mod:`experiments.family_config`.
"""

from __future__ import annotations

from contextlib import closing
from pathlib import Path

from experiments.family_config import family_of_text
from experiments.sweep.results_db import connect, stored_family
from feeders.device_family import DeviceFamily
from feeders.fields import shown

# the column names the ``designs`` table already has (SQLite compares them without case)
TAKEN_COLUMNS = {"design_id", "holdout"}
# the experiment properties a sweep's job adds to OMPL's log beside the parameters
# (experiments.sweep.job): a parameter of that name would be overwritten
JOB_PROPERTIES = {"design_id", "level", "seed"}


def column_problem(family: DeviceFamily) -> str | None:
    """Why the family's parameter names cannot be columns, or None. A parameter becomes a
    column of the results database's ``designs`` table and an experiment property of OMPL's
    log, which OMPL's reader adds as a column without quoting: each name must pass
    :func:`planners.sql_names.column_name_problem` (a plain identifier, not an SQL keyword,
    not a column of OMPL's experiments table) and not be one of the sweep's own columns and
    properties, in any case; no two may differ only in case (SQLite's column names do not)."""
    from planners.sql_names import RULE, column_name_problem

    names = family.vector_names
    own = sorted(TAKEN_COLUMNS | JOB_PROPERTIES)
    for name in names:
        problem = column_name_problem(name)
        if problem is None and name.lower() in own:
            problem = "a column the sweep writes itself"
        if problem is not None:
            return (
                f"parameters.{shown(name)}: {problem}; a swept family's parameter becomes a "
                f"column of the results database and of OMPL's: allowed: {RULE}, other than "
                f"{', '.join(own)}"
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
