"""Fields of parsed YAML documents (scenes, experiment configs), read with errors that name
the field and its allowed range, so a user can fix the file without reading our code."""

from __future__ import annotations

import math
import re
import reprlib
import stat
import unicodedata
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import yaml

MAX_SHOWN = 120  # longest path or value quoted whole in a message (characters)
MAX_NAME = 100  # characters of a scene's or config's name (it becomes part of file names)


def shown(text: object) -> str:
    """``text`` for a one-line message: whole when short, else its ends and its length (a
    5,000-character path or name must not make the error unreadable)."""
    text = str(text)
    if len(text) <= MAX_SHOWN:
        return text
    return f"{text[:50]}...{text[-50:]} ({len(text)} characters)"


class _BoundedRepr(reprlib.Repr):
    """``repr`` that stops early: a value from a document (an alias-expanded list of millions
    of items, a 4,000-digit integer) is never turned into a whole string to be shortened."""

    def __init__(self) -> None:
        super().__init__()
        self.maxlevel, self.maxlist, self.maxtuple, self.maxdict, self.maxset = 3, 8, 8, 8, 8
        self.maxstring, self.maxother, self.maxlong = 200, 200, 80

    def repr_int(self, x: int, level: int) -> str:
        if x.bit_length() > 256:  # converting it whole is slow (and refused past 4,300 digits)
            return f"<an integer of {x.bit_length()} bits>"
        return super().repr_int(x, level)


_REPR = _BoundedRepr()


def shown_value(value: object) -> str:
    """``value``'s repr for a one-line message, bounded whatever the value (at most a few
    hundred characters, built without the whole repr)."""
    return shown(_REPR.repr(value))


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
        raise FieldError(f"{field}: expected a number, got {shown_value(value)}")
    try:
        number = float(value)
    except OverflowError:  # an int beyond 1.8e308
        number = math.inf if value > 0 else -math.inf
    if not (math.isfinite(number) and low <= number <= high):
        raise FieldError(f"{field} = {number!r} is outside the allowed range [{low:g}, {high:g}]")
    return number


