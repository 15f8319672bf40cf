"""The bracketing search for one side of a margin: from the nominal value outward, steps
doubling until P(both) falls below the target or the box's edge is reached, then bisection
between the last value inside and the first outside to a stated resolution.

The estimator is injected (``evaluate(value) -> Estimate``), so the search is tested on a
synthetic success function with a known threshold. A value is *inside* when the estimated
P(both) = successes / planned drops is at least the target; an estimate whose drops stopped
early (it could no longer reach the target) counts as outside. The search assumes P(both)
falls once with distance from the nominal: a narrower dip between two of its points is not
seen (the doubling steps are the sampling of that assumption).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from experiments.proportions import wilson_interval

FIRST_STEP = 1 / 32  # the first step outward, as a fraction of the box's width
RESOLUTION = 1 / 128  # bisection stops when inside and outside are this close (box fraction)


def required(target: float, planned: int) -> int:
    """The fewest successes of ``planned`` trials whose estimate k / planned reaches
    ``target``."""
    return max(0, math.ceil(target * planned - 1e-9))


@dataclass(frozen=True)
class Estimate:
    """P(both) at one value: ``successes`` of ``drops`` trials made (each a drop from every
    entry), of ``planned``; fewer made than planned means it stopped once it could not reach
    the target."""

    value: float
    successes: int
    drops: int
    planned: int

    def inside(self, target: float) -> bool:
        return self.drops >= self.planned and self.successes >= required(target, self.planned)

    @property
    def interval(self) -> tuple[float, float]:
        """Wilson 95% interval of P(both) over the trials made."""
        return wilson_interval(self.successes, self.drops)

    def to_dict(self) -> dict:
        lo, hi = self.interval
        return {
            "value": self.value,
            "successes": self.successes,
            "drops": self.drops,
            "planned": self.planned,
            "p": self.successes / self.drops if self.drops else None,
            "interval": [lo, hi],
        }


@dataclass(frozen=True)
class Bracket:
    """One side of a margin: the last value found inside (``inside``, the margin's end), the
    first found outside (``outside``; None when the box's ``edge`` is inside: the margin
    reaches the edge), and every estimate the search made, in order."""

    nominal: float
    edge: float
    inside: Estimate
    outside: Estimate | None
    evaluations: tuple[Estimate, ...]
    resolution: float

    @property
    def limit(self) -> float:
        return self.inside.value

    @property
    def at_edge(self) -> bool:
        return self.outside is None

    @property
    def drops(self) -> int:
        return sum(e.drops for e in self.evaluations)

    def to_dict(self) -> dict:
        return {
            "limit": self.limit,
            "at_box_edge": self.at_edge,
            "edge": self.edge,
            "last_inside": self.inside.to_dict(),
            "first_outside": None if self.outside is None else self.outside.to_dict(),
            "evaluations": len(self.evaluations),
            "drops": self.drops,
            "resolution": self.resolution,
        }


def bracket(
    evaluate: Callable[[float], Estimate],
    nominal: Estimate,
    edge: float,
    width: float,
    target: float,
    first_step: float = FIRST_STEP,
    resolution: float = RESOLUTION,
) -> Bracket:
    """The side of the margin from ``nominal`` (an estimate inside) toward ``edge``:
    steps of ``first_step * width`` doubling, each clipped to the edge, then bisection until
    the last inside and first outside values are within ``resolution * width``. Every value
    evaluated lies between the nominal and the edge."""
    if not nominal.inside(target):
        raise ValueError(f"the nominal value {nominal.value:g} is not inside the margin")
    span = abs(edge - nominal.value)
    sign = 1.0 if edge >= nominal.value else -1.0
    tol = resolution * width
    made: list[Estimate] = []
    inside, outside = nominal, None
    step = first_step * width
    while span > 0.0:
        value = edge if step >= span else nominal.value + sign * step
        estimate = evaluate(value)
        made.append(estimate)
        if not estimate.inside(target):
            outside = estimate
            break
        inside = estimate
        if value == edge:
            break
        step *= 2.0
    while outside is not None and abs(outside.value - inside.value) > tol:
        estimate = evaluate(0.5 * (inside.value + outside.value))
        made.append(estimate)
        if estimate.inside(target):
            inside = estimate
        else:
            outside = estimate
    return Bracket(nominal.value, edge, inside, outside, tuple(made), tol)
