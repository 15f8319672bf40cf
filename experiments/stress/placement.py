"""Poses of the part in and near contact, found with shapely (never with the code under test).

A placement starts from an anchor on the solid's boundary, a point and its outward normal,
turns the part as the kind of contact asks (a side flush with the face, a corner at the point,
any yaw) and slides it along the normal until its signed distance to the solid is the target
(a gap > 0 or an overlap < 0), by bisection on :func:`signed_distance`.

Any part (:data:`feeders.part_shape.Part`): the peg, or a composite part measured as the union
of its pieces (:class:`experiments.stress.measures.PartShape`, convex or not). A function
given the part builds its shape; callers that place one part many times pass the shape.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import shapely
from shapely.geometry.polygon import orient

from experiments.stress.measures import PartShape, Solid, penetration_depths, placed_points
from feeders.part import Peg
from feeders.part_shape import Part, part_extent

Pose = tuple[float, float, float]
_BISECTIONS = 60  # halvings of the slide: 2^-60 of a few lengths, below the float spacing


def signed_distance(solid: Solid, part: Part | PartShape, pose: Pose) -> float:
    """Gap from the part at ``pose`` to the solid (length), or minus the overlap depth of
    :func:`experiments.stress.measures.penetration_depths` when they overlap (touch included).
    A composite part's gap is the least over its pieces, a disc's exact (the distance from its
    centre less its radius)."""
    shape = PartShape.of(part)
    state = np.array([pose], dtype=float)
    if shape.rectangle:
        polygon = shapely.Polygon(placed_points(shape.outline, state)[0])
        if not polygon.intersects(solid.union):
            return float(polygon.distance(solid.union))
        return -float(penetration_depths(solid, shape, state)[0])
    if solid.union.is_empty:
        return math.inf
    pieces = [shapely.Polygon(placed_points(v, state)[0]) for v in shape.polygons]
    gaps = list(shapely.distance(pieces, solid.union))
    if len(shape.discs):
        centres = placed_points(shape.discs[:, :2], state)[0]
        gaps += list(shapely.distance(shapely.points(centres), solid.union) - shape.discs[:, 2])
    gap = float(min(gaps))
    if gap > 0.0:
        return gap
    return -float(penetration_depths(solid, shape, state)[0])


def boundary_anchors(solid: Solid) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Every edge of the solid's boundary as ``(start, end, outward unit normal)``."""
    edges = []
    polygons = getattr(solid.union, "geoms", [solid.union])
    for polygon in polygons:
        if polygon.is_empty:
            continue
        polygon = orient(polygon, 1.0)  # exterior CCW, holes CW: (dy, -dx) points out
        for ring in [polygon.exterior, *polygon.interiors]:
            pts = np.asarray(ring.coords)
            for a, b in itertools.pairwise(pts):
                d = b - a
                length = math.hypot(*d)
                if length > 1e-9:
                    edges.append((a, b, np.array([d[1], -d[0]]) / length))
    return edges


def in_bounds(pose: Pose, bounds: tuple[float, float, float, float]) -> bool:
    return bounds[0] <= pose[0] <= bounds[1] and bounds[2] <= pose[1] <= bounds[3]


def slide_to(
    solid: Solid, part: Part | PartShape, pose: Pose, direction: np.ndarray, target: float
) -> Pose | None:
    """``pose`` moved along ``direction`` (unit) until the signed distance is ``target``
    (within 1e-12), or None when no move of at most 10 lengths (the part's extent) reaches
    it."""
    part = PartShape.of(part)

    def at(s: float) -> Pose:
        return (pose[0] + s * direction[0], pose[1] + s * direction[1], pose[2])

    size = part_extent(part.part)
    reach = 10.0 * size
    lo, hi = 0.0, 0.0  # signed distance at lo is below target, at hi above
    if signed_distance(solid, part, pose) > target:
        step = 0.01 * size
        while signed_distance(solid, part, at(lo)) > target:
            lo -= step
            step *= 2.0
            if -lo > reach:
                return None
    else:
        step = 0.01 * size
        while signed_distance(solid, part, at(hi)) <= target:
            hi += step
            step *= 2.0
            if hi > reach:
                return None
    for _ in range(_BISECTIONS):
        mid = 0.5 * (lo + hi)
        if signed_distance(solid, part, at(mid)) > target:
            hi = mid
        else:
            lo = mid
    # hi: the closest pose on the far side of the target, so a gap target is never overlapped
    return at(hi)


