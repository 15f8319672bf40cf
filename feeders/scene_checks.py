"""Physical sanity of a scene as a user gives it: one place for each rule, used by every reader.

A scene can be well-typed and still mean nothing: gravity of 1e308, bounds of +-1e308, a start
pose inside a wall or outside the bounds, a goal no part can reach, a part bigger than the
scene. The levels would run such a scene and report something; a user must instead hear which
field is wrong and what is allowed. :func:`scene_problems` lists the problems (each message
names the field); readers raise the first.
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from feeders.scene import Scene

MAX_GRAVITY = 1e3  # |g| (length/s^2): 100 times Earth's, far beyond any feeder
MAX_COORDINATE = 1e6  # |bounds|, |vertex|, |centre| (length)
MAX_YAW = 2.0 * math.pi  # |start yaw| (rad): a pose is given within one turn either way
MAX_STARTS = 100
START_OVERLAP = 0.01  # deepest a start may overlap the obstacles (length): the levels'
# largest penetration tolerance (the dynamic level's), so every level can start there


def _solid(scene: Scene) -> shapely.Geometry:
    pieces = [shapely.Polygon(p) for p in scene.obstacles.polygons]
    pieces += [shapely.Point(c[:2]).buffer(c[2], 64) for c in scene.obstacles.circles]
    return shapely.union_all(pieces) if pieces else shapely.Polygon()


def _pieces_at(scene: Scene, pose: tuple[float, float, float]) -> list[np.ndarray]:
    """The part's convex pieces at ``pose``, each disc as the regular polygon through its
    circle (:data:`feeders.part_shape.DISC_SIDES` sides)."""
    from feeders.part_shape import DISC_SIDES, body_pieces  # composite parts import this module

    c, s = math.cos(pose[2]), math.sin(pose[2])
    rot, at = np.array([[c, s], [-s, c]]), np.array(pose[:2])
    polygons, discs = body_pieces(scene.part)
    angles = 2.0 * math.pi * np.arange(DISC_SIDES) / DISC_SIDES
    ring = np.column_stack([np.cos(angles), np.sin(angles)])
    shapes = list(polygons) + [np.array([x, y]) + r * ring for x, y, r in discs]
    return [v @ rot + at for v in shapes]


INSCRIBED_TOLERANCE = 1e-4
"""Tolerance (length) of shapely's maximum inscribed circle in :func:`overlap_depth`: the disc
it finds lies inside the overlap whatever the tolerance, so its radius stays a lower bound."""


def overlap_depth(solid: shapely.Geometry, corners: np.ndarray) -> float:
    """How deep the convex polygon ``corners (n, 2)`` overlaps ``solid`` (length, 0 when
    apart): the deepest of its corners inside the solid and of the solid's boundary points
    inside it, by distance to the other's boundary, and the radius of the largest disc inside
    the overlap (the part cannot leave a disc it holds by a shorter move: this sees a thin wall
    through the middle of the part, where the corners read little or nothing)."""
    if solid.is_empty:
        return 0.0
    part = shapely.Polygon(corners)
    if not part.intersects(solid):
        return 0.0
    depth = 0.0
    for x, y in corners:
        point = shapely.Point(x, y)
        if solid.contains(point):
            depth = max(depth, solid.boundary.distance(point))
    inside = part.intersection(solid.boundary)
    for x, y in shapely.get_coordinates(inside):
        depth = max(depth, part.exterior.distance(shapely.Point(x, y)))
    overlap = shapely.buffer(part.intersection(solid), 0.0)  # its polygons only
    if overlap.area > INSCRIBED_TOLERANCE**2:
        depth = max(depth, shapely.maximum_inscribed_circle(overlap, INSCRIBED_TOLERANCE).length)
    return float(depth)


def gravity_problem(gravity: tuple[float, float], field: str = "gravity") -> str | None:
    """What is wrong with a gravity vector (length/s^2), or None."""
    g = math.hypot(*gravity)
    if math.isfinite(g) and g <= MAX_GRAVITY:
        return None
    return f"{field} = {list(gravity)}: its magnitude must be at most {MAX_GRAVITY:g}"


def scene_problems(scene: Scene) -> list[str]:
    """What is physically wrong with ``scene`` (empty when nothing is), each message naming the
    field and what is allowed."""
    problems = []
    gravity = gravity_problem(scene.gravity)
    if gravity:
        problems.append(gravity)
    x0, x1, y0, y1 = scene.bounds
    if not all(math.isfinite(v) and abs(v) <= MAX_COORDINATE for v in scene.bounds):
        problems.append(f"bounds = {list(scene.bounds)}: each must lie within +-{MAX_COORDINATE:g}")
        return problems  # the rest is measured against the bounds
    diagonal = math.hypot(x1 - x0, y1 - y0)
    from feeders.part_shape import part_extent

    if part_extent(scene.part) > diagonal:
        problems.append(
            f"part.length = {part_extent(scene.part):g} (its largest extent) does not fit the "
            f"scene: at most the diagonal of the bounds, {diagonal:.4g}"
        )
        return problems
    coordinates = [np.abs(p).max() for p in scene.obstacles.polygons]
    coordinates += [np.abs(c[:2]).max() + c[2] for c in scene.obstacles.circles]
    if coordinates and max(coordinates) > MAX_COORDINATE:
        problems.append(f"obstacles: coordinates must lie within +-{MAX_COORDINATE:g}")
        return problems
    if len(scene.starts) > MAX_STARTS:
        problems.append(f"starts: {len(scene.starts)} poses; at most {MAX_STARTS} are allowed")
        return problems
    goal = scene.goal
    if not (x0 <= goal.x_min and goal.x_max <= x1 and y0 <= goal.y_min and goal.y_max <= y1):
        problems.append(
            f"goal: the box x [{goal.x_min:g}, {goal.x_max:g}], y [{goal.y_min:g}, "
            f"{goal.y_max:g}] must lie inside the bounds {list(scene.bounds)}"
        )
    solid = _solid(scene)
    box = shapely.box(goal.x_min, goal.y_min, goal.x_max, goal.y_max)
    if box.difference(solid).area <= 1e-12 * max(box.area, 1.0):
        problems.append("goal: the box lies inside the obstacles; no part can reach it")
    for name, pose in scene.starts.items():
        x, y, yaw = pose
        if not all(math.isfinite(v) for v in pose):
            problems.append(f"starts.{name} = {list(pose)}: expected finite numbers")
            continue
        if not (x0 <= x <= x1 and y0 <= y <= y1):
            problems.append(
                f"starts.{name} = {list(pose)}: the position must lie inside the bounds "
                f"{list(scene.bounds)}"
            )
        if abs(yaw) > MAX_YAW:
            problems.append(
                f"starts.{name}: yaw = {yaw:g} is outside the allowed range "
                f"[{-MAX_YAW:.6g}, {MAX_YAW:.6g}]"
            )
            continue
        depth = max(overlap_depth(solid, piece) for piece in _pieces_at(scene, pose))
        if depth > START_OVERLAP:
            problems.append(
                f"starts.{name}: the part there overlaps the obstacles by {depth:.3g}; "
                f"at most {START_OVERLAP:g} is allowed"
            )
    return problems
