"""A design's robustness: its smallest normalised margin (issue 34), defined once for the
sweep's recommendation, the optimiser's robust objective and the reports.

From a design's margins (:meth:`experiments.margins.run.MarginsReport.to_dict`), the room on
each side of each device axis (the design's parameters and the walls' mu; not the part's,
which the designer is given, not choosing) is the distance from the nominal to the last value
found inside, as a fraction of the axis's box. The **robustness** is the smallest such room
over the sides that ended inside the box: how far, in the worst direction found, the design
may be made, worn or run off nominal before P(both) falls below the target. A side whose
search reached the box's edge is limited by the box, not by the design: it is reported
(``edges``) and never taken as the minimum. An axis whose nominal is below the target on the
margins' draws has no room at all (robustness 0). A design none of whose sides ended inside
the box is unlimited within it (``value`` inf, JSON ``null`` with ``unlimited`` true).

This is the worst-case (one-at-a-time) form of design centering: the largest box of
tolerances, aligned with the axes and scaled to each axis's range, whose corners along the
axes all stay acceptable (Director and Hachtel 1977, Bandler and Abdel-Malek 1978;
docs/robustness.md).

**Its error.** Each limiting end is bracketed by the search: the true crossing of the target
lies between the last value inside and the first outside, at most one resolution step apart,
so the robustness lies in ``bracket`` = [smallest inside room, smallest outside room] up to
the estimates' sampling error (each end's P(both) is a count of N drops: 18/20 has the Wilson
interval [0.70, 0.97]). Two designs are told apart by robustness only when their brackets do
not overlap (:func:`more_robust`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

SIDES = ("low", "high")
ABUTTING = 1e-9  # box fraction: brackets that merely touch (rounding of the box's steps) tie
DEVICE_KINDS = ("design", "friction")  # the axes a designer chooses or a feeder wears


def room(row: Mapping[str, Any]) -> tuple[float, float] | None:
    """The room below and above the nominal of one margins row, as fractions of its box's
    width (``(0.0, 0.0)`` is no room at all); None when the row has no margin."""
    interval = row.get("interval")
    if interval is None:
        return None
    low, high = row["box"]
    width = float(high - low) or 1.0
    nominal = float(row["nominal"])
    return (nominal - float(interval[0])) / width, (float(interval[1]) - nominal) / width


def at_edge(row: Mapping[str, Any], side: str) -> bool:
    """Whether the margin's ``side`` ("low" or "high") end is the box's edge (its room is a
    lower bound: the search stopped there)."""
    end = row.get(side) or {}
    return bool(end.get("at_box_edge"))


def outside_room(row: Mapping[str, Any], side: str) -> float | None:
    """The room to the first value found outside on ``side``, as a fraction of the box
    (the upper end of that side's bracket); None at the box's edge or without a margin."""
    end = row.get(side) or {}
    first = end.get("first_outside")
    if not first:
        return None
    low, high = row["box"]
    width = float(high - low) or 1.0
    return abs(float(first["value"]) - float(row["nominal"])) / width


@dataclass(frozen=True)
class Robustness:
    """The smallest normalised room of a design (see the module): ``value`` (a fraction of
    the limiting axis's box; 0 when an axis has no margin, inf when no side ended inside the
    box), the limiting ``axis`` and ``side``, ``bracket`` (where the true value lies, up to
    the ends' sampling error), ``edges`` (the "axis side" pairs that reached the box's edge)
    and ``none`` (axes below the target at nominal)."""

    value: float
    axis: str | None
    side: str | None
    bracket: tuple[float, float]
    edges: tuple[str, ...]
    none: tuple[str, ...]

    @property
    def unlimited(self) -> bool:
        return math.isinf(self.value)

    def to_dict(self) -> dict[str, Any]:
        def finite(x: float) -> float | None:
            return None if math.isinf(x) else x

        return {
            "value": finite(self.value),
            "unlimited": self.unlimited,
            "axis": self.axis,
            "side": self.side,
            "bracket": [finite(self.bracket[0]), finite(self.bracket[1])],
            "edges": list(self.edges),
            "none": list(self.none),
            "meaning": MEANING,
        }


MEANING = (
    "the smallest room, over the design's parameters and the walls' mu, between the nominal "
    "and the last value found with P(both) at or above the target, as a fraction of the "
    "axis's box; sides that reached the box's edge are the box's limit, not the design's"
)


def device_rows(margins: Mapping[str, Any]) -> list[Mapping[str, Any]]:
    """The margins rows of the device's axes (design parameters and friction)."""
    return [r for r in margins.get("margins") or [] if r.get("kind", "design") in DEVICE_KINDS]


def robustness(margins: Mapping[str, Any], kinds: Iterable[str] = DEVICE_KINDS) -> Robustness:
    """The robustness of the design whose margins are ``margins`` (the axes of ``kinds``);
    a design that does not work (no margins) has robustness 0."""
    kinds = tuple(kinds)
    if not margins.get("works"):
        return Robustness(0.0, None, None, (0.0, 0.0), (), ())
    best: tuple[float, str | None, str | None] = (math.inf, None, None)
    upper = math.inf  # the smallest room to a first value outside: the bracket's top
    edges: list[str] = []
    none: list[str] = []
    for row in margins.get("margins") or []:
        if row.get("kind", "design") not in kinds:
            continue
        name = str(row["parameter"])
        r = room(row)
        if r is None:
            none.append(name)
            continue
        for side, inside in zip(SIDES, r, strict=True):
            if at_edge(row, side):
                edges.append(f"{name} {side}")
                continue
            outside = outside_room(row, side)
            upper = min(upper, inside if outside is None else outside)
            if inside < best[0]:
                best = (inside, name, side)
    if none:
        return Robustness(0.0, none[0], None, (0.0, 0.0), tuple(edges), tuple(none))
    value, limiting, limiting_side = best
    return Robustness(value, limiting, limiting_side, (value, upper), tuple(edges), ())


def of_dict(data: Mapping[str, Any]) -> Robustness:
    """A :class:`Robustness` from its :meth:`Robustness.to_dict`."""

    def number(x: Any) -> float:
        return math.inf if x is None else float(x)

    lo, hi = data.get("bracket") or [None, None]
    return Robustness(
        number(data.get("value")),
        data.get("axis"),
        data.get("side"),
        (number(lo), number(hi)),
        tuple(data.get("edges") or ()),
        tuple(data.get("none") or ()),
    )


def more_robust(a: Robustness, b: Robustness) -> bool:
    """Whether ``a`` is more robust than ``b`` beyond the search's resolution: its bracket
    lies wholly above ``b``'s (``a``'s last inside room beyond ``b``'s first outside)."""
    if a.unlimited:
        return not b.unlimited
    return a.bracket[0] > b.bracket[1] + ABUTTING


def in_words(r: Robustness, stopped: bool = False) -> str:
    """``r`` in a few words, "6.3% (gx low)"; "at most" the top of its bracket for a design
    whose margins were ``stopped`` before every axis was measured."""
    if r.unlimited:
        return "unlimited within the box"
    where = f" ({r.axis} {r.side})" if r.side else f" ({r.axis}: no margin)" if r.axis else ""
    if stopped:
        return f"at most {100.0 * r.bracket[1]:.1f}%{where}"
    return f"{100.0 * r.value:.1f}%{where}"