def flush_yaw(normal: np.ndarray, side: int) -> float:
    """Yaw that turns the part's side ``side`` (0: -y, 1: +x, 2: +y, 3: -x of the body frame)
    to face the solid along ``-normal``."""
    side_normal_angle = (-0.5 * math.pi, 0.0, 0.5 * math.pi, math.pi)[side]
    return math.atan2(-normal[1], -normal[0]) - side_normal_angle


def hull_sides(part: Part) -> np.ndarray:
    """Angles (rad, body frame) of the outward normals of the part's convex hull's sides longer
    than a hundredth of its extent: the faces it can rest flush on (the cup's base, walls and
    rims; a disc's short chords are left out)."""
    shape = PartShape.of(part)
    hull = np.asarray(shapely.MultiPoint(shape.outline).convex_hull.exterior.coords)
    hull = np.asarray(orient(shapely.Polygon(hull), 1.0).exterior.coords)
    d = np.diff(hull, axis=0)
    long = np.hypot(d[:, 0], d[:, 1]) > 0.01 * part_extent(shape.part)
    return np.arctan2(-d[long, 0], d[long, 1])


def side_flush_yaw(normal: np.ndarray, side_angle: float) -> float:
    """Yaw that turns the hull side whose outward normal is at ``side_angle`` (body frame) to
    face the solid along ``-normal``."""
    return math.atan2(-normal[1], -normal[0]) - side_angle


def touching_pose(
    part: Part | PartShape, point: np.ndarray, normal: np.ndarray, yaw: float
) -> Pose:
    """The pose at ``yaw`` whose outline point deepest along ``-normal`` (a corner) sits at
    ``point``."""
    corners = placed_points(PartShape.of(part).outline, np.array([[0.0, 0.0, yaw]]))[0]
    k = int(np.argmin(corners @ normal))
    return (float(point[0] - corners[k, 0]), float(point[1] - corners[k, 1]), yaw)


def wedge_yaw(part: Peg, width: float) -> float | None:
    """Angle between the part's long axis and a chute's axis at which the part spans exactly
    ``width`` across it: W cos(phi) + L sin(phi) = width, phi in (0, atan(L / W)); None when
    the part cannot span it (width outside (W, sqrt(L^2 + W^2)))."""
    length, w = part.length, part.width
    top = math.atan2(length, w)
    if not (w < width < math.hypot(length, w)):
        return None
    lo, hi = 0.0, top  # the span rises on [0, top]
    for _ in range(_BISECTIONS):
        mid = 0.5 * (lo + hi)
        if w * math.cos(mid) + length * math.sin(mid) < width:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def spans(part: Part | PartShape, angles: np.ndarray) -> np.ndarray:
    """The part's width across a chute whose normal is at ``angles`` (rad, body frame): the
    extent of its outline projected on that normal (length)."""
    outline = PartShape.of(part).outline
    projected = outline @ np.array([np.cos(angles), np.sin(angles)])
    return projected.max(axis=0) - projected.min(axis=0)


def span_range(part: Part | PartShape) -> tuple[float, float, float, float]:
    """``(narrowest, its angle, widest, its angle)``: the least and largest :func:`spans` over
    the angles (on a grid of 0.25 degree; lengths, rad)."""
    angles = np.linspace(0.0, math.pi, 721)
    width = spans(part, angles)
    i, j = int(np.argmin(width)), int(np.argmax(width))
    return float(width[i]), float(angles[i]), float(width[j]), float(angles[j])


def wedge_angle(part: Part | PartShape, width: float) -> float | None:
    """A body-frame angle of the chute's normal at which any part spans exactly ``width``
    (bisection between its narrowest and widest angles, on which the span is continuous);
    None outside the part's range of spans. For the peg it plays the role of
    :func:`wedge_yaw`, which it does not replace (the peg's cases keep their draws)."""
    narrow, lo, wide, hi = span_range(part)
    if not narrow < width < wide:
        return None
    for _ in range(_BISECTIONS):
        mid = 0.5 * (lo + hi)
        if spans(part, np.array([mid]))[0] < width:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def free_pose(
    rng: np.random.Generator,
    solid: Solid,
    part: Part | PartShape,
    bounds: tuple[float, float, float, float],
    clearance: float,
    tries: int = 400,
) -> Pose | None:
    """A uniformly drawn pose in the bounds at least ``clearance`` from the solid, or None."""
    part = PartShape.of(part)
    for _ in range(tries):
        pose = (
            float(rng.uniform(bounds[0], bounds[1])),
            float(rng.uniform(bounds[2], bounds[3])),
            float(rng.uniform(-math.pi, math.pi)),
        )
        if signed_distance(solid, part, pose) >= clearance:
            return pose
    return None
