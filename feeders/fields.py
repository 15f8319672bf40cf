"""Fields of parsed YAML documents (scenes, experiment configs), read with errors that name
the field and its allowed range, so a user can fix the file without reading our code."""

from __future__ import annotations

import math
from typing import Any


class FieldError(ValueError):
    """A field of a document that is missing, of the wrong type or out of range."""


def number_field(value: Any, field: str, low: float = -math.inf, high: float = math.inf) -> float:
    """``value`` as a finite float in [low, high]."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise FieldError(f"{field}: expected a number, got {value!r}")
    value = float(value)
    if not (math.isfinite(value) and low <= value <= high):
        raise FieldError(f"{field} = {value!r} is outside the allowed range [{low:g}, {high:g}]")
    return value


def integer_field(value: Any, field: str, low: int, high: int) -> int:
    """``value`` as an int in [low, high] (a float such as 3.0 is not accepted)."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise FieldError(f"{field}: expected an integer, got {value!r}")
    if not (low <= value <= high):
        raise FieldError(f"{field} = {value!r} is outside the allowed range [{low}, {high}]")
    return int(value)


def numbers_field(value: Any, field: str, count: int) -> list[float]:
    """``value`` as a list of ``count`` finite floats."""
    if not isinstance(value, (list, tuple)) or len(value) != count:
        raise FieldError(f"{field}: expected a list of {count} numbers, got {value!r}")
    return [number_field(v, f"{field}[{i}]") for i, v in enumerate(value)]


def mapping_field(value: Any, field: str, allowed: set[str]) -> dict[str, Any]:
    """``value`` as a mapping whose keys are all in ``allowed``."""
    if not isinstance(value, dict):
        raise FieldError(f"{field}: expected a mapping, got {value!r}")
    unknown = sorted(set(value) - allowed)
    if unknown:
        raise FieldError(f"{field}: unknown key(s) {unknown}; allowed: {sorted(allowed)}")
    return value
