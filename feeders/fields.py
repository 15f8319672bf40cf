"""Fields of parsed YAML documents (scenes, experiment configs), read with errors that name
the field and its allowed range, so a user can fix the file without reading our code."""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import yaml


class FieldError(ValueError):
    """A field of a document that is missing, of the wrong type or out of range."""


@contextmanager
def field_errors_as(error: type[FieldError]) -> Iterator[None]:
    """Inside, a :class:`FieldError` of another kind is raised as ``error`` (same message), so
    a document's reader raises its own error type whichever helper found the problem."""
    try:
        yield
    except error:
        raise
    except FieldError as exc:
        raise error(str(exc)) from None


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


def _yaml_problem(exc: yaml.YAMLError) -> str:
    """PyYAML's error on one line: the problem and where it is."""
    problem = getattr(exc, "problem", None)
    mark = getattr(exc, "problem_mark", None)
    if problem and mark is not None:
        return f"{problem} (line {mark.line + 1}, column {mark.column + 1})"
    return str(exc).splitlines()[0] if str(exc) else type(exc).__name__


def read_yaml(path: Path, kind: str, error: type[FieldError]) -> Any:
    """The document in the YAML file ``path`` (``yaml.safe_load``); a file that cannot be read
    or parsed raises ``error`` naming the file (``kind``: what it is, for the message)."""
    try:
        text = path.read_text()
    except OSError as exc:
        raise error(f"cannot read {kind} file '{path}': {exc.strerror}") from None
    try:
        return yaml.safe_load(text)
    except yaml.YAMLError as exc:
        raise error(f"'{path}' is not valid YAML: {_yaml_problem(exc)}") from None
