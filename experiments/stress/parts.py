"""The composite parts of the stress cases (issue 24): drawn as ``part:`` documents, and read
back with the case's mass and moment of inertia.

A case's scene document holds its part as a scene file would: the peg's keys
(``{length, width, mass, heavy_fraction}``), or a composite part as
:func:`feeders.scene_yaml.environment_from_dict` reads it with ``composite=True`` (``cup``, or
``pieces`` / ``outline`` of :func:`feeders.composite_part.part_from_dict`). Three kinds are
drawn, dealt in turn (:data:`KINDS`):

- ``cup``: the paper's U (:func:`feeders.cup.cup_part`) scaled: height (along its axis) 0.4
  to 2.5 and outer width 0.4 to 1.6 (the feeder family's: within the 1.6 x 1.0 of its peg),
  the walls and base 8% to 30% of the smaller, so the opening is at least 40% of the width and
  the walls stand above the base: always a U of three rectangles sharing two seams;
- ``outline``: an L, a T, or a step (a bar with notches at opposite corners), a simple
  non-convex outline that :func:`feeders.composite_part.split_outline` cuts into convex
  pieces, arms 15% to 40% of the smaller side thick;
- ``disc``: a rectangular plate with a disc touching it, either at the middle of an end (a
  point joint, the deepest crevice a part can have) or at a corner, or with a second disc
  touching the first (a disc-to-disc joint).

Each piece gets a density from 0.2 to 5 (so the centre of mass is off every symmetry), scaled
so the part's mass is the case's. Lengths in the paper's units.
"""

from __future__ import annotations

import copy
import math
from typing import Any

import numpy as np

from feeders.composite_part import CompositePart
from feeders.cup import cup_part
from feeders.part_shape import Part
from feeders.scene_yaml import COMPOSITE_KEYS, environment_from_dict

KINDS = ("cup", "outline", "disc")
FEEDER_STAND_IN = {"length": 1.6, "width": 1.0}
"""The peg the feeder family's scene is built around (its chutes fit it: the peg cases' part);
a composite part drawn for the feeder fits within its 1.6 x 1.0."""
FREE_FORM_STAND_IN = {"length": 1e-3, "width": 1e-3}
"""The peg a free-form scene document is read with before its composite part replaces it:
small enough that the scene reader's start check (0.01) never sees it; the composite part's
own start is then checked (:func:`feeders.scene_yaml.checked_scene`)."""


def is_composite(spec: Any) -> bool:
    """``spec`` (a scene document's ``part:``) is a composite part, not the peg's keys."""
    return isinstance(spec, str) or (isinstance(spec, dict) and bool(set(spec) & COMPOSITE_KEYS))


def read_part(spec: Any) -> Part:
    """The part of a ``part:`` document, peg or composite (errors name ``part...``)."""
    return environment_from_dict({"part": spec}, composite=True)["part"]


def with_mass(part: CompositePart, mass: float, inertia: float) -> CompositePart:
    """``part`` with the case's ``mass`` and moment of inertia about its centre of mass
    (mass x length^2) in place of its own, as the peg's are replaced: the levels read only
    ``mass`` and ``inertia``; the pieces' densities place the centre of mass."""
    made = copy.copy(part)
    object.__setattr__(made, "mass", float(mass))
    object.__setattr__(made, "inertia", float(inertia))
    return made


def _rounded(points: np.ndarray) -> list[list[float]]:
    return [[float(x), float(y)] for x, y in points]


def _densities(rng: np.random.Generator, areas: list[float], mass: float) -> list[float]:
    """A density per piece from 0.2 to 5 (relative), scaled so the pieces weigh ``mass``."""
    relative = rng.uniform(0.2, 5.0, len(areas))
    return [float(d) for d in relative * mass / float(np.dot(relative, areas))]


def _area(points: np.ndarray) -> float:
    x, y = points[:, 0], points[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def _cup(rng: np.random.Generator, size: tuple[float, float], mass: float) -> dict[str, Any]:
    height, width = (float(rng.uniform(0.4, s)) for s in size)
    wall = float(rng.uniform(0.08, 0.3) * min(width, height))
    polygons = cup_part(width, height, wall).polygons
    rho = _densities(rng, [_area(p) for p in polygons], mass)
    return {
        "pieces": [
            {"polygon": _rounded(p), "density": d} for p, d in zip(polygons, rho, strict=True)
        ]
    }


def _outline(rng: np.random.Generator, size: tuple[float, float], mass: float) -> dict[str, Any]:
    a, b = (float(rng.uniform(0.4, s)) for s in size)
    t = float(rng.uniform(0.15, 0.4) * min(a, b))
    shape = int(rng.integers(3))
    if shape == 0:  # an L: a foot a long, an upright b tall
        points = [[0, 0], [a, 0], [a, t], [t, t], [t, b], [0, b]]
    elif shape == 1:  # a T: a bar a long on a stem b tall
        m = 0.5 * (a - t)
        points = [[m, 0], [m + t, 0], [m + t, b - t], [a, b - t], [a, b], [0, b], [0, b - t]]
        points.append([m, b - t])
    else:  # a step: notches at the top left and the bottom right
        points = [[0, 0], [a - t, 0], [a - t, b - t], [a, b - t], [a, b], [t, b], [t, t]]
        points.append([0, t])
    outline = np.array(points, dtype=float)
    return {"outline": _rounded(outline), "density": mass / _area(outline)}


def _disc(rng: np.random.Generator, size: tuple[float, float], mass: float) -> dict[str, Any]:
    length = float(rng.uniform(0.3, 0.6) * size[0])
    width = float(rng.uniform(0.15, 0.6) * min(size[1], length))
    r = float(rng.uniform(0.25, 0.5) * min(size[1], size[0] - length))
    plate = np.array([[0, -width / 2], [length, -width / 2], [length, width / 2], [0, width / 2]])
    way = int(rng.integers(3))
    if way == 0:  # at the middle of the end: a point joint
        discs = [(length + r, 0.0, r)]
    elif way == 1:  # on the corner, along the diagonal
        u = np.array([length, width / 2]) - np.array([length / 2, 0.0])
        u /= float(np.hypot(*u))
        centre = np.array([length, width / 2]) + r * u
        discs = [(float(centre[0]), float(centre[1]), r)]
    else:  # a smaller disc touching the first
        small = float(rng.uniform(0.3, 1.0) * r)
        angle = float(rng.uniform(-0.5, 0.5) * math.pi)
        centre = np.array([length + r, 0.0]) + (r + small) * np.array(
            [math.cos(angle), math.sin(angle)]
        )
        discs = [(length + r, 0.0, r), (float(centre[0]), float(centre[1]), small)]
    areas = [_area(plate)] + [math.pi * d[2] ** 2 for d in discs]
    rho = _densities(rng, areas, mass)
    pieces: list[dict[str, Any]] = [{"polygon": _rounded(plate), "density": rho[0]}]
    pieces += [
        {"circle": {"centre": [d[0], d[1]], "radius": d[2]}, "density": p}
        for d, p in zip(discs, rho[1:], strict=True)
    ]
    return {"pieces": pieces}


def draw_part(rng: np.random.Generator, kind: str, family: str, mass: float) -> dict[str, Any]:
    """A ``part:`` document of ``kind`` (:data:`KINDS`) weighing ``mass``: within 1.6 x 1.0 for
    the feeder family (its chutes are made for that peg), else up to 2.5 x 1.6."""
    size = (1.6, 1.0) if family == "feeder" else (2.5, 1.6)
    draw = {"cup": _cup, "outline": _outline, "disc": _disc}[kind]
    return draw(rng, size, mass)
