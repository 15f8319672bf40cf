"""Fields of parsed YAML documents (scenes, experiment configs), read with errors that name
the field and its allowed range, so a user can fix the file without reading our code."""

from __future__ import annotations

import math
import stat
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


MAX_DOCUMENT_BYTES = 1 << 20  # a scene or config is a few kilobytes; 1 MiB is generous
MAX_DEPTH = 32  # nesting of mappings and lists (a scene needs 4)


class _BoundedLoader(yaml.SafeLoader):
    """``yaml.safe_load``'s loader that refuses aliases (``*name``: a 322-byte "billion laughs"
    document expands to gigabytes) and nesting deeper than ``MAX_DEPTH`` (Python's recursion
    limit otherwise ends it in a RecursionError). A scene or config never needs either."""

    def __init__(self, stream: str) -> None:
        super().__init__(stream)
        self._depth = 0

    def compose_node(self, parent: Any, index: Any) -> Any:
        if self.check_event(yaml.AliasEvent):
            event = self.peek_event()
            raise yaml.composer.ComposerError(
                None, None, "aliases (*name) are not allowed", event.start_mark
            )
        self._depth += 1
        try:
            if self._depth > MAX_DEPTH:
                raise yaml.composer.ComposerError(
                    None,
                    None,
                    f"nested deeper than {MAX_DEPTH} levels",
                    self.peek_event().start_mark,
                )
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1


def _read_text(path: Path, kind: str, error: type[FieldError]) -> str:
    """The UTF-8 text of a regular file of at most ``MAX_DOCUMENT_BYTES``, without blocking
    on a FIFO or reading a device forever."""
    try:
        info = path.stat()
    except OSError as exc:
        raise error(f"cannot read {kind} file '{path}': {exc.strerror}") from None
    if not stat.S_ISREG(info.st_mode):
        raise error(f"{kind} file '{path}' is not a regular file")
    if info.st_size > MAX_DOCUMENT_BYTES:
        raise error(
            f"{kind} file '{path}' is {info.st_size} bytes; the limit is {MAX_DOCUMENT_BYTES}"
        )
    try:
        with path.open("rb") as handle:
            raw = handle.read(MAX_DOCUMENT_BYTES + 1)
    except OSError as exc:
        raise error(f"cannot read {kind} file '{path}': {exc.strerror}") from None
    if len(raw) > MAX_DOCUMENT_BYTES:
        raise error(f"{kind} file '{path}' is larger than the limit of {MAX_DOCUMENT_BYTES} bytes")
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise error(
            f"{kind} file '{path}' is not UTF-8 text (byte {exc.start}: {raw[exc.start]:#04x})"
        ) from None


def parse_yaml(text: str) -> Any:
    """The YAML document in ``text``: ``yaml.safe_load`` with aliases refused and nesting
    bounded (:class:`_BoundedLoader`); raises ``yaml.YAMLError``."""
    loader = _BoundedLoader(text)
    try:
        return loader.get_single_data()
    finally:
        loader.dispose()


def read_yaml(path: Path, kind: str, error: type[FieldError]) -> Any:
    """The document in the YAML file ``path`` (``yaml.safe_load``, bounded: a regular UTF-8
    file of at most ``MAX_DOCUMENT_BYTES``, no aliases, at most ``MAX_DEPTH`` levels); a file
    that cannot be read or parsed raises ``error`` naming the file (``kind``: what it is)."""
    text = _read_text(Path(path), kind, error)
    try:
        return parse_yaml(text)
    except yaml.YAMLError as exc:
        raise error(f"'{path}' is not valid YAML: {_yaml_problem(exc)}") from None
