"""What a feeder sees from one part to the next: the perturbations of a passive drop.

A design's verdict is a success probability over drops that differ the way real ones do
(issue 13): the part enters a little off the nominal pose and not quite at rest, the friction
coefficient varies from part to part, and the feeder itself is made to a tolerance. Each
perturbation is uniform in a stated half-range; a drop's draw is a function of the verdict's
seed and the drop's index only, so the same seed gives the same drops on any executor and in
any batching.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass

import numpy as np

from feeders.design import PARAMETER_NAMES, PHYSICAL_BOUNDS, DesignParameters
from feeders.fields import shown

LIMITS = {
    "position": (0.0, 0.5),
    "yaw": (0.0, 0.5),
    "speed": (0.0, 1.0),
    "friction": (0.0, 0.9),
    "tolerance": (0.0, 0.1),
}
"""Allowed half-ranges: position (length), yaw (rad), speed (length/s), friction (relative,
below 1 so mu stays >= 0) and tolerance (relative, per design parameter)."""


@dataclass(frozen=True)
class Perturbations:
    """Half-ranges of the uniform perturbations of one drop (the issue's defaults).

    ``position``: entry offset in x and y (length); ``yaw``: entry yaw offset (rad); ``speed``:
    entry velocity in x and y (length/s); ``friction``: relative change of mu (0.2: mu times
    a factor in [0.8, 1.2]); ``tolerance``: relative manufacturing error of each of the 12
    design parameters (0.01: +-1%).
    """

    position: float = 0.05
    yaw: float = 0.05
    speed: float = 0.05
    friction: float = 0.2
    tolerance: float = 0.01

    def __post_init__(self) -> None:
        for name, (low, high) in LIMITS.items():
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise ValueError(f"perturbations.{name} = {value!r} must be a number")
            try:
                finite = math.isfinite(value)
            except OverflowError:  # an int beyond 1.8e308
                finite = False
            if not finite:
                raise ValueError(
                    f"perturbations.{name} = {shown(value)} must be a finite number in "
                    f"[{low:g}, {high:g}]"
                )
            if not low <= value <= high:
                raise ValueError(
                    f"perturbations.{name} = {value!r} is outside the allowed range "
                    f"[{low:g}, {high:g}]"
                )

    @classmethod
    def none(cls) -> Perturbations:
        """No perturbation: every drop is the nominal one."""
        return cls(0.0, 0.0, 0.0, 0.0, 0.0)

    def to_dict(self) -> dict[str, float]:
        return asdict(self)


@dataclass(frozen=True)
class DropDraw:
    """One drop's perturbation: design factors (one per design parameter: 12 for the
    feeder), friction factor, and per entry orientation the offset (dx, dy, dyaw) and entry
    velocity (vx, vy)."""

    design_factors: tuple[float, ...]
    friction_factor: float
    entry_offsets: tuple[tuple[float, float, float], ...]
    entry_velocities: tuple[tuple[float, float], ...]


def draw(
    perturbations: Perturbations,
    seed: int,
    index: int,
    entries: int = 2,
    parameters: int = len(PARAMETER_NAMES),
) -> DropDraw:
    """The perturbation of drop ``index`` of a verdict with ``seed`` (``entries`` entry
    orientations share the toleranced feeder and the friction: one made feeder, one part
    batch, both entries), with a design factor for each of ``parameters`` design parameters
    (the 12-parameter feeder's by default; a device family's n,
    :mod:`experiments.drop.family_verdict`). The generator draws the factors first, one after
    another, so the first k factors of a draw are the same numbers for any ``parameters`` >= k;
    the friction and entry draws that follow them shift with ``parameters``."""
    if isinstance(parameters, bool) or not isinstance(parameters, int) or parameters < 0:
        raise ValueError(f"parameters = {parameters!r} must be a whole number >= 0")
    rng = np.random.default_rng([seed, index])
    p = perturbations
    factors = 1.0 + p.tolerance * rng.uniform(-1.0, 1.0, parameters)
    friction = 1.0 + p.friction * rng.uniform(-1.0, 1.0)
    offsets, velocities = [], []
    for _ in range(entries):
        dx, dy = p.position * rng.uniform(-1.0, 1.0, 2)
        dyaw = p.yaw * rng.uniform(-1.0, 1.0)
        vx, vy = p.speed * rng.uniform(-1.0, 1.0, 2)
        offsets.append((float(dx), float(dy), float(dyaw)))
        velocities.append((float(vx), float(vy)))
    return DropDraw(
        tuple(float(f) for f in factors), float(friction), tuple(offsets), tuple(velocities)
    )


def toleranced(design: DesignParameters, factors: tuple[float, ...]) -> DesignParameters:
    """The design as made: each parameter times its factor, kept within what can be built
    (``feeders.design.PHYSICAL_BOUNDS``)."""
    values = []
    for name, factor in zip(PARAMETER_NAMES, factors, strict=True):
        low, high = PHYSICAL_BOUNDS[name]
        values.append(min(high, max(low, getattr(design, name) * factor)))
    return DesignParameters.from_vector(values)


def toleranced_values(
    values: Sequence[float],
    factors: Sequence[float],
    low: Sequence[float] | None = None,
    high: Sequence[float] | None = None,
) -> tuple[float, ...]:
    """Parameter values as made: each value times its factor (a relative error, so a value of
    0 is made exactly), kept within ``[low, high]`` per value when they are given. A device
    family passes no bounds: its box is what a sweep samples, not what can be built, and its
    rules decide whether the made values build (a made device they refuse is a failed trial,
    :data:`experiments.drop.verdict.UNBUILDABLE`)."""
    if len(factors) != len(values):
        raise ValueError(f"{len(factors)} factors for {len(values)} values")
    made = [float(v) * float(f) for v, f in zip(values, factors, strict=True)]
    if low is not None:
        made = [max(lo, m) for lo, m in zip(low, made, strict=True)]
    if high is not None:
        made = [min(hi, m) for hi, m in zip(high, made, strict=True)]
    return tuple(made)
