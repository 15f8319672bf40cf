"""Design centering for the robust objective (issue 34): maximise a design's robustness (its
smallest normalised margin, :func:`experiments.margins.robustness.robustness`) subject to the
verdict's reliability target, Eq. 10's exit time only breaking ties.

The method is the one-axis form of design centering (Director and Hachtel 1977): the margins
of a design are line searches from its nominal along each axis, and they bound the region
where the design works. Each step moves every design parameter toward the centre of its
allowed interval (a side that reached the box's edge counts as ending there), damped by a
step factor: ``x + step * (centre - x)``. A move is accepted only when the new design works
(its margins' verdict at the target) and is more robust (its robustness value larger, or
equal with a shorter mean exit time); a rejected move halves the step. Optionally, after a
rejected centering move, ``explore`` seeded random moves of ``spread * step`` of each box
are tried before the step is halved (a centring step along the axes cannot widen an interval
that depends on another parameter; a random direction sometimes can).

The run stops when it has made ``budget`` margins evaluations (a count, not a time), when
the step falls below ``min_step``, or when a move would change nothing. Every evaluation is
a call of ``measure(values) -> margins dict``: the optimiser stores them by design and
settings, so a stopped run started again replays the same moves from the store (the random
moves are seeded by ``seed`` and the evaluation's index).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from experiments.margins.robustness import SIDES, Robustness, at_edge, robustness, room

Measure = Callable[[list[float]], Mapping[str, Any]]


@dataclass(frozen=True)
class CenteringSettings:
    """``budget`` margins evaluations in all (the starts' included), ``step`` the first
    damping factor (1: straight to the centre), halved on each rejected move down to
    ``min_step``; ``explore`` random moves tried after a rejected centring move, each of
    ``spread`` times the step of every parameter's box, seeded by ``seed``; ``starts``: how
    many of the best starts get a chain each (the budget split between them); ``drops``:
    trials per value of the margins; ``focus`` > 0: only the parameters with a side whose
    room is within ``focus`` times the robustness move (the bottlenecks: moving every
    parameter at once to its one-axis centre ignores how they interact; measured on table3,
    such a move at step 0.7 left a design that does not work)."""

    budget: int = 12
    step: float = 0.7
    min_step: float = 0.1
    explore: int = 0
    spread: float = 0.1
    seed: int = 0
    starts: int = 1
    drops: int = 20
    focus: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        return {
            "budget": self.budget,
            "step": self.step,
            "min_step": self.min_step,
            "explore": self.explore,
            "spread": self.spread,
            "seed": self.seed,
            "starts": self.starts,
            "drops": self.drops,
            "focus": self.focus,
        }


def mean_exit_time(margins: Mapping[str, Any]) -> float:
    """The mean over the entries of the margins' verdict's mean exit time (s); inf when it
    has none (the tie-break: shorter is better)."""
    per = ((margins.get("verdict") or {}).get("orientations") or {}).values()
    times = [p.get("mean_exit_time_s") for p in per]
    times = [t for t in times if t is not None]
    return sum(times) / len(times) if times else math.inf


def works(margins: Mapping[str, Any]) -> bool:
    """Whether the design works: its verdict at the target (the margins' first step)."""
    return bool(margins.get("works"))


def better(new: Mapping[str, Any], old: Mapping[str, Any]) -> bool:
    """Whether ``new`` may replace ``old``: it works, and it is more robust (a larger
    robustness value), or as robust and faster (Eq. 10's exit time as the tie-break)."""
    if not works(new):
        return False
    a, b = robustness(new).value, robustness(old).value
    if not math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12):  # rounding is not robustness
        return a > b
    return mean_exit_time(new) < mean_exit_time(old)


def limited_room(row: Mapping[str, Any]) -> float:
    """The smallest room of a margins row over its sides that ended inside the box (inf when
    both reached the box's edge)."""
    r = room(row)
    if r is None:
        return 0.0
    sides = [x for side, x in zip(SIDES, r, strict=True) if not at_edge(row, side)]
    return min(sides, default=math.inf)


def centre_targets(
    margins: Mapping[str, Any],
    names: Sequence[str],
    values: Sequence[float],
    focus: float = 0.0,
) -> list[float]:
    """Per design parameter (``names``, in order, nominal ``values``), the centre of its
    allowed interval in the margins (with one side at the box's edge, only when that moves
    away from the limited side); a parameter with no row or no interval, or whose both
    sides reached the box's edge (nothing limits it), keeps its value; with ``focus`` > 0,
    so does one whose smallest limited room exceeds ``focus`` times the robustness."""
    rows = {str(r["parameter"]): r for r in margins.get("margins") or []}
    bound = focus * robustness(margins).value if focus > 0 else math.inf
    out = []
    for name, value in zip(names, values, strict=True):
        row = rows.get(name)
        if (
            row is None
            or row.get("interval") is None
            or (at_edge(row, "low") and at_edge(row, "high"))
            or limited_room(row) > bound
        ):
            out.append(float(value))
            continue
        low, high = row["interval"]
        centre = 0.5 * (float(low) + float(high))
        # one side at the box's edge: that side's room never counts, so never move toward
        # the limited side (its room would shrink), only away from it
        if at_edge(row, "low"):
            centre = min(centre, float(value))
        elif at_edge(row, "high"):
            centre = max(centre, float(value))
        out.append(centre)
    return out


def centring_move(
    margins: Mapping[str, Any],
    names: Sequence[str],
    values: Sequence[float],
    step: float,
    low: Sequence[float],
    high: Sequence[float],
    focus: float = 0.0,
) -> list[float]:
    """The damped move toward the centres (:func:`centre_targets`), clipped into the box."""
    x = np.asarray(values, dtype=float)
    c = np.asarray(centre_targets(margins, names, values, focus), dtype=float)
    return np.clip(x + step * (c - x), low, high).tolist()


def random_move(
    values: Sequence[float],
    step: float,
    spread: float,
    low: Sequence[float],
    high: Sequence[float],
    seed: int,
    index: int,
) -> list[float]:
    """A seeded random move of ``spread * step`` of each box in a random direction."""
    rng = np.random.default_rng([seed, index])
    direction = rng.normal(size=len(values))
    direction /= np.linalg.norm(direction) or 1.0
    width = np.asarray(high, dtype=float) - np.asarray(low, dtype=float)
    x = np.asarray(values, dtype=float) + spread * step * width * direction * math.sqrt(len(values))
    return np.clip(x, low, high).tolist()


@dataclass
class Step:
    """One margins evaluation of a chain: the design, its robustness, whether it works,
    its mean exit time, the kind of move (``start``, ``centre``, ``random``), the step factor
    and whether it was accepted."""

    values: list[float]
    robustness: Robustness
    works: bool
    exit_time: float
    kind: str
    step: float
    accepted: bool

    def to_dict(self) -> dict[str, Any]:
        return {
            "values": self.values,
            "robustness": self.robustness.to_dict(),
            "works": self.works,
            "mean_exit_time_s": None if math.isinf(self.exit_time) else self.exit_time,
            "move": self.kind,
            "step": self.step,
            "accepted": self.accepted,
        }


@dataclass
class Chain:
    """A centring run from one start: its steps in order and the best design found."""

    start: str
    steps: list[Step] = field(default_factory=list)
    best: list[float] | None = None
    best_margins: Mapping[str, Any] | None = None
    stopped: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {
            "start": self.start,
            "evaluations": len(self.steps),
            "accepted": sum(s.accepted for s in self.steps),
            "best": self.best,
            "best_robustness": None
            if self.best_margins is None
            else robustness(self.best_margins).to_dict(),
            "stopped": self.stopped,
            "steps": [s.to_dict() for s in self.steps],
        }


def _step(values: list[float], margins: Mapping[str, Any], kind: str, step: float) -> Step:
    return Step(
        list(values),
        robustness(margins),
        works(margins),
        mean_exit_time(margins),
        kind,
        step,
        False,
    )


def design_centering(
    start: Sequence[float],
    names: Sequence[str],
    low: Sequence[float],
    high: Sequence[float],
    measure: Measure,
    settings: CenteringSettings,
    budget: int | None = None,
    label: str = "start",
    on_step: Callable[[Step], object] | None = None,
) -> Chain:
    """Centre the design ``start`` (values of ``names`` in the box ``low``..``high``) by
    ``measure`` (values -> margins dict) within ``budget`` evaluations (``settings.budget``
    unless given): see the module. The start is the first evaluation; it is kept as the best
    only if it works (a chain whose start does not work stops there)."""
    budget = settings.budget if budget is None else budget
    chain = Chain(label)
    if budget < 1:
        chain.stopped = "no budget"
        return chain
    x = [float(v) for v in start]
    current = measure(x)
    first = _step(x, current, "start", 0.0)
    first.accepted = works(current)
    chain.steps.append(first)
    if on_step:
        on_step(first)
    if not works(current):
        chain.stopped = "the start does not work"
        return chain
    chain.best, chain.best_margins = x, current
    step = settings.step
    while True:
        if len(chain.steps) >= budget:
            chain.stopped = "budget spent"
            break
        if step < settings.min_step:
            chain.stopped = "step below min_step"
            break
        moves = [("centre", centring_move(current, names, x, step, low, high, settings.focus))]
        moves += [
            (
                "random",
                random_move(
                    x, step, settings.spread, low, high, settings.seed, len(chain.steps) + i
                ),
            )
            for i in range(settings.explore)
        ]
        accepted = False
        for kind, y in moves:
            if np.allclose(y, x, rtol=0.0, atol=1e-12):
                continue
            if len(chain.steps) >= budget:
                break
            new = measure(y)
            record = _step(y, new, kind, step)
            if better(new, current):
                record.accepted = accepted = True
                x, current = y, new
                chain.best, chain.best_margins = x, current
            chain.steps.append(record)
            if on_step:
                on_step(record)
            if accepted:
                break
        if not accepted:
            if all(np.allclose(y, x, rtol=0.0, atol=1e-12) for _, y in moves):
                chain.stopped = "at the centre: no move left"
                break
            step *= 0.5
    return chain
