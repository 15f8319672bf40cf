"""The part's shape as every level takes it, whichever kind of part it is (issue 24).

A part is the two-density peg (:class:`feeders.part.Peg`, one rectangle to the levels) or a
composite part (:class:`feeders.composite_part.CompositePart`: convex polygons and discs).
The levels see both as convex pieces and discs in the body frame (origin at the centre of
mass, lengths in the paper's units); pictures, checks and references see it as one shapely
geometry placed at a pose.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TypeAlias

import numpy as np
import shapely

from feeders.composite_part import CompositePart
from feeders.part import Peg

Part: TypeAlias = Peg | CompositePart

DISC_SIDES = 64  # a disc drawn or measured by shapely is this regular polygon


def body_pieces(part: Part) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    """``(polygons, discs)`` in the body frame: convex CCW ``(K_i, 2)`` polygons and discs
    ``(D, 3)`` (cx, cy, radius). The peg is one rectangle: its halves' seam is no surface."""
    if isinstance(part, Peg):
        return (part.body_vertices(),), np.zeros((0, 3))
    return part.body_polygons(), part.body_discs()


def _placed(points: np.ndarray, pose: Sequence[float]) -> np.ndarray:
    c, s = math.cos(pose[2]), math.sin(pose[2])
    return points @ np.array([[c, s], [-s, c]]) + np.array([pose[0], pose[1]])


def part_geometry(part: Part, pose: Sequence[float] = (0.0, 0.0, 0.0)) -> shapely.Geometry:
    """The part at ``pose`` (x, y, yaw of the centre of mass) as one shapely geometry: the
    union of its pieces, each disc a regular ``DISC_SIDES``-gon through its circle."""
    polygons, discs = body_pieces(part)
    shapes = [shapely.Polygon(_placed(v, pose)) for v in polygons]
    for cx, cy, r in discs:
        centre = _placed(np.array([[cx, cy]]), pose)[0]
        shapes.append(shapely.Point(centre).buffer(r, quad_segs=DISC_SIDES // 4))
    return shapes[0] if len(shapes) == 1 else shapely.union_all(shapes)


def part_extent(part: Part) -> float:
    """The part's largest extent (length): the peg's length; for a composite part, the
    largest distance between two of its points (its convex hull's diameter)."""
    if isinstance(part, Peg):
        return part.length
    hull = part.convex_hull()
    gaps = hull[:, None, :] - hull[None, :, :]
    return float(np.max(np.hypot(gaps[..., 0], gaps[..., 1])))