def integer_field(value: Any, field: str, low: int, high: int) -> int:
    """``value`` as an int in [low, high] (a float such as 3.0 is not accepted)."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise FieldError(f"{field}: expected an integer, got {shown_value(value)}")
    if not (low <= value <= high):
        raise FieldError(f"{field} = {shown(value)} is outside the allowed range [{low}, {high}]")
    return int(value)


def numbers_field(value: Any, field: str, count: int) -> list[float]:
    """``value`` as a list of ``count`` finite floats."""
    if not isinstance(value, (list, tuple)) or len(value) != count:
        raise FieldError(f"{field}: expected a list of {count} numbers, got {shown_value(value)}")
    return [number_field(v, f"{field}[{i}]") for i, v in enumerate(value)]


def _breaks_lines(c: str) -> bool:
    """A control character (C0, DEL, C1 such as U+0085) or a Unicode line or paragraph
    separator: readers that split text into lines (OMPL's log reader) split on them."""
    return unicodedata.category(c) in ("Cc", "Zl", "Zp")


def name_field(value: Any, field: str = "name") -> str:
    """``value`` as a name that can be part of a file name: a string of 1 to ``MAX_NAME``
    characters, without '/', control characters or line separators, not '.' or '..', and
    without white space at either end (refused, not stripped: the name a user wrote is the
    name of the sweep's directory and of OMPL's experiment)."""
    if not isinstance(value, (str, int, float)) or isinstance(value, bool):
        raise FieldError(f"{field}: expected a string, got {shown_value(value)}")
    name = str(value)
    if not 1 <= len(name) <= MAX_NAME:
        raise FieldError(f"{field}: {len(name)} characters; a name has 1 to {MAX_NAME} characters")
    if "/" in name or name in (".", "..") or any(_breaks_lines(c) for c in name):
        raise FieldError(
            f"{field} = {shown_value(name)}: a name cannot hold '/', control characters or line "
            "separators, or be '.' or '..'"
        )
    if name != name.strip():  # OMPL's log reader strips it: the name would change on its way
        raise FieldError(
            f"{field} = {shown(repr(name))}: a name cannot begin or end with white space"
        )
    return name


# the fields that are a whole document (a config, a family, a scene, a stress case): a file
# of which not one key is allowed is of another kind, and its keys are not echoed
DOCUMENT_FIELDS = frozenset({"config", "family", "scene", "stress case"})
MAX_UNKNOWN_SHOWN = 5  # unknown keys named in a message


def mapping_field(value: Any, field: str, allowed: set[str]) -> dict[str, Any]:
    """``value`` as a mapping whose keys are all in ``allowed``."""
    if not isinstance(value, dict):
        raise FieldError(f"{field}: expected a mapping, got {shown_value(value)}")
    unknown = sorted(map(str, set(value) - allowed))
    if unknown and len(unknown) == len(value) and field in DOCUMENT_FIELDS:
        # not one field of the kind: another kind of file (credentials, another program's
        # settings), whose keys are its content: named, never quoted (issue 37)
        raise FieldError(
            f"{field}: none of its {len(value)} keys is a field of a {field} (not quoted: is "
            f"this the right file?); allowed: {sorted(allowed)}"
        )
    if unknown:
        named = [shown_value(key) for key in unknown[:MAX_UNKNOWN_SHOWN]]
        more = f" and {len(unknown) - len(named)} more" if len(unknown) > len(named) else ""
        raise FieldError(
            f"{field}: unknown key(s) [{', '.join(named)}]{more}; allowed: {sorted(allowed)}"
        )
    return value


# What PyYAML's pure-Python parser quotes of the file in a problem ("found character '\\t'",
# "found undefined tag handle '!x!'", "but found '#'"): the file may be any text at all.
_QUOTED = re.compile(r" ?'[^']*'")


def _yaml_problem(exc: yaml.YAMLError) -> str:
    """PyYAML's error on one line: the problem and where it is (line and column), without
    anything it quotes of the file (issue 23: /etc/shadow as a config had its text in the
    error). A reader error (a character YAML refuses) says where by position."""
    problem = getattr(exc, "problem", None)
    mark = getattr(exc, "problem_mark", None)
    if problem and mark is not None:
        return f"{_QUOTED.sub('', problem)} (line {mark.line + 1}, column {mark.column + 1})"
    first = _QUOTED.sub("", str(exc).splitlines()[0]) if str(exc) else type(exc).__name__
    if isinstance(exc, yaml.reader.ReaderError):  # no line: where is the character's index
        return f"{first} (character {exc.position + 1})"
    return first


MAX_DOCUMENT_BYTES = 1 << 20  # a scene or config is a few kilobytes; 1 MiB is generous
MAX_DEPTH = 32  # nesting of mappings and lists (a scene needs 4)
MAX_NODES = 100_000  # scalars, lists and mappings (a 1,000-point polygon is 3,001)
# libyaml's parser when PyYAML was built with it: 10-50 times faster than the pure-Python one,
# which takes ~20 s on a 800 kB list of numbers (within the byte limit, but a hang to a user).
_FAST = yaml.__with_libyaml__
_PARSER: Any = yaml.CSafeLoader if _FAST else yaml.SafeLoader


# Plain scalars YAML 1.1 reads as numbers a reader would not expect: base 60 (1:30 is 90) and
# a leading zero (017 is 15, octal).
_SEXAGESIMAL = re.compile(r"[-+]?[0-9][0-9_]*(:[0-5]?[0-9])+(\.[0-9_]*)?")
_LEADING_ZERO = re.compile(r"[-+]?0[0-9_]+")


def _scalar_problem(event: yaml.ScalarEvent) -> str | None:
    """Why a scalar is refused: an explicit tag, or a plain YAML 1.1 number that surprises;
    said without quoting the scalar (the file may be any text: its line and column say where)."""
    if event.tag is not None and event.tag != "!":
        return "an explicit tag (!...) is not allowed"
    if not event.style:  # plain (None or '', by parser)
        if _SEXAGESIMAL.fullmatch(event.value):
            return "a number with colons is sexagesimal (base 60) in YAML 1.1; quote it"
        if _LEADING_ZERO.fullmatch(event.value):
            return "a number with a leading zero is octal in YAML 1.1; drop the zero or quote it"
    return None


def _check_events(text: str) -> None:
    """Walk the document's parse events (no objects are built) and raise
    ``yaml.composer.ComposerError`` at the first alias (``*name``: a 322-byte "billion laughs"
    document expands to gigabytes), nesting deeper than ``MAX_DEPTH`` (Python's recursion limit
    ends it in a RecursionError), node beyond ``MAX_NODES`` (construction time), repeated key
    in one mapping (the last would silently win), explicit tag (``!!float`` made a name a
    number) or plain number that YAML 1.1 reads in base 60 or 8. A scene or config never needs
    any of them."""
    depth = nodes = 0
    mappings: list[tuple[set, list[bool]] | None] = []  # per open node: keys seen, at a key
    for event in yaml.parse(text, Loader=_PARSER):
        problem = None
        node = isinstance(
            event, (yaml.ScalarEvent, yaml.MappingStartEvent, yaml.SequenceStartEvent)
        )
        if node and mappings and mappings[-1] is not None:
            keys, at_key = mappings[-1]
            if at_key[0] and isinstance(event, yaml.ScalarEvent):
                if event.value in keys:
                    problem = "a repeated key (the same key twice in one mapping)"
                elif event.value == "<<" and not event.style:
                    problem = "a merge key (<<) is not allowed; write the keys out"
                keys.add(event.value)
            at_key[0] = not at_key[0]
        if isinstance(event, yaml.AliasEvent):
            problem = "aliases (*name) are not allowed"
        elif isinstance(event, (yaml.MappingStartEvent, yaml.SequenceStartEvent)):
            depth += 1
            nodes += 1
            if depth > MAX_DEPTH:
                problem = f"nested deeper than {MAX_DEPTH} levels"
            elif event.tag is not None and problem is None:
                problem = "an explicit tag (!...) is not allowed"
            is_map = isinstance(event, yaml.MappingStartEvent)
            mappings.append((set(), [True]) if is_map else None)
        elif isinstance(event, (yaml.MappingEndEvent, yaml.SequenceEndEvent)):
            depth -= 1
            mappings.pop()
        elif isinstance(event, yaml.ScalarEvent):
            nodes += 1
            problem = problem or _scalar_problem(event)
        if nodes > MAX_NODES and problem is None:
            problem = f"more than {MAX_NODES} values"
        if problem is not None:
            raise yaml.composer.ComposerError(None, None, problem, event.start_mark)


def read_text(path: Path, kind: str, error: type[FieldError]) -> str:
    """The UTF-8 text of a regular file of at most ``MAX_DOCUMENT_BYTES``, without blocking
    on a FIFO or reading a device forever."""
    try:
        info = path.stat()
    except OSError as exc:
        raise error(f"cannot read {kind} file '{shown(path)}': {exc.strerror}") from None
    if not stat.S_ISREG(info.st_mode):
        raise error(f"{kind} file '{shown(path)}' is not a regular file")
    if info.st_size > MAX_DOCUMENT_BYTES:
        raise error(
            f"{kind} file '{shown(path)}' is {info.st_size} bytes; "
            f"the limit is {MAX_DOCUMENT_BYTES}"
        )
    try:
        with path.open("rb") as handle:
            raw = handle.read(MAX_DOCUMENT_BYTES + 1)
    except OSError as exc:
        raise error(f"cannot read {kind} file '{shown(path)}': {exc.strerror}") from None
    if len(raw) > MAX_DOCUMENT_BYTES:
        raise error(
            f"{kind} file '{shown(path)}' is larger than the limit of {MAX_DOCUMENT_BYTES} bytes"
        )
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise error(
            f"{kind} file '{shown(path)}' is not UTF-8 text "
            f"(byte {exc.start}: {raw[exc.start]:#04x})"
        ) from None


def parse_yaml(text: str) -> Any:
    """The YAML document in ``text``: ``yaml.safe_load``'s result, with aliases refused and
    nesting and size bounded (:func:`_check_events`) before any object is built; raises
    ``yaml.YAMLError``, or ValueError for an integer of more than 4,300 digits (Python's
    limit on converting text to int)."""
    _check_events(text)
    return yaml.load(text, Loader=_PARSER)  # a safe loader


def parse_document(text: str, where: str, error: type[FieldError]) -> Any:
    """:func:`parse_yaml` of ``text`` (a file's, or a text a database keeps), any problem
    raised as ``error`` on one line beginning with ``where``, never quoting the text."""
    try:
        return parse_yaml(text)
    except yaml.YAMLError as exc:
        raise error(f"{where} is not valid YAML: {_yaml_problem(exc)}") from None
    except ValueError as exc:  # an integer too long to convert
        raise error(f"{where}: {str(exc).split(';')[0]}") from None
    except RecursionError:  # nesting is bounded before any object is built; kept as a guard
        raise error(f"{where} is nested too deep (at most {MAX_DEPTH} levels)") from None


def read_yaml(path: Path, kind: str, error: type[FieldError]) -> Any:
    """The document in the YAML file ``path`` (``yaml.safe_load``, bounded: a regular UTF-8
    file of at most ``MAX_DOCUMENT_BYTES``, no aliases, at most ``MAX_DEPTH`` levels), a
    mapping; a file that cannot be read or parsed, or whose document is not a mapping, raises
    ``error`` naming the file (``kind``: what it is), never quoting its content."""
    text = read_text(Path(path), kind, error)
    document = parse_document(text, f"'{shown(path)}'", error)
    if not isinstance(document, dict):  # named, never echoed: it may be any file at all
        what = {str: "text", list: "a list", type(None): "empty"}.get(type(document), "a number")
        raise error(
            f"'{shown(path)}' is not a {kind}: a {kind} is a YAML mapping of fields "
            f"(name: value), and this file's document is {what}"
        )
    return document
