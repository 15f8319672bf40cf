"""A part on its own, named or read from a file (issue 39): what ``partfeeder part`` reports
and ``partfeeder family new`` builds a family around.

A part is given as a shipped part's name (:data:`SHIPPED_PARTS`: ``peg``, the paper's
two-density peg, :data:`feeders.part.DEFAULT_PEG`; ``cup``, :func:`feeders.cup.cup_part`) or
as a YAML file. The file is either a document with a ``part:`` field, read as a device
family's ``part:`` is (so a family or scene file serves too), or a part's own fields at the
top: ``outline`` and ``density``, ``pieces``, or the peg's ``length``, ``width``, ``mass``,
``heavy_fraction`` ([parts.md](../docs/parts.md)). The file's ``part:`` is kept as written
(:attr:`PartSource.spec`), so a family made for the part says ``part:`` in the user's words.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from feeders.composite_part import CompositePart, CompositePartError
from feeders.fields import FieldError, read_yaml, shown
from feeders.part import (
    DEFAULT_HEAVY_FRACTION,
    DEFAULT_LENGTH,
    DEFAULT_PEG,
    DEFAULT_WIDTH,
    Peg,
)
from feeders.part_shape import Part
from feeders.scene_yaml import COMPOSITE_KEYS, PEG_KEYS, environment_from_dict

# name: a family's ``part:`` that gives the shipped part
SHIPPED_PARTS: dict[str, Any] = {
    "peg": {
        "length": DEFAULT_LENGTH,
        "width": DEFAULT_WIDTH,
        "mass": DEFAULT_PEG.mass,
        "heavy_fraction": DEFAULT_HEAVY_FRACTION,
    },
    "cup": "cup",
}


class PartFileError(FieldError):
    """A part that cannot be named or read; the message names the file (or name) and field."""


@dataclass(frozen=True)
class PartSource:
    """A part and where it came from: ``name`` (the shipped name or the file's stem),
    ``part`` (built and checked) and ``spec`` (what a family's ``part:`` takes to give it)."""

    name: str
    part: Part
    spec: Any


def part_of_spec(spec: Any, where: str = "part") -> Part:
    """The part of a family's ``part:`` = ``spec``; PartFileError beginning with ``where``."""
    try:
        part = environment_from_dict({"part": spec}, composite=True)["part"]
    except FieldError as exc:
        raise PartFileError(f"{where}: {exc}") from None
    if isinstance(part, Peg):  # measured as its two halves: the light one must have mass
        try:
            CompositePart.from_peg(part)
        except CompositePartError as exc:
            raise PartFileError(
                f"{where}: a peg is measured as its two halves and its light half cannot be "
                f"one ({exc}): give part.heavy_fraction below 1"
            ) from None
    return part


def shipped_part(name: str) -> PartSource | None:
    """The part shipped as ``name`` (:data:`SHIPPED_PARTS`), or None."""
    if name not in SHIPPED_PARTS:
        return None
    return PartSource(name, part_of_spec(SHIPPED_PARTS[name], name), SHIPPED_PARTS[name])


def read_part_file(path: str | Path) -> PartSource:
    """The part of a YAML file: its ``part:`` field, or a part's fields at its top level."""
    path = Path(path)
    where = f"'{shown(path)}'"
    data = read_yaml(path, "part", PartFileError)
    if "part" in data:
        spec = data["part"]
        if spec is None:
            raise PartFileError(f"{where}: part: is empty; give a part (see docs/parts.md)")
    elif set(data) <= PEG_KEYS | COMPOSITE_KEYS:
        spec = data
    else:
        raise PartFileError(
            f"{where} has no part: field and is not a part's own fields; a part file holds "
            f"part: (as a family does) or {', '.join(sorted(COMPOSITE_KEYS | PEG_KEYS))}"
        )
    return PartSource(path.stem, part_of_spec(spec, where), spec)


def part_source(given: str | Path) -> PartSource:
    """The part ``given`` names: a file if one exists there, else a shipped part; else
    PartFileError naming it and listing the shipped parts."""
    path = Path(given)
    if path.exists() or path.parent != Path(".") or str(given).endswith((".yaml", ".yml")):
        return read_part_file(path)
    found = shipped_part(str(given))
    if found is None:
        raise PartFileError(
            f"part '{shown(given)}' is neither a file nor a shipped part; shipped parts: "
            f"{', '.join(SHIPPED_PARTS)} (or give a part YAML file, docs/parts.md)"
        )
    return found
