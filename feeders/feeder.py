"""The part feeder built from a design: walls, protuberance, start poses, goal (Fig. 1, Table 1).

Fig. 3 of the paper is not in its text; the device is reconstructed from Fig. 1 (input chute A,
pin B, exit chute C), Table 1's definitions and Table 2's ranges, as documented with pictures
in ``docs/feeder-geometry.md``. In short (x right, y up, gravity along -y):

* exit chute C: vertical, walls at ``x = -b/2`` and ``x = +b/2`` from ``y = 0`` down to
  ``y = -2L`` (L the part length), closed at the bottom;
* chamfer: both walls of C flare outward at angle ``alpha`` from horizontal up to depth ``c``
  (a funnel whose mouth is ``b + 2c/tan(alpha)`` wide at ``y = c``);
* cavity: floor at ``y = c``; left wall at ``x = e``; roof at the height of the input chute's
  upper wall where it ends above the lip;
* input chute A: a channel of width ``a`` and length ``d`` rising to the right at angle
  ``theta``; its floor ends at the lip ``g`` (its lower left corner); closed at its top;
* below the lip the cavity's right wall drops vertically to the floor or chamfer; when the lip
  overhangs the exit chute (``g.x < b/2``) the underside runs from the lip to the chute's top
  right corner;
* protuberance B: a finger of thickness ``2r`` from the left wall to the tip centre ``f``,
  ending in a half-disc of radius ``r`` (an exact rounded tip).

Walls are convex quads of thickness ``WALL_THICKNESS`` on the outside of the free interior.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from shapely.geometry import Point, Polygon

from feeders.design import DesignParameters
from feeders.part import DEFAULT_PEG, Peg
from feeders.scene import Goal, InputSet, Pose, Scene, wrap_angle
from feeders.shapes import Obstacles

WALL_THICKNESS = 0.4
DEFAULT_FRICTION = 0.05  # walls' Coulomb mu unless a scene says otherwise (docs/calibration.md)
START_CLEARANCE = 0.05  # gap between the part and the cap at the top of the input chute
# The feeder's two entries: the peg enters heavy end first or last; a design must serve both.
ORIENTATIONS = ("heavy_leading", "heavy_trailing")
GOAL_YAW_TOL = 0.35  # rad: "heavy end down" within 20 degrees
CLEARANCE = 1e-9  # length: a part this far from every wall is clear of their union
CLEARANCE_SLACK = 1e-9  # length: beyond the rounding of a projection gap (coordinates ~10)


class DegenerateDesign(ValueError):
    """A design whose geometry cannot be built; ``parameters`` names the values involved."""

    def __init__(self, reason: str, parameters: tuple[str, ...]):
        super().__init__(f"{reason} [parameters: {', '.join(parameters)}]")
        self.reason = reason
        self.parameters = parameters


@dataclass(frozen=True)
class Edge:
    """One edge of the free interior, with the parameters that place it."""

    start: tuple[float, float]
    end: tuple[float, float]
    label: str
    parameters: tuple[str, ...]


def _dedupe(points: list[tuple[tuple[float, float], str, tuple[str, ...]]]) -> list:
    out: list = []
    for p in points:
        if out and math.dist(out[-1][0], p[0]) < 1e-9:
            out[-1] = p  # the earlier edge has zero length: the later one starts here
            continue
        out.append(p)
    if len(out) > 1 and math.dist(out[0][0], out[-1][0]) < 1e-9:
        out.pop()
    return out


def interior_edges(
    design: DesignParameters, part: Peg = DEFAULT_PEG, roof_rise: float = 0.0
) -> list[Edge]:
    """The boundary of the free interior, counter-clockwise (interior on the left).

    ``roof_rise`` lifts the cavity roof above the end of the input chute's upper wall (the
    paper fixes no roof height; 0 is this reconstruction's choice).
    """
    p = design
    half_b = p.b / 2
    depth = 2.0 * part.length
    mouth = half_b + p.c / math.tan(p.alpha)
    u = (math.cos(p.theta), math.sin(p.theta))
    n = (-math.sin(p.theta), math.cos(p.theta))
    g = (p.gx, p.gy)
    top_floor = (g[0] + p.d * u[0], g[1] + p.d * u[1])
    top_ceiling = (top_floor[0] + p.a * n[0], top_floor[1] + p.a * n[1])
    lip_ceiling = (g[0] + p.a * n[0], g[1] + p.a * n[1])
    roof_y = lip_ceiling[1] + roof_rise

    # (vertex, label of the edge that starts at this vertex, parameters of that edge)
    pts: list[tuple[tuple[float, float], str, tuple[str, ...]]] = [
        ((-half_b, -depth), "exit chute bottom", ("b",)),
        ((half_b, -depth), "exit chute right wall", ("b",)),
    ]
    if p.gx >= mouth:
        pts += [
            ((half_b, 0.0), "right chamfer", ("b", "c", "alpha")),
            ((mouth, p.c), "cavity floor (right)", ("c", "gx")),
            ((p.gx, p.c), "wall below the lip", ("gx", "gy", "c")),
        ]
    elif p.gx >= half_b:
        pts += [
            ((half_b, 0.0), "right chamfer", ("b", "c", "alpha")),
            (
                (p.gx, (p.gx - half_b) * math.tan(p.alpha)),
                "wall below the lip",
                ("gx", "gy", "alpha"),
            ),
        ]
    else:
        pts += [((half_b, 0.0), "underside of the lip", ("gx", "gy", "b"))]
    pts += [
        (g, "input chute floor", ("gx", "gy", "d", "theta")),
        (top_floor, "input chute cap", ("a", "d", "theta")),
        (top_ceiling, "input chute upper wall", ("a", "d", "theta", "gx", "gy")),
        (lip_ceiling, "wall above the input chute", ("a", "theta", "gx", "gy")),
        ((lip_ceiling[0], roof_y), "cavity roof", ("e", "a", "theta", "gy")),
        ((p.e, roof_y), "left cavity wall", ("e",)),
    ]
    if p.e <= -mouth:
        pts += [
            ((p.e, p.c), "cavity floor (left)", ("c", "e")),
            ((-mouth, p.c), "left chamfer", ("b", "c", "alpha")),
        ]
    else:
        pts += [
            ((p.e, (-half_b - p.e) * math.tan(p.alpha)), "left chamfer", ("b", "c", "alpha", "e"))
        ]
    pts += [((-half_b, 0.0), "exit chute left wall", ("b",))]
    pts = _dedupe(pts)
    return [
        Edge(pts[i][0], pts[(i + 1) % len(pts)][0], pts[i][1], pts[i][2]) for i in range(len(pts))
    ]


def wall_quad(edge: Edge, thickness: float = WALL_THICKNESS) -> np.ndarray:
    """The wall behind an interior edge: a CCW quad extruded outward (to the edge's right)."""
    (x0, y0), (x1, y1) = edge.start, edge.end
    length = math.hypot(x1 - x0, y1 - y0)
    nx, ny = (y1 - y0) / length * thickness, -(x1 - x0) / length * thickness
    return np.array([[x0, y0], [x0 + nx, y0 + ny], [x1 + nx, y1 + ny], [x1, y1]])


def _outward_normal(edge: Edge) -> np.ndarray:
    d = np.subtract(edge.end, edge.start)
    return np.array([d[1], -d[0]]) / np.hypot(*d)


def _clip(poly: np.ndarray, point: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Sutherland-Hodgman: the part of convex ``poly`` where (x - point) . normal >= 0."""
    out = []
    side = (poly - point) @ normal
    for i in range(len(poly)):
        j = (i + 1) % len(poly)
        if side[i] >= 0:
            out.append(poly[i])
        if (side[i] >= 0) != (side[j] >= 0):
            t = side[i] / (side[i] - side[j])
            out.append(poly[i] + t * (poly[j] - poly[i]))
    kept = [q for k, q in enumerate(out) if np.hypot(*(q - out[k - 1])) > 1e-12]
    return np.array(kept)


def walls_reference(edges: list[Edge], thickness: float = WALL_THICKNESS) -> list[np.ndarray]:
    """:func:`walls` in numpy, as it was before the kernel: the reference the kernel is
    tested against, and what runs where a clip leaves no vertex (which it cannot clip)."""
    quads = [wall_quad(e, thickness) for e in edges]
    normals = [_outward_normal(e) for e in edges]
    n = len(edges)
    for i in range(n):
        prev, cur = (i - 1) % n, i
        vertex = np.asarray(edges[cur].start)
        d_prev = np.subtract(edges[prev].end, edges[prev].start)
        d_cur = np.subtract(edges[cur].end, edges[cur].start)
        if d_prev[0] * d_cur[1] - d_prev[1] * d_cur[0] >= 0:
            continue  # left turn: the walls part on the outside, nothing to clip
        bisector = normals[prev] + normals[cur]
        across = np.array([-bisector[1], bisector[0]])
        if across @ d_cur < 0:
            across = -across
        quads[cur] = _clip(quads[cur], vertex, across)
        quads[prev] = _clip(quads[prev], vertex, -across)
    return quads


def _mitred(segments: np.ndarray, thickness: float) -> tuple[np.ndarray, np.ndarray] | None:
    """The walls of the edges ``segments`` from the kernel: padded vertices and counts, or
    None where a clip left no vertex (:func:`walls_reference` decides)."""
    from feeders.wall_kernel import mitred_walls  # numba on first build, not on import

    lengths = np.array([math.hypot(x1 - x0, y1 - y0) for (x0, y0), (x1, y1) in segments.tolist()])
    verts, counts = mitred_walls(segments, lengths, thickness)
    return None if counts.min() < 0 else (verts, counts)


def walls(edges: list[Edge], thickness: float = WALL_THICKNESS) -> list[np.ndarray]:
    """One convex wall per edge, mitred where the solid has a convex corner.

    Where the interior turns right (a corner of solid material pointing into the free space,
    e.g. the lip), a plain quad would stick out past the neighbouring edge; both walls are
    clipped along the corner's bisector so they meet there and never enter the interior.
    Bit for bit :func:`walls_reference` (``feeders.wall_kernel``).
    """
    mitred = _mitred(_segments(edges), thickness)
    if mitred is None:
        return walls_reference(edges, thickness)
    verts, counts = mitred
    return [verts[i, :k] for i, k in enumerate(counts.tolist())]


def protuberance(design: DesignParameters) -> tuple[np.ndarray, np.ndarray]:
    """The finger (CCW rectangle from inside the left wall to the tip) and its tip disc."""
    p = design
    root = p.e - WALL_THICKNESS
    finger = np.array(
        [[root, p.fy - p.r], [p.fx, p.fy - p.r], [p.fx, p.fy + p.r], [root, p.fy + p.r]]
    )
    return finger, np.array([p.fx, p.fy, p.r])


def _segments(edges: list[Edge]) -> np.ndarray:
    """``(n, 2, 2)``: each edge's start and end."""
    return np.array([(e.start, e.end) for e in edges], dtype=np.float64)


def _check_crossings(edges: list[Edge], segments: np.ndarray) -> bool:
    """:class:`DegenerateDesign` for the first pair (in edge order) of edges that meet other
    than at a shared end, as shapely's intersection says. ``segments``: the edges ``(n, 2,
    2)``. Pairs whose bounding boxes are apart cannot meet (GEOS finds no intersection there
    either) and are not asked; pairs exact orientation tests decide are not asked either
    (``feeders.wall_kernel.first_suspect_pair``), the others are asked of shapely. Returns
    whether every pair was decided without shapely (then the ring is a simple polygon)."""
    from feeders.wall_kernel import UNSURE, first_suspect_pair  # numba on first build

    after = -1
    decided = len(edges) >= 3
    while True:
        k, i, j, status = first_suspect_pair(segments, after)
        if k < 0:
            return decided
        after = k
        if status == UNSURE:
            decided = False
            inter = shapely.intersection(
                shapely.LineString(segments[i]), shapely.LineString(segments[j])
            )
            if inter.is_empty:
                continue
            adjacent = j == i + 1 or (i == 0 and j == len(edges) - 1)
            if adjacent and inter.geom_type == "Point":
                continue
        names = tuple(dict.fromkeys(edges[i].parameters + edges[j].parameters))
        raise DegenerateDesign(
            f"walls cross: the {edges[i].label} meets the {edges[j].label}", names
        )


LEFT_SIDE = ("left cavity wall", "cavity floor (left)", "left chamfer")  # the finger's root
TIP_TOLERANCE = 1e-9  # length: tip distances this close to r are asked of shapely


def _check_tip(p: DesignParameters, edges: list[Edge], segments: np.ndarray) -> None:
    """:class:`DegenerateDesign` if the protuberance's tip centre is not inside the cavity
    (shapely's ``contains``: not on its boundary) or its disc reaches an edge other than
    the left side it grows from (shapely's distance at most r), first edge first. Decided by
    the kernels where floating point is certain, by shapely where not."""
    from feeders.wall_kernel import UNSURE, first_reached, point_inside  # numba on first build

    inside = point_inside(segments, p.fx, p.fy)
    if inside == UNSURE:
        inside = Polygon(segments[:, 0]).contains(Point(p.fx, p.fy))
    if not inside:
        distances = shapely.distance(shapely.linestrings(segments), Point(p.fx, p.fy))
        nearest = edges[int(np.argmin(distances))]
        raise DegenerateDesign(
            f"the protuberance tip f = ({p.fx:g}, {p.fy:g}) lies inside a wall ({nearest.label})",
            tuple(dict.fromkeys(("fx", "fy", *nearest.parameters))),
        )
    skip = np.array([e.label in LEFT_SIDE for e in edges])
    start = 0
    while True:
        i, status = first_reached(segments, p.fx, p.fy, p.r, skip, start, TIP_TOLERANCE)
        if i < 0:
            return
        start = i + 1
        line = shapely.LineString(segments[i])
        if status == UNSURE and shapely.distance(line, Point(p.fx, p.fy)) > p.r:
            continue
        raise DegenerateDesign(
            f"the protuberance (f, r = {p.r:g}) reaches the {edges[i].label}",
            tuple(dict.fromkeys(("fx", "fy", "r", *edges[i].parameters))),
        )


def _clearly_apart(shapes: list[Polygon], pieces: list[np.ndarray], disc: np.ndarray) -> bool:
    """Whether every polygon of ``shapes`` is more than ``1e-9`` (length) from every convex
    piece and from the disc (x, y, r), so that it overlaps their union nowhere. False says
    nothing (the union decides)."""
    gap = CLEARANCE
    k = max(len(q) for q in pieces)
    padded = np.array([np.concatenate([q, np.repeat(q[-1:], k - len(q), axis=0)]) for q in pieces])
    solids = shapely.polygons(padded)  # repeated closing vertices: the same convex pieces
    centre = Point(disc[0], disc[1])
    for shape in shapes:
        if shapely.distance(shape, centre) <= disc[2] + gap:
            return False
        if np.any(shapely.distance(solids, shape) <= gap):
            return False
    return True


def _with_finger(
    wall_verts: np.ndarray, wall_counts: np.ndarray, finger: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The walls' padded vertices ``(n, WALL_CAPACITY, 2)`` and counts with the finger's
    after them."""
    verts = np.zeros((len(wall_verts) + 1, wall_verts.shape[1], 2))
    verts[:-1] = wall_verts
    verts[-1, : len(finger)] = finger
    counts = np.empty(len(wall_counts) + 1, dtype=np.int64)
    counts[:-1] = wall_counts
    counts[-1] = len(finger)
    return verts, counts


def _pose_vertices(part: Peg, pose: Pose) -> np.ndarray:
    c, s = math.cos(pose[2]), math.sin(pose[2])
    body = part.body_vertices()
    return body @ np.array([[c, s], [-s, c]]) + np.array(pose[:2])


def _pose_polygon(part: Peg, pose: Pose) -> Polygon:
    return Polygon(_pose_vertices(part, pose))


def build_feeder(
    design: DesignParameters,
    part: Peg = DEFAULT_PEG,
    inputs: InputSet | None = None,
    friction: float = DEFAULT_FRICTION,
    gravity: tuple[float, float] = (0.0, -9.81),
    name: str = "feeder",
    roof_rise: float = 0.0,
    restitution: float = 0.3,
) -> Scene:
    """The scene of the feeder with this design, or :class:`DegenerateDesign` with a reason.

    Start poses: the part in the top of the input chute, centred across it, its end
    ``START_CLEARANCE`` below the cap, heavy end leading (pointing down the chute) or
    trailing. Goal: the centre of mass below the part length under the chute's mouth and
    heavy end down within ``GOAL_YAW_TOL``.
    """
    p = design
    if p.a <= part.width:
        raise DegenerateDesign(
            f"input chute width a = {p.a:g} is not wider than the part ({part.width:g})", ("a",)
        )
    if p.b <= part.width:
        raise DegenerateDesign(
            f"exit chute width b = {p.b:g} is not wider than the part ({part.width:g})", ("b",)
        )
    if p.d < part.length + 2 * START_CLEARANCE:
        raise DegenerateDesign(
            f"input chute length d = {p.d:g} cannot hold the part (length {part.length:g})",
            ("d",),
        )
    if p.e >= -p.b / 2:
        raise DegenerateDesign(
            f"the left cavity wall (e = {p.e:g}) is not left of the exit chute "
            f"(-b/2 = {-p.b / 2:g})",
            ("e", "b"),
        )
    if p.gy <= p.c:
        raise DegenerateDesign(
            f"the lip (g.y = {p.gy:g}) is not above the cavity floor (c = {p.c:g})", ("gy", "c")
        )
    if not (math.isfinite(roof_rise) and 0.0 <= roof_rise <= 10.0):
        raise ValueError(f"roof_rise = {roof_rise!r} is outside the allowed range [0, 10]")
    edges = interior_edges(p, part, roof_rise)
    segments = _segments(edges)
    decided = _check_crossings(edges, segments)
    outline = np.ascontiguousarray(segments[:, 0])
    if not decided:  # a ring without crossings (all pairs certain) is a valid polygon
        interior = Polygon(outline)
        if not interior.is_valid or interior.area <= 0:
            raise DegenerateDesign("the walls do not enclose a cavity", ("e", "gx", "gy", "theta"))
    _check_tip(p, edges, segments)
    finger, tip = protuberance(p)

    mitred = _mitred(segments, WALL_THICKNESS)
    if mitred is None:
        wall_polygons = walls_reference(edges)
    else:
        wall_verts, wall_counts = mitred
        wall_polygons = [wall_verts[i, :k] for i, k in enumerate(wall_counts.tolist())]
    labels = [e.label for e in edges] + ["protuberance finger", "protuberance tip"]
    obstacles = Obstacles(tuple([*wall_polygons, finger]), tip.reshape(1, 3), tuple(labels))

    u = np.array([math.cos(p.theta), math.sin(p.theta)])
    nrm = np.array([-math.sin(p.theta), math.cos(p.theta)])
    centre = np.array([p.gx, p.gy]) + (p.d - part.length / 2 - START_CLEARANCE) * u + p.a / 2 * nrm
    starts: dict[str, Pose] = {}
    for orientation, yaw in zip(ORIENTATIONS, (p.theta + math.pi, p.theta), strict=True):
        yaw = wrap_angle(yaw)
        com = centre + part.com_offset * np.array([math.cos(yaw), math.sin(yaw)])
        starts[orientation] = (float(com[0]), float(com[1]), yaw)

    from feeders.wall_kernel import surely_apart  # numba on first build, not on import

    pieces = [*wall_polygons, finger]
    corners = np.array([_pose_vertices(part, pose) for pose in starts.values()])
    if mitred is None or not surely_apart(
        corners,
        *_with_finger(wall_verts, wall_counts, finger),
        tip,
        CLEARANCE,
        CLEARANCE_SLACK,
    ):
        placed = {o: Polygon(c) for o, c in zip(starts, corners, strict=True)}
        if not _clearly_apart(list(placed.values()), pieces, tip):
            disc = Point(p.fx, p.fy).buffer(p.r)
            solid = shapely.unary_union([Polygon(w) for w in pieces] + [disc])
            for orientation, shape in placed.items():
                if shape.intersection(solid).area > 1e-9:
                    raise DegenerateDesign(
                        f"the part does not fit at the top of the input chute ({orientation})",
                        ("a", "d", "theta"),
                    )

    depth = 2.0 * part.length
    heavy_below = part.length / 2 - part.com_offset
    goal = Goal(
        x_min=-p.b / 2,
        x_max=p.b / 2,
        y_min=-depth + heavy_below,
        y_max=-part.length,
        yaw=-math.pi / 2,
        yaw_tol=GOAL_YAW_TOL,
    )
    xmin, ymin = outline.min(axis=0)
    xmax, ymax = outline.max(axis=0)
    return Scene(
        name=name,
        obstacles=obstacles,
        part=part,
        bounds=(float(xmin), float(xmax), float(ymin), float(ymax)),
        starts=starts,
        goal=goal,
        gravity=gravity,
        friction=friction,
        restitution=restitution,
        inputs=inputs or InputSet(),
        design=design,
        outline=outline,
    )
