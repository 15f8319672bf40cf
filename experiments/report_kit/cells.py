"""The text of a report's table cells: a number formatted, a dash when it is unknown.

A report shows whatever a summary holds, including a sweep still running: a missing value,
NaN or an infinity is a dash, never an error or the text "nan".
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

DASH = "–"


def number(value: Any) -> float | None:
    """A finite float, or None for None, NaN, infinities and anything not a number."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def cell(value: Any, spec: str = ".3g") -> str:
    """A table cell's text: integers as they are, floats by ``spec``, a dash when unknown."""
    if value is None:
        return DASH
    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    x = number(value)
    if x is None:
        return DASH if isinstance(value, float) else str(value)
    return format(x, spec)


UNKNOWN = "n/a"  # an unknown quantity in a sentence (a table's cell shows DASH)


def quantity(value: Any, unit: str, spec: str = ".3g") -> str:
    """A number with its unit for a sentence ("1.25 s"), or ``n/a`` alone when it is unknown
    (a mean exit time of an entry with no successful drop): never a unit after a dash."""
    text = cell(value, spec)
    return UNKNOWN if text == DASH else f"{text} {unit}"


def interval(ci: Any, spec: str = ".2f") -> str:
    """A confidence interval ``[low, high]`` by ``spec``; a dash unless both ends are numbers."""
    if not isinstance(ci, (list, tuple)) or len(ci) != 2:
        return DASH
    low, high = number(ci[0]), number(ci[1])
    if low is None or high is None:
        return DASH
    return f"[{format(low, spec)}, {format(high, spec)}]"
