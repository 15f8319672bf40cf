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


CONTACT_SLACK = 1e-5
"""Relative slack (of the part's extent) on the reach of a step: the union's discs are
inscribed polygons, so a distance read on them is up to 5e-6 r too long."""


def obstacle_corners(solid: Solid, discs: np.ndarray) -> np.ndarray:
    """The solid's boundary vertices that are corners, not points of a disc's inscribed
    polygon (:data:`CIRCLE_SEGMENTS`): those within 5e-6 r of a disc's circle are the disc's,
    which :func:`linearisation_errors` treats as the disc. Shape (M, 2)."""
    corners = solid.vertices
    for cx, cy, r in np.asarray(discs, dtype=float).reshape(-1, 3):
        off = np.abs(np.hypot(corners[:, 0] - cx, corners[:, 1] - cy) - r)
        corners = corners[off > 5e-6 * r + 1e-9]
    return corners


def linearisation_errors(
    states: np.ndarray, solid: Solid, part: Part | PartShape, discs: np.ndarray
) -> np.ndarray:
    """Per step, how much deeper than its linearised gaps the part may end (length), from the
    contacts it can have in that step. Shape (S - 1,).

    Eq. 7 keeps every contact's gap psi(q) linearised at the step's start non-negative:
    psi(q0) + J dq >= 0, dq = (dx, dtheta) the step (pose corrections included). The true gap
    at q0 + dq differs from that by the gap function's second-order part, which depends on the
    kind of feature pair (unit normals turn by at most |dtheta|; |e^{i a} - 1 - i a| <= a^2/2):

    - a point of the part at b (body frame) against an obstacle face, vertex or disc: the gap
      is a convex function of the point's position (a plane's is linear, a vertex's or a
      disc's, |p - c| - r, convex), so it is at least its linearisation in p, and p moves by
      J dq plus at most |b| dtheta^2 / 2 (the arc against its tangent). Error |b| dtheta^2/2.
      A disc of the part (its centre at b) against any obstacle feature: the same, with its
      centre's |b|. A disc the point slides along does not add: it curves away from the point.
    - an obstacle vertex v, or an obstacle disc of centre c and radius r, against a face of
      the part: the gap n(theta) . (c - x) - d - r has the face's normal turning with the
      part, so the error is (n1 - n0 - n0' dtheta) . (c - x0) - (n1 - n0) . dx: at most
      |c - x0| dtheta^2 / 2 + |dx| |dtheta|. The lever |c - x0| reaches past the contact
      point by the disc's radius (|c - x0| <= |p - x0| + r; a vertex's r is 0).

    The step's contacts are the feature pairs within its reach, the furthest any point of the
    part moves in it (|dx| + R |dtheta|, R the part's bounding radius): only those can close.
    A part vertex or disc that far from the solid counts with its lever |b|; an obstacle
    corner (:func:`obstacle_corners`) or disc that far from the part with |c - x0| and the
    cross term. The step's error is the largest of these bounds over them, each taken as the
    norm of its residual vector (|b| |e^{i dtheta} - 1 - i dtheta| for a part point,
    :func:`_face_residual` for an obstacle point: the normal is not known, so its worst
    direction); 0 when nothing is within reach or the part does not turn (a translation keeps
    every flat gap linear, and the convex ones above it).

    Flat contacts therefore allow only the turn; a disc's radius enters only through its
    centre's lever, never as d^2 / (2 r) of the slide (the rule of issue 11, which took the
    smallest disc of the scene whether the part touched it or not, and grew without bound as
    that disc shrank: issue 35)."""
    shape = PartShape.of(part)
    discs = np.asarray(discs, dtype=float).reshape(-1, 3)
    states = np.asarray(states, dtype=float)
    errors = np.zeros(max(len(states) - 1, 0))
    if len(states) < 2 or solid.union.is_empty:
        return errors
    turn = np.abs(np.remainder(np.diff(states[:, 2]) + np.pi, 2.0 * np.pi) - np.pi)
    move = np.hypot(*np.diff(states[:, :2], axis=0).T)
    points = np.vstack([*shape.polygons, shape.discs[:, :2]])  # the part's vertices, disc centres
    radii = np.concatenate([np.zeros(len(points) - len(shape.discs)), shape.discs[:, 2]])
    levers = np.hypot(points[:, 0], points[:, 1])
    bounding = float(np.max(levers + radii))
    reach = move + bounding * turn + CONTACT_SLACK * max(bounding, 1.0)
    steps = np.nonzero(turn > 0.0)[0]
    if len(steps) == 0:
        return errors
    starts = states[steps]
    parts = shape.placed(starts)
    near = shapely.distance(parts, solid.union) <= reach[steps]
    steps, starts, parts = steps[near], starts[near], parts[near]
    if len(steps) == 0:
        return errors
    placed = placed_points(points, starts)  # (K, n, 2)
    gaps = shapely.distance(solid.union, shapely.points(placed.reshape(-1, 2))).reshape(
        len(steps), -1
    )
    touching = gaps - radii[None, :] <= reach[steps][:, None]
    part_lever = np.max(np.where(touching, levers[None, :], 0.0), axis=1)
    corners = obstacle_corners(solid, discs)
    centres = np.vstack([corners, discs[:, :2]])
    sizes = np.concatenate([np.zeros(len(corners)), discs[:, 2]])
    a = turn[steps]
    arc = np.hypot(1.0 - np.cos(a), a - np.sin(a))  # |e^{ia} - 1 - ia| <= a^2 / 2
    errors[steps] = part_lever * arc
    shift = np.diff(states[:, :2], axis=0)[steps]
    signed = np.remainder(np.diff(states[:, 2]) + np.pi, 2.0 * np.pi)[steps] - np.pi
    for k in range(len(steps)):
        u = centres - starts[k, :2]
        lever = np.hypot(u[:, 0], u[:, 1])
        candidate = np.nonzero(lever - sizes <= bounding + reach[steps[k]])[0]
        if len(candidate) == 0:
            continue
        gap = shapely.distance(parts[k], shapely.points(centres[candidate])) - sizes[candidate]
        within = candidate[gap <= reach[steps[k]]]
        if len(within):
            residual = _face_residual(u[within], shift[k], float(signed[k]))
            errors[steps[k]] = max(errors[steps[k]], float(residual.max()))
    return errors


