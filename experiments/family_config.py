"""A config's device family (issue 24): where its file is, and the family as plain data.

A job's config (the sweep's, the optimiser's) may name a device family
(:mod:`feeders.device_family`) with ``family:``: a family packaged with partfeeder by name
(``fig1``) or a YAML file, its path relative to the config file's folder. The config keeps the
file's absolute path and its text; the text is what travels in every job (a Dask worker on
another machine has no such file) and what a job's database stores, so a report rebuilds the
family's devices from the database alone. Shared by the jobs: a job never imports a sibling
job's internals.
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Any

from feeders.device_family import (
    DeviceFamily,
    FamilyError,
    family_from_dict,
    packaged_families,
    packaged_family,
)
from feeders.fields import (
    MAX_DOCUMENT_BYTES,
    FieldError,
    parse_document,
    read_text,
    shown,
    shown_value,
)

FAMILY_DEFAULT = "default"  # a family's default design by name: a baseline, an optimiser's start


def family_file(given: str, base: Path) -> Path | None:
    """The family file ``given`` names: a file (relative to ``base``, the config's folder), or
    a family packaged under that name (``fig1`` or ``fig1.yaml``,
    :func:`feeders.device_family.packaged_family`); None when it is neither."""
    path = Path(given).expanduser()
    path = path if path.is_absolute() else base / path
    if path.is_file():
        return path.resolve()
    packaged = None if "/" in given else packaged_family(given)
    return packaged.resolve() if packaged is not None else None


def family_of_text(text: str, name: str) -> DeviceFamily:
    """The family written in ``text`` (a family file's YAML), named ``name`` unless it names
    itself; :class:`FamilyError` naming the field. Read by the one bounded reader
    (:func:`feeders.fields.parse_document`: size, depth, aliases, tags, repeated and merge
    keys, YAML 1.1's octal and base 60), as a family file is: the text may come from a
    results database anyone could have written."""
    if len(text.encode("utf-8", "surrogatepass")) > MAX_DOCUMENT_BYTES:
        raise FamilyError(
            f"the family's text is larger than the limit of {MAX_DOCUMENT_BYTES} bytes"
        )
    data = parse_document(text, "the family's text", FamilyError)
    return family_from_dict(data, name=name)


def read_family_field(
    value: Any, base: Path, error: type[FieldError]
) -> tuple[str, str, DeviceFamily]:
    """A config's ``family`` field: the family file's absolute path, its text and the family
    (checked: it reads and builds its default). ``error`` (the config's own error class) is
    raised with one line naming the field and what is allowed."""
    if not isinstance(value, str) or not value:
        raise error(
            f"family = {shown_value(value)}; allowed: a packaged family's name "
            f"({', '.join(packaged_families())}) or a family file"
        )
    path = family_file(value, base)
    if path is None:
        raise error(
            f"family = '{shown(value)}' is neither a file (relative to {shown(base)}) nor a "
            f"packaged family; packaged families: {', '.join(packaged_families())}"
        )
    text = read_text(path, "device family", error)  # bounded: size, regular file, UTF-8
    try:
        family = family_of_text(text, path.stem)
    except FamilyError as exc:
        raise error(f"family: {shown(path)}: {exc}") from None
    return str(path), text, family


def family_default(family: DeviceFamily) -> tuple[str, list[float]]:
    """``(FAMILY_DEFAULT, the family's default vector)``: what a job compares a family's
    designs with unless given another baseline (the paper's feeder's is table3)."""
    return FAMILY_DEFAULT, [float(v) for v in family.default()]


def family_record(family: DeviceFamily, text: str) -> dict[str, Any]:
    """What a job's database stores of the family (plain data): its name, parameter names,
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
    """A digest of a family file's text, for a job's results key."""
    return hashlib.sha256(text.encode()).hexdigest()[:16]
