"""One stress case as plain data: everything needed to run it again, and nothing else.

A case is a scene document (the schema of :mod:`feeders.scene_yaml`), the level that runs it,
the start state, the input (a velocity for the geometric and kinematic levels, a wrench for
the dynamic one), the step h and duration (s), the part's mass and moment of inertia and the
friction coefficient (overriding the scene's), and where it came from: the seed, its index
and its family and placement (names only; the rest is already in the numbers).

The scene's ``part:`` is the peg's keys or a composite part (issue 24: ``cup``, or the
``pieces`` / ``outline`` of :func:`feeders.composite_part.part_from_dict`), read as
:mod:`experiments.stress.parts` says; a composite part that cannot be built is refused when the
case is read, naming ``case.scene.part...``.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

from feeders.fields import FieldError

LEVEL_NAMES = ("geometric", "kinematic", "dynamic")


class CaseError(FieldError):
    """A case document that cannot be read; the message names the field."""


@dataclass(frozen=True)
class Case:
    """A stress case (see the module docstring); units: lengths of the scene, seconds,
    mass, mass length^2 (inertia about the centre of mass)."""

    seed: int
    index: int
    level: str
    family: str
    placement: str
    scene: dict[str, Any]
    state: tuple[float, ...]
    control: tuple[float, float, float]
    h: float
    duration: float
    mass: float
    inertia: float
    friction: float

    def to_dict(self) -> dict[str, Any]:
        """A YAML- and JSON-ready mapping (lists, not tuples) that :meth:`from_dict` reads back
        to an equal case."""
        data = asdict(self)
        data["state"], data["control"] = list(self.state), list(self.control)
        return data

    @classmethod
    def from_dict(cls, data: Any) -> Case:
        """The case of a mapping written by :meth:`to_dict`; a bad field is a
        :class:`CaseError` naming it and the allowed range."""
        if not isinstance(data, dict):
            raise CaseError("case: expected a mapping")
        names = set(cls.__dataclass_fields__)
        unknown, missing = sorted(set(data) - names), sorted(names - set(data))
        if unknown or missing:
            raise CaseError(f"case: unknown fields {unknown}, missing fields {missing}")
        level = data["level"]
        if level not in LEVEL_NAMES:
            raise CaseError(f"case.level = {level!r}; allowed: {', '.join(LEVEL_NAMES)}")
        if not isinstance(data["scene"], dict):
            raise CaseError("case.scene: expected a scene mapping")
        _check_part(data["scene"].get("part"))
        size = 3 if level == "geometric" else 6
        state = _numbers(data["state"], "state", size)
        control = _numbers(data["control"], "control", 3)
        return cls(
            seed=_integer(data["seed"], "seed"),
            index=_integer(data["index"], "index"),
            level=level,
            family=str(data["family"]),
            placement=str(data["placement"]),
            scene=data["scene"],
            state=state,
            control=control,  # type: ignore[arg-type]
            h=_positive(data["h"], "h", 1e-6, 0.1),
            duration=_positive(data["duration"], "duration", 1e-6, 3600.0),
            mass=_positive(data["mass"], "mass", 1e-9, 1e9),
            inertia=_positive(data["inertia"], "inertia", 1e-12, 1e12),
            friction=_positive(data["friction"], "friction", 0.0, 10.0),
        )


def _check_part(spec: Any) -> None:
    """A composite ``part:`` builds (the peg's keys are checked with the rest of the scene)."""
    from experiments.stress.parts import is_composite, read_part  # numpy, shapely: when read

    if is_composite(spec):
        try:
            read_part(spec)
        except FieldError as exc:
            raise CaseError(f"case.scene.{exc}") from None


def _integer(value: Any, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise CaseError(f"case.{name} = {value!r}: expected an integer >= 0")
    return value


def _number(value: Any, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise CaseError(f"case.{name} = {value!r}: expected a number")
    if not math.isfinite(value):
        raise CaseError(f"case.{name} = {value!r}: expected a finite number")
    return float(value)


def _numbers(value: Any, name: str, size: int) -> tuple[float, ...]:
    if not isinstance(value, (list, tuple)) or len(value) != size:
        raise CaseError(f"case.{name}: expected a list of {size} numbers")
    return tuple(_number(v, f"{name}[{i}]") for i, v in enumerate(value))


def _positive(value: Any, name: str, low: float, high: float) -> float:
    number = _number(value, name)
    if not low <= number <= high:
        raise CaseError(f"case.{name} = {number!r} is outside the allowed range [{low}, {high}]")
    return number
