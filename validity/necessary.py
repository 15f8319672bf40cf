"""Exact necessary conditions for a feeder design to work: sound pruning (issue 21).

A design *works* when the peg, dropped from either entry of feeders made to tolerance, leaves
heavy end down (the passive verdict). A drop that succeeds is a continuous motion of the peg
from a perturbed entry pose to the goal region inside one made feeder, overlapping its walls
by at most the dynamic model's contact slack. Each test below asks for a consequence of such a
motion, against an outer bound of every made feeder's free space
(:mod:`validity.made_envelope`) on a grid that errs toward "fits"
(:mod:`validity.necessary_kernel`), so a design that fails one cannot have a single
successful drop from that entry: pruning on it never loses a working design.

* ``corridor``: the peg contains a disc of radius ``w/2`` round its geometric centre, so
  that disc must get from the entry region to a centre below ``goal.y_max + com_offset``
  (a centre of mass below the goal's top with heavy end down puts the geometric centre at most
  ``com_offset`` higher) in the free space.
* ``turn``: from the heavy-trailing entry (yaw ``theta``, in (0, pi/2) with its perturbation)
  to heavy end down (yaw ``-pi/2 +- goal.yaw_tol``) the yaw changes continuously, so it
  passes a multiple of pi: the peg is horizontal at some moment, at a position whose disc
  is reachable. So a horizontal peg must fit at a cell the corridor's flood reached.
* ``sliced``: the whole motion in (x, y, yaw): 36 yaw slices of the cells that may hold the
  peg, joined across neighbouring cells and slices, from each entry's poses to the goal's.

The heavy-leading entry (yaw ``theta + pi``) can reach heavy end down without a horizontal
pose, so the turn test is for the heavy-trailing entry only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from feeders.scene import Scene
from validity.made_envelope import made_envelope, roof_rise_of
from validity.necessary_kernel import (
    corridor_flood,
    distance_grid,
    free_mask,
    sliced_flood,
    turn_room,
)

TESTS = ("corridor", "turn", "sliced")
CONTACT_SLACK = 0.01  # length: overlap granted between peg and wall (the dynamic model's
# resting overlaps reach 2.7e-5, issue 21; 0.01 keeps a wide margin)
CELL = 0.04  # grid step (length)
SLICES = 36  # yaw slices of the sliced test over [0, 2 pi)
_LIMITS = {
    "tolerance": (0.0, 0.1),
    "position": (0.0, 0.5),
    "yaw": (0.0, 0.5),
    "slack": (0.0, 0.5),
    "cell": (1e-3, 0.5),
}


@dataclass(frozen=True)
class NecessaryVerdict:
    """Whether a design passes every necessary condition tested; ``failed`` names the first
    that fails (None when all pass); ``details`` holds each test's outcome (None: not run)
    and the grid's size."""

    passes: bool
    failed: str | None
    details: dict[str, Any] = field(default_factory=dict)


def _slices_overlapping(low: float, high: float, n: int) -> np.ndarray:
    """Flags of the yaw slices ``[k, k + 1] * 2 pi / n`` that meet ``[low, high]`` (mod 2 pi)."""
    width = 2.0 * math.pi / n
    start = low % (2.0 * math.pi)
    end = start + (high - low)
    flags = np.zeros(n, dtype=np.bool_)
    for k in range(n):
        for shift in (-2.0 * math.pi, 0.0, 2.0 * math.pi):
            if k * width <= end + shift and start + shift <= (k + 1) * width:
                flags[k] = True
    return flags


def _check(name: str, value: float) -> float:
    low, high = _LIMITS[name]
    value = float(value)
    if not (math.isfinite(value) and low <= value <= high):
        raise ValueError(
            f"necessary {name} = {value!r} is outside the allowed range [{low:g}, {high:g}]"
        )
    return value


def necessary_conditions(
    scene: Scene,
    tolerance: float = 0.01,
    *,
    position: float = 0.05,
    yaw: float = 0.05,
    slack: float = CONTACT_SLACK,
    cell: float = CELL,
    slices: int = SLICES,
    tests: tuple[str, ...] = TESTS,
) -> NecessaryVerdict:
    """The necessary conditions ``tests`` (in order, stopping at the first that fails) of the
    feeder ``scene`` (built from a design), for feeders made to ``tolerance`` (relative, per
    parameter) and entries up to ``position`` (length, in x and y) and ``yaw`` (rad) off the
    start, as the verdict's perturbations draw them; ``slack`` is the overlap of peg and wall
    the test grants, ``cell`` the grid step, ``slices`` the yaw slices of the sliced test."""
    if scene.design is None or scene.outline is None:
        raise ValueError("necessary conditions need a feeder built from a design (scene.design)")
    unknown = sorted(set(tests) - set(TESTS))
    if unknown:
        raise ValueError(f"necessary tests {unknown} unknown; known: {', '.join(TESTS)}")
    if not 4 <= int(slices) <= 720:
        raise ValueError(f"necessary slices = {slices!r} is outside the allowed range [4, 720]")
    tolerance, position, yaw = (
        _check(k, v) for k, v in (("tolerance", tolerance), ("position", position), ("yaw", yaw))
    )
    slack, h = _check("slack", slack), _check("cell", cell)
    part, goal = scene.part, scene.goal
    envelope = made_envelope(
        scene.design,
        part,
        tolerance,
        position,
        yaw,
        slack,
        roof_rise_of(scene.design, scene.outline),
    )
    margin = float(envelope.capsules.max()) + 2.0 * h
    low = envelope.outline.min(axis=0) - margin
    high = envelope.outline.max(axis=0) + margin
    nx, ny = (math.ceil(v) + 1 for v in (high - low) / h)
    x0, y0 = float(low[0]), float(low[1])
    room = free_mask(
        envelope.outline, envelope.capsules, envelope.finger, envelope.tip, x0, y0, h, nx, ny
    )
    dist = distance_grid(room, h)
    radius = 0.5 * part.width
    span = 0.5 * (part.length - part.width)
    axis = np.linspace(-span, span, math.ceil(2.0 * span / (0.25 * part.width)) + 1)
    y_goal = goal.y_max + part.com_offset
    details: dict[str, Any] = dict.fromkeys(TESTS)
    details.update(grid=(nx, ny), cell=h)
    reached = None
    for test in TESTS:
        if test not in tests:
            continue
        if test == "corridor" or reached is None:
            ok, reached = corridor_flood(dist, x0, y0, h, radius, envelope.entry, y_goal)
            if test == "corridor":
                details[test] = bool(ok)
        if test == "turn":
            ok = turn_room(dist, x0, y0, h, reached, axis, radius) > 0
            details[test] = bool(ok)
        elif test == "sliced":
            goal_slices = _slices_overlapping(
                goal.yaw - goal.yaw_tol, goal.yaw + goal.yaw_tol, slices
            )
            fits = np.zeros((slices // 2 if slices % 2 == 0 else slices, nx, ny), np.int8)
            ok = True
            for shift in (0.0, math.pi):  # heavy trailing, heavy leading
                entry = _slices_overlapping(
                    envelope.entry_yaw[0] + shift, envelope.entry_yaw[1] + shift, slices
                )
                ok = ok and sliced_flood(
                    dist,
                    x0,
                    y0,
                    h,
                    axis,
                    radius,
                    envelope.entry,
                    entry,
                    goal_slices,
                    y_goal,
                    reached,
                    fits,
                )
            details[test] = bool(ok)
        if not ok:
            return NecessaryVerdict(False, test, details)
    return NecessaryVerdict(True, None, details)
