"""Independent measures of a recorded motion: shapely geometry and closed forms only.

Nothing here calls the code under test (the contact kernels of :mod:`validity`): the solid is
shapely's union of the scene's obstacles, the part is its shape as shapely sees it
(:class:`PartShape`: the peg's rectangle, or the union of a composite part's pieces from
:func:`feeders.part_shape.body_pieces`, convex or not, with its discs) placed at each recorded
pose, and the energies are the textbook sums. Lengths in the scene's units, energies in mass
length^2/s^2.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import shapely

from feeders.part import Peg
from feeders.part_shape import Part, body_pieces
from feeders.scene import Scene
from feeders.scene_checks import INSCRIBED_TOLERANCE

CIRCLE_SEGMENTS = 256  # a disc as a polygon of 4 * 256 sides: inscribed, so a depth read on
# it is never more than on the true disc (off by at most r (1 - cos(pi / 1024)) < 5e-6 r)


UNION_GRID = 1e-12
"""Grid (length) the union is taken on: pieces meant to share an edge differ in the last bits
of a coordinate (table3's funnel), and an exact union keeps a slit between them as boundary."""


def union_of(polygons: Sequence[Any], circles: Sequence[Any] | np.ndarray) -> shapely.Geometry:
    """The union of simple polygons (rows [x, y]) and discs ``(cx, cy, r)``, prepared."""
    pieces = [shapely.Polygon(p) for p in polygons]
    pieces += [shapely.Point(c[0], c[1]).buffer(c[2], quad_segs=CIRCLE_SEGMENTS) for c in circles]
    solid = shapely.union_all(pieces, grid_size=UNION_GRID) if pieces else shapely.Polygon()
    shapely.prepare(solid)
    return solid


def placed_points(points: np.ndarray, states: np.ndarray) -> np.ndarray:
    """Body-frame ``points (N, 2)`` at every pose ``states[:, :3]`` (x, y, yaw), shape (S, N, 2)."""
    c, s = np.cos(states[:, 2]), np.sin(states[:, 2])
    x = c[:, None] * points[None, :, 0] - s[:, None] * points[None, :, 1] + states[:, 0:1]
    y = s[:, None] * points[None, :, 0] + c[:, None] * points[None, :, 1] + states[:, 1:2]
    return np.stack([x, y], axis=-1)


@dataclass(frozen=True)
class PartShape:
    """The part in its body frame as the measures need it (built once per part).

    ``outline (N, 2)``: points of the part's boundary, every corner of its outline (the peg's
    four corners; for a composite part the vertices of the union of its pieces, concave corners
    included, a disc's arc as the vertices of an inscribed ``4 * CIRCLE_SEGMENTS``-gon).
    ``ring``: the outline as one ring in order when the part is one polygon without holes
    (None otherwise). ``body``: the union as a shapely geometry, discs inscribed (prepared).
    ``polygons``, ``discs``: the pieces, for exact gaps. ``rectangle``: the part is the peg's
    rectangle, whose depths have a closed form. ``anchor (2,)``: a point of the part's
    material, followed by the wall-crossing measure: the centre of mass (the origin) when it
    lies inside the part, else the centre of the largest disc inside the part (a cup's centre
    of mass is in its mouth, where an obstacle may be without touching it)."""

    part: Part
    outline: np.ndarray
    ring: np.ndarray | None
    body: shapely.Geometry
    boundary: shapely.Geometry
    polygons: tuple[np.ndarray, ...]
    discs: np.ndarray
    rectangle: bool
    anchor: np.ndarray

    @classmethod
    def of(cls, part: Part | PartShape) -> PartShape:
        """The shape of ``part`` (a shape is its own)."""
        if isinstance(part, PartShape):
            return part
        polygons, discs = body_pieces(part)
        if len(polygons) == 1 and len(discs) == 0:
            ring = np.asarray(polygons[0], dtype=float)
            body = shapely.Polygon(ring)
        else:
            body = union_of(polygons, discs)
            ring = None
            if body.geom_type == "Polygon" and not body.interiors:
                ring = np.asarray(body.exterior.coords)[:-1]
        rings = [ring] if ring is not None else _rings(body)
        anchor = np.zeros(2)
        if not shapely.contains_xy(body, 0.0, 0.0):
            largest = max(getattr(body, "geoms", [body]), key=lambda g: g.area)
            centre = shapely.maximum_inscribed_circle(largest, INSCRIBED_TOLERANCE)
            anchor = np.asarray(centre.coords[0], dtype=float)
        boundary = body.boundary
        shapely.prepare(body)
        shapely.prepare(boundary)
        return cls(
            part,
            np.vstack(rings),
            ring,
            body,
            boundary,
            tuple(np.asarray(v, dtype=float) for v in polygons),
            np.asarray(discs, dtype=float).reshape(-1, 3),
            isinstance(part, Peg),
            anchor,
        )

    def placed(self, states: np.ndarray) -> np.ndarray:
        """The part at every pose ``states[:, :3]`` as shapely geometries, shape (S,)."""
        if self.ring is not None:
            return shapely.polygons(placed_points(self.ring, states))
        n = len(shapely.get_coordinates(self.body))
        xy = placed_points(shapely.get_coordinates(self.body), states).reshape(-1, 2)
        copies = np.array([self.body] * len(states), dtype=object)
        return shapely.transform(copies, lambda _: xy) if n else copies


def _rings(body: shapely.Geometry) -> list[np.ndarray]:
    """Every ring's vertices (closing point dropped) of a polygon or multipolygon."""
    rings = []
    for polygon in getattr(body, "geoms", [body]):
        for ring in [polygon.exterior, *polygon.interiors]:
            rings.append(np.asarray(ring.coords)[:-1])
    return rings


def part_corners(part: Part | PartShape, states: np.ndarray) -> np.ndarray:
    """The part's outline points (:attr:`PartShape.outline`; the peg's four corners) at every
    pose ``states[:, :3]`` (x, y, yaw), shape (S, N, 2)."""
    return placed_points(PartShape.of(part).outline, states)


@dataclass(frozen=True)
class Solid:
    """The obstacles as the measures need them: the union, its boundary and boundary vertices."""

    union: shapely.Geometry
    boundary: shapely.Geometry
    vertices: np.ndarray  # (M, 2): every vertex of the union's boundary

    @classmethod
    def of(cls, scene: Scene) -> Solid:
        return cls.of_union(union_of(scene.obstacles.polygons, scene.obstacles.circles))

    @classmethod
    def of_union(cls, union: shapely.Geometry) -> Solid:
        boundary = union.boundary
        shapely.prepare(boundary)
        vertices = shapely.get_coordinates(boundary) if not union.is_empty else np.zeros((0, 2))
        return cls(union, boundary, np.unique(vertices, axis=0))


def penetration_depths(solid: Solid, part: Part | PartShape, states: np.ndarray) -> np.ndarray:
    """How deep the part overlaps the solid at every pose (length, 0 when apart), shape (S,).

    The deepest of (a) the part's outline points (:class:`PartShape`) inside the union, by
    shapely's distance to the union's boundary, and (b) the union's boundary vertices inside the
    part, by the distance to the part's boundary (closed form in the body frame for the peg's
    rectangle; shapely's distance to the boundary of the union of the pieces otherwise, and for
    a point inside a disc piece at least r - |v - c|, since the disc is inside the part). A
    square sunk 0.1 into a floor reads 0.1. And (c) the radius of the largest disc inside the
    overlap region (shapely's maximum inscribed circle of part and union): the part cannot leave
    a disc it holds by a shorter move, so that radius is a lower bound on the depth, and it is
    what sees a wall through the middle of the part, or a corner just short of the far side of
    a thin wall, where (a) and (b) read little or nothing. A non-convex part is measured as it
    is (no convex hull): an obstacle in the mouth of a cup overlaps nothing.
    """
    shape = PartShape.of(part)
    states = np.asarray(states, dtype=float).reshape(-1, states.shape[-1])
    depth = np.zeros(len(states))
    if solid.union.is_empty or len(states) == 0:
        return depth
    placed = placed_points(shape.outline, states)
    corners = placed.reshape(-1, 2)
    inside = shapely.contains_xy(solid.union, corners[:, 0], corners[:, 1])
    if inside.any():
        d = np.zeros(len(corners))
        d[inside] = shapely.distance(solid.boundary, shapely.points(corners[inside]))
        depth = np.maximum(depth, d.reshape(len(states), -1).max(axis=1))
    c, s = np.cos(states[:, 2])[:, None], np.sin(states[:, 2])[:, None]
    for lo in range(0, len(solid.vertices), 256):  # bounded memory: S x 256 at a time
        v = solid.vertices[lo : lo + 256]
        dx = v[None, :, 0] - states[:, 0:1]
        dy = v[None, :, 1] - states[:, 1:2]
        bx, by = c * dx + s * dy, -s * dx + c * dy  # body frame
        depth = np.maximum(depth, _depth_in_part(shape, bx, by))
    return np.maximum(depth, _held_disc(solid, shape, states))


def _depth_in_part(shape: PartShape, bx: np.ndarray, by: np.ndarray) -> np.ndarray:
    """Per row, the deepest of the body-frame points ``(bx, by)`` (rows: poses) inside the
    part, by their distance to its boundary (0 outside), shape (S,)."""
    if shape.rectangle:
        body = shape.outline
        x0, y0 = body[:, 0].min(), body[:, 1].min()
        x1, y1 = body[:, 0].max(), body[:, 1].max()
        inner = np.minimum(np.minimum(bx - x0, x1 - bx), np.minimum(by - y0, y1 - by))
        return np.maximum(inner, 0.0).max(axis=1)
    inner = np.zeros(bx.shape)
    x, y = bx.ravel(), by.ravel()
    inside = shapely.contains_xy(shape.body, x, y)
    if inside.any():
        flat = inner.reshape(-1)
        flat[inside] = shapely.distance(shape.boundary, shapely.points(x[inside], y[inside]))
    for cx, cy, r in shape.discs:
        inner = np.maximum(inner, r - np.hypot(bx - cx, by - cy))
    return np.maximum(inner, 0.0).max(axis=1)


def _held_disc(solid: Solid, shape: PartShape, states: np.ndarray) -> np.ndarray:
    """Radius of the largest disc inside the overlap of the part and the solid at every pose
    (0 where they do not overlap with area)."""
    radius = np.zeros(len(states))
    parts = shape.placed(states)
    touching = np.nonzero(shapely.intersects(solid.union, parts))[0]
    if len(touching) == 0:
        return radius
    overlap = shapely.intersection(parts[touching], solid.union)
    mixed = shapely.get_type_id(overlap) == shapely.GeometryType.GEOMETRYCOLLECTION
    overlap[mixed] = shapely.buffer(overlap[mixed], 0.0)  # its polygons (drops lines, points)
    area = shapely.area(overlap)
    some = area > INSCRIBED_TOLERANCE**2
    if some.any():
        lines = shapely.maximum_inscribed_circle(overlap[some], INSCRIBED_TOLERANCE)
        radius[touching[some]] = shapely.length(lines)
    return radius


def free_components(solid: Solid, bounds: tuple[float, float, float, float]) -> list:
    """The connected pieces of free space for the centre of mass: the bounds box minus the
    union of the obstacles (shapely polygons, each prepared). A part whose centre of mass moves
    from one piece to another, or into the solid, went through a wall: the pieces touch only
    across solid."""
    box = shapely.box(bounds[0], bounds[2], bounds[1], bounds[3])
    free = box.difference(solid.union) if not solid.union.is_empty else box
    pieces = list(getattr(free, "geoms", [free]))
    for piece in pieces:
        shapely.prepare(piece)
    return [p for p in pieces if not p.is_empty]


def component_of(components: list, states: np.ndarray) -> np.ndarray:
    """Index of the free-space piece holding each centre of mass (-1: inside the solid or out
    of the bounds), shape (S,). A point on a piece's boundary counts as in it."""
    label = np.full(len(states), -1, dtype=np.int64)
    x, y = states[:, 0], states[:, 1]
    for k, piece in enumerate(components):
        hit = shapely.intersects_xy(piece, x, y) & (label < 0)
        label[hit] = k
    return label


def mechanical_energy(
    states: np.ndarray, mass: float, inertia: float, gravity: tuple[float, float]
) -> np.ndarray:
    """Kinetic plus gravitational potential energy at every state (x, y, yaw, vx, vy, omega)."""
    kinetic = (
        0.5 * mass * (states[:, 3] ** 2 + states[:, 4] ** 2) + 0.5 * inertia * states[:, 5] ** 2
    )
    return kinetic - mass * (gravity[0] * states[:, 0] + gravity[1] * states[:, 1])


def wrench_work(states: np.ndarray, wrench: tuple[float, float, float]) -> np.ndarray:
    """Work done by a constant wrench (fx, fy, tau) from the first state to each state: the
    force times the displacement plus the torque times the rotation (exact for any path)."""
    d = states[:, :3] - states[0, :3]
    return wrench[0] * d[:, 0] + wrench[1] * d[:, 1] + wrench[2] * d[:, 2]


def linearisation_errors(
    states: np.ndarray, radius: float, disc_radius: float = np.inf
) -> np.ndarray:
    """Per step, how much deeper than its linearised gap a point of the part may end (length):
    R dtheta^2 / 2 for the turn (a point at R from the centre of mass leaves its tangent line by
    at most that) plus d^2 / (2 r) for a slide of d (the largest point displacement) along a
    disc of radius r (the smallest disc of the scene; inf without discs). Shape (S - 1,)."""
    turn = np.abs(np.remainder(np.diff(states[:, 2]) + np.pi, 2.0 * np.pi) - np.pi)
    slide = np.hypot(*np.diff(states[:, :2], axis=0).T) + radius * turn
    return radius * turn**2 / 2.0 + slide**2 / (2.0 * disc_radius)


def pose_corrections(states: np.ndarray, h: float) -> np.ndarray:
    """Per step, the part of the pose change its new velocity does not explain (rows dx, dy,
    dtheta): Eq. 7 moves q' = q + h v', so anything else is a pose correction of an overlap."""
    step = states[1:, :3] - states[:-1, :3] - h * states[1:, 3:6]
    step[:, 2] = np.remainder(step[:, 2] + np.pi, 2.0 * np.pi) - np.pi
    return step


def correction_work(
    corrections: np.ndarray, wrench: tuple[float, float, float], mass: float, gravity
) -> np.ndarray:
    """Energy the pose corrections may have moved the part through the field of gravity and
    the wrench, summed from the first state to each state: sum |(f + m g) . dxy| + |tau dtheta|
    (a correction changes the pose without work, so this is the most it can add)."""
    fx, fy = wrench[0] + mass * gravity[0], wrench[1] + mass * gravity[1]
    each = np.abs(fx * corrections[:, 0] + fy * corrections[:, 1])
    each += np.abs(wrench[2] * corrections[:, 2])
    return np.concatenate(([0.0], np.cumsum(each)))


def kinetic_energy(velocity: np.ndarray, mass: float, inertia: float) -> np.ndarray:
    """0.5 m |v|^2 + 0.5 I omega^2 of rows (vx, vy, omega)."""
    v = np.atleast_2d(velocity)
    return 0.5 * mass * (v[:, 0] ** 2 + v[:, 1] ** 2) + 0.5 * inertia * v[:, 2] ** 2
