"""The scene families of the stress cases, as scene documents (the schema of
:mod:`feeders.scene_yaml`) drawn from a random generator.

Every free-form family lives in one world: bounds ``[-5, 5] x [-4, 6]`` for the centre of mass
and, for most, the floor ``[-5, 5] x [-1, 0]`` spanning the bounds, so that falling through the
floor puts the part in another piece of free space. Each family returns the obstacles and a
list of anchors ``(point, outward normal)`` where the part is best placed (a post's foot, the
junction of the pin's finger and disc), besides the generic ones of the solid's boundary.
Lengths in the scene's units.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import shapely

BOUNDS = (-5.0, 5.0, -4.0, 6.0)
FLOOR = [[-5.0, -1.0], [5.0, -1.0], [5.0, 0.0], [-5.0, 0.0]]
# The issue's post on a floor: a 1 x 0.5 box dropped at x = 3 from y = 1 fell through the floor.
ISSUE_POST = [[-0.5, 0.0], [0.5, 0.0], [0.5, 3.0], [-0.5, 3.0]]

Anchor = tuple[tuple[float, float], tuple[float, float]]


@dataclass(frozen=True)
class Obstacles:
    """A free-form family's draw: polygons (lists of [x, y]), discs (cx, cy, r) and anchors."""

    polygons: list[list[list[float]]]
    circles: list[list[float]] = field(default_factory=list)
    anchors: list[Anchor] = field(default_factory=list)
    wedge: tuple[float, float, float] | None = None  # chute: (centre x, centre y, axis angle)

    def document(self) -> list[dict]:
        """The ``obstacles:`` list of a scene document."""
        items: list[dict] = [{"polygon": p} for p in self.polygons]
        items += [{"circle": {"centre": [c[0], c[1]], "radius": c[2]}} for c in self.circles]
        return items


def _box(x0: float, y0: float, x1: float, y1: float) -> list[list[float]]:
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


def _round(points: np.ndarray) -> list[list[float]]:
    return [[float(x), float(y)] for x, y in points]


def convex(rng: np.random.Generator) -> Obstacles:
    """The floor and one to three random convex polygons (hulls of random points), which may
    overlap each other and the floor."""
    polygons = [FLOOR]
    for _ in range(int(rng.integers(1, 4))):
        centre = np.array([rng.uniform(-4.0, 4.0), rng.uniform(0.3, 4.0)])
        radius = rng.uniform(0.3, 1.5)
        points = centre + radius * rng.uniform(-1.0, 1.0, size=(int(rng.integers(5, 10)), 2))
        hull = shapely.MultiPoint(points).convex_hull
        if hull.geom_type == "Polygon" and hull.area > 0.05:
            polygons.append(_round(np.asarray(hull.exterior.coords)[:-1]))
    return Obstacles(polygons)


def nonconvex(rng: np.random.Generator) -> Obstacles:
    """The floor and a random star-shaped polygon with reflex corners (the scene reader splits
    it into convex pieces)."""
    while True:  # a gap of more than pi between neighbours can make the ring cross itself
        n = int(rng.integers(5, 13))
        gap = 0.05  # radians between neighbours at least: strictly increasing angles
        angles = np.sort(rng.uniform(0.0, 2.0 * math.pi - n * gap, n)) + np.arange(n) * gap
        radii = rng.uniform(0.4, 1.8, n)
        centre = (rng.uniform(-3.0, 3.0), rng.uniform(0.5, 3.0))
        star = np.column_stack(
            [centre[0] + radii * np.cos(angles), centre[1] + radii * np.sin(angles)]
        )
        if shapely.Polygon(star).is_valid:
            break
    return Obstacles([FLOOR, _round(star)])


def circles(rng: np.random.Generator) -> Obstacles:
    """The floor and one to four discs, some sunk into the floor."""
    discs = []
    for _ in range(int(rng.integers(1, 5))):
        r = rng.uniform(0.1, 1.2)
        discs.append([rng.uniform(-4.0, 4.0), rng.uniform(0.5 * r, 4.0), r])
    return Obstacles([FLOOR], discs)


def shared_edges(rng: np.random.Generator) -> Obstacles:
    """A floor cut into two to four boxes that share their vertical edges, a block standing
    across one of the cuts (it covers part of two top edges) and a ramp sharing the block's
    side: every kind of seam between the pieces of one solid."""
    cuts = np.sort(rng.uniform(-4.0, 4.0, int(rng.integers(1, 4))))
    xs = [-5.0, *cuts.tolist(), 5.0]
    polygons = [_box(xs[i], -1.0, xs[i + 1], 0.0) for i in range(len(xs) - 1)]
    cut = float(rng.choice(cuts))
    x0, x1 = cut - rng.uniform(0.2, 1.0), cut + rng.uniform(0.2, 1.0)
    top = rng.uniform(0.3, 2.0)
    polygons.append(_box(x0, 0.0, x1, top))
    polygons.append([[x1, 0.0], [x1 + rng.uniform(0.5, 2.0), 0.0], [x1, top]])
    anchors = [((cut, 0.0), (0.0, 1.0)), ((x0, top), (-1.0, 1.0))]
    return Obstacles(polygons, anchors=anchors)


def post_on_floor(rng: np.random.Generator) -> Obstacles:
    """The floor with a post standing on the middle of its top edge (the post covers the middle
    of that edge, the rest of it faces free space); a quarter of the draws are the issue's post
    exactly."""
    if rng.uniform() < 0.25:
        post = ISSUE_POST
    else:
        x, w = rng.uniform(-3.0, 3.0), rng.uniform(0.2, 1.5)
        post = _box(x - w / 2, 0.0, x + w / 2, rng.uniform(0.5, 3.0))
    foot = (post[1][0], 0.0)
    return Obstacles([FLOOR, post], anchors=[(foot, (0.0, 1.0)), ((3.0, 0.0), (0.0, 1.0))])