def accumulated_errors(errors: np.ndarray, depths: np.ndarray) -> np.ndarray:
    """Per step, the linearisation errors (:func:`linearisation_errors`, shape (S - 1,)) summed
    over the steps since the part last started a step clear of the solid (``depths``, the
    overlap at every state, shape (S,)). An overlapping contact is only asked not to approach
    (its linearised gap may not fall), so each step may leave it deeper by its own error and
    the overlap can grow by their sum while it lasts (a corner rocking against a disc at
    h = 1e-2: seed 1's cases 1631, 4622 and 5195 grow by less than each step's error, 0.03
    over five steps); a step begun apart keeps its gap >= -error. So the overlap after step k
    is at most the tolerance plus this sum."""
    total = np.zeros(len(errors))
    running = 0.0
    for k, error in enumerate(errors):
        running = (running if depths[k] > 0.0 else 0.0) + float(error)
        total[k] = running
    return total


def _face_residual(u: np.ndarray, shift: np.ndarray, turn: float) -> np.ndarray:
    """|R(-a) (u - dx) - u + dx + a J u| for obstacle points at ``u (N, 2)`` from the start's
    centre of mass, a step ``shift`` = dx and a signed ``turn`` = a (J: a quarter turn): the
    most a part face's gap to them leaves its linearisation (:func:`linearisation_errors`),
    at most |u| a^2 / 2 + |dx| |a|."""
    c, s = np.cos(turn), np.sin(turn)
    w = u - shift
    back = np.column_stack([c * w[:, 0] + s * w[:, 1], -s * w[:, 0] + c * w[:, 1]])
    e = back - u + shift + turn * np.column_stack([-u[:, 1], u[:, 0]])
    return np.hypot(e[:, 0], e[:, 1])


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
