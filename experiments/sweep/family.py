"""The device family a sweep designs (issue 24): where its file is, and the family as plain data.

A sweep config's optional ``family:`` names a device family (:mod:`feeders.device_family`): a
family packaged with partfeeder by name (``fig1``) or a YAML file, its path relative to the
config file's folder. The config keeps the file's absolute path and its text; the text is what
travels in every job (a Dask worker on another machine has no such file) and what the results
database stores, so a report rebuilds the family's devices from the database alone.
"""

from __future__ import annotations

import hashlib
import re
from importlib.resources import files
from pathlib import Path
from typing import Any

import yaml

from feeders.device_family import DeviceFamily, FamilyError, family_from_dict

PACKAGED_FOLDER = "families"  # feeders/families/<name>.yaml, package data of the wheel
# a parameter becomes a column of the results database's ``designs`` table, unquoted
COLUMN_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
# the column names the ``designs`` table already has (SQLite compares them without case)
TAKEN_COLUMNS = {"design_id", "holdout"}


def packaged_families() -> list[str]:
    """The names of the families packaged with partfeeder."""
    found = files("feeders").joinpath(PACKAGED_FOLDER).iterdir()
    return sorted(e.name[: -len(".yaml")] for e in found if e.name.endswith(".yaml"))


def family_file(given: str, base: Path) -> Path | None:
    """The family file ``given`` names: a file (relative to ``base``, the config's folder), or
    a family packaged under that name (``fig1`` or ``fig1.yaml``); None when it is neither."""
    path = Path(given).expanduser()
    path = path if path.is_absolute() else base / path
    if path.is_file():
        return path.resolve()
    name = given[: -len(".yaml")] if given.endswith(".yaml") else given
    if "/" not in given and name in packaged_families():
        return Path(str(files("feeders").joinpath(PACKAGED_FOLDER, f"{name}.yaml"))).resolve()
    return None


def family_of_text(text: str, name: str) -> DeviceFamily:
    """The family written in ``text`` (a family file's YAML), named ``name`` unless it names
    itself; :class:`FamilyError` naming the field."""
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        raise FamilyError(f"not valid YAML ({str(exc).splitlines()[0]})") from None
    return family_from_dict(data, name=name)


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


def family_record(family: DeviceFamily, text: str) -> dict[str, Any]:
    """What a results database stores of the family (plain data): its name, parameter names,
    box (``low``, ``high``), entry names in the file's order and the file's text."""
    low, high = family.bounds()
    return {
        "name": family.name,
        "parameters": list(family.vector_names),
        "low": [float(v) for v in low],
        "high": [float(v) for v in high],
        "entries": [name for name, _ in family.entries],
        "yaml": text,
    }


def text_digest(text: str) -> str:
    """A digest of a family file's text, for the sweep's results key."""
    return hashlib.sha256(text.encode()).hexdigest()[:16]