def thin_wall(rng: np.random.Generator) -> Obstacles:
    """A wall 0.005 to 0.05 thick across the whole bounds: upright from the floor to the top,
    or a shelf from side to side above the floor. The part starts near it and is sent at it."""
    t = rng.uniform(0.005, 0.05)
    if rng.uniform() < 0.5:
        x = rng.uniform(-2.0, 2.0)
        wall = _box(x - t / 2, 0.0, x + t / 2, 6.0)
        anchors = [((x - t / 2, rng.uniform(0.5, 4.0)), (-1.0, 0.0))]
        anchors.append(((x + t / 2, rng.uniform(0.5, 4.0)), (1.0, 0.0)))
    else:
        y = rng.uniform(1.0, 3.0)
        wall = _box(-5.0, y - t / 2, 5.0, y + t / 2)
        anchors = [((rng.uniform(-3.0, 3.0), y + t / 2), (0.0, 1.0))]
    return Obstacles([FLOOR, wall], anchors=anchors)


def chute(rng: np.random.Generator) -> Obstacles:
    """Two parallel walls 0.3 thick at a random angle through the origin, as far apart as the
    part must be wedged across them (the width is set when the part is known: the walls are
    drawn here for a unit width and scaled by :func:`scale_chute`)."""
    angle = rng.uniform(0.0, math.pi)
    return Obstacles([], wedge=(0.0, 0.0, angle))


def scale_chute(obstacles: Obstacles, width: float) -> Obstacles:
    """The chute of :func:`chute` with the walls ``width`` apart (length 40, 0.3 thick)."""
    assert obstacles.wedge is not None
    cx, cy, angle = obstacles.wedge
    axis = np.array([math.cos(angle), math.sin(angle)])
    normal = np.array([-axis[1], axis[0]])
    walls = []
    for side in (1.0, -1.0):
        inner = np.array([cx, cy]) + side * 0.5 * width * normal
        outer = inner + side * 0.3 * normal
        corners = [inner - 20 * axis, inner + 20 * axis, outer + 20 * axis, outer - 20 * axis]
        walls.append(_round(np.array(corners)))
    return Obstacles(walls, wedge=obstacles.wedge)


def pin(rng: np.random.Generator) -> Obstacles:
    """A left wall with a finger ending in a disc of the finger's half thickness (the feeder's
    protuberance): the finger's faces and the disc meet tangentially, where near-duplicate
    contacts arise."""
    r = rng.uniform(0.1, 0.3)
    fx, fy = rng.uniform(-2.0, 1.0), rng.uniform(1.0, 3.0)
    wall = _box(-5.0, 0.0, -4.6, 6.0)
    finger = _box(-4.7, fy - r, fx, fy + r)
    side = 1.0 if rng.uniform() < 0.5 else -1.0
    anchors = [((fx, fy + side * r), (0.0, side)), ((fx + r, fy), (1.0, 0.0))]
    return Obstacles([FLOOR, wall, finger], [[fx, fy, r]], anchors=anchors)


RAMP_ANGLES = (40.0, 75.0)  # degrees: the ramps of issue 35's ramp-foot cases


@dataclass(frozen=True)
class RampFoot:
    """A ramp (or an upright wall) standing on the floor, its face meeting the floor's top in a
    concave corner, the foot: the obstacles, the foot's x, the unit vector down the face and
    the face's outward normal (issue 35: a corner sliding down it into the foot)."""

    obstacles: Obstacles
    foot: float
    down: np.ndarray
    normal: np.ndarray


def ramp_foot(rng: np.random.Generator, wall: bool) -> RampFoot:
    """The floor and a ramp at 40 to 75 degrees standing on it (a triangle whose base covers
    part of the floor's top edge, as issue 35's seam: the floor's nearest point to a corner
    near the foot may lie under the ramp), or for ``wall`` an upright wall 0.3 thick; the face
    descends to the right or to the left, its foot at x in [-2, 2]."""
    foot = float(rng.uniform(-2.0, 2.0))
    side = 1.0 if rng.uniform() < 0.5 else -1.0
    top = float(rng.uniform(0.5, 2.0) if not wall else rng.uniform(1.0, 3.0))
    angle = 0.5 * math.pi if wall else math.radians(rng.uniform(*RAMP_ANGLES))
    back = foot - side * (0.3 if wall else top / math.tan(angle))
    if wall:
        piece = [[foot, 0.0], [foot, top], [back, top], [back, 0.0]]
    else:
        piece = [[foot, 0.0], [back, top], [back, 0.0]]
    if side < 0:
        piece.reverse()  # counter-clockwise either way
    down = np.array([side * math.cos(angle), -math.sin(angle)])
    normal = np.array([side * math.sin(angle), math.cos(angle)])
    anchors = [((foot, 0.0), (float(normal[0]), float(normal[1])))]
    return RampFoot(Obstacles([FLOOR, piece], anchors=anchors), foot, down, normal)


FREE_FORM: dict[str, Callable[[np.random.Generator], Obstacles]] = {
    "convex": convex,
    "nonconvex": nonconvex,
    "circles": circles,
    "shared_edges": shared_edges,
    "post_on_floor": post_on_floor,
    "thin_wall": thin_wall,
    "chute": chute,
    "pin": pin,
}
