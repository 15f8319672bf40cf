"""A part made of pieces: convex polygons and discs, each of its own density (issue 24).

The two-density peg of :mod:`feeders.part` is one case (two rectangles,
:meth:`CompositePart.from_peg`); the paper's cup (Fig. 1) is another
(:func:`feeders.cup.cup_part`). Mass (density x area), centre of mass and the moment of inertia
about it (mass x length^2) come from the pieces by closed forms: a polygon's by the shoelace
formula and its second moments
(``int x^2 dA = 1/12 sum (x_i^2 + x_i x_{i+1} + x_{i+1}^2)(x_i y_{i+1} - x_{i+1} y_i)``),
a disc's ``m r^2 / 2``, moved to the part's centre of mass by the parallel-axis theorem.

Pieces are given in any frame (the *part frame*); the *body frame* is the part frame moved so
its origin is the centre of mass, axes unchanged, as for :class:`feeders.part.Peg` (a pose
``(x, y, yaw)`` places the body frame in the plane).

Rules (a part the levels can trust): pieces may touch (an edge shared by two polygons is an
internal *seam*, :meth:`CompositePart.seams`, which is not a surface of the part) but must not
overlap, since an overlap's density would be ambiguous (the sum? the later piece's?) and the
part's area would not be the area of its shape; and together they must form one connected body.
A simple polygon that is not convex (an *outline*) is split into convex pieces here
(:func:`split_outline`: ear clipping, then Hertel-Mehlhorn merging of triangles).

Every level takes such a part (:mod:`feeders.part_shape`, :class:`validity.scene_arrays.PartArrays`:
its pieces as convex polygons and discs, its seams no surface).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np
import shapely

from feeders.fields import FieldError, field_errors_as, mapping_field, number_field, numbers_field
from feeders.part import PartError, Peg, two_density_moments
from feeders.scene_checks import MAX_COORDINATE

DENSITY_RANGE = (1e-9, 1e9)  # mass per area
RADIUS_RANGE = (1e-9, 1e6)  # a disc's radius (length)
MAX_PIECES = 200
MAX_VERTICES = 200  # points of one polygon or outline: ear clipping is cubic in them
RELATIVE_TOLERANCE = 1e-9  # of the part's size: touching, collinear, overlapping


class CompositePartError(PartError, FieldError):
    """A part that cannot be built from its pieces; the message names the field (one line)."""


def _size(points: np.ndarray) -> float:
    return float(np.max(np.abs(points))) if points.size else 1.0


def _signed_area(v: np.ndarray) -> float:
    x, y = v[:, 0], v[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _cross(o: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    return float((a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]))


def _drop_straight(v: np.ndarray, tol: float) -> np.ndarray:
    """``v`` without vertices where the boundary goes straight on (a 180-degree corner)."""
    keep = [
        i
        for i in range(len(v))
        if abs(_cross(v[i - 1], v[i], v[(i + 1) % len(v)]))
        > tol * max(np.hypot(*(v[(i + 1) % len(v)] - v[i - 1])), 1e-300)
    ]
    return v[keep]


def _reflex_corner(v: np.ndarray, tol: float) -> int | None:
    """Index of the first corner of CCW ``v`` that turns clockwise (by more than ``tol``)."""
    for i in range(len(v)):
        a, b, c = v[i - 1], v[i], v[(i + 1) % len(v)]
        if _cross(a, b, c) < -tol * max(np.hypot(*(c - a)), 1e-300):
            return i
    return None


def _in_triangle(p: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> bool:
    """``p`` inside CCW triangle abc or on its boundary."""
    return _cross(a, b, p) >= 0 and _cross(b, c, p) >= 0 and _cross(c, a, p) >= 0


def _ear_clip(v: np.ndarray, field_name: str) -> list[list[int]]:
    """Triangles (vertex indices, CCW) of a simple CCW polygon without straight corners."""
    index = list(range(len(v)))
    triangles = []
    while len(index) > 3:
        for k in range(len(index)):
            i0, i1, i2 = index[k - 1], index[k], index[(k + 1) % len(index)]
            if _cross(v[i0], v[i1], v[i2]) <= 0:
                continue
            if any(_in_triangle(v[j], v[i0], v[i1], v[i2]) for j in index if j not in (i0, i1, i2)):
                continue
            triangles.append([i0, i1, i2])
            index.pop(k)
            break
        else:
            raise CompositePartError(
                f"{field_name}: the outline could not be split into triangles; "
                "give a simple polygon (edges that do not cross or touch)"
            )
    if _cross(v[index[0]], v[index[1]], v[index[2]]) > 0:
        triangles.append(index)
    return triangles


def _merge(p: list[int], q: list[int], a: int, b: int) -> list[int]:
    """Pieces ``p`` (with edge a->b) and ``q`` (with b->a) as one cycle without edge ab."""
    ip, iq = p.index(b), q.index(a)
    p_from_b = p[ip:] + p[:ip]  # b ... a
    q_from_a = q[iq:] + q[:iq]  # a ... b
    return p_from_b + q_from_a[1:-1]


def _hertel_mehlhorn(v: np.ndarray, pieces: list[list[int]], tol: float) -> list[list[int]]:
    """Merge pieces across shared diagonals while the merged piece stays convex (at most four
    times the fewest convex pieces, Hertel and Mehlhorn 1983)."""
    merged = True
    while merged:
        merged = False
        owner = {
            (p[k], p[(k + 1) % len(p)]): i for i, p in enumerate(pieces) for k in range(len(p))
        }
        for (a, b), i in owner.items():
            j = owner.get((b, a))
            if j is None or j == i:
                continue
            candidate = _merge(pieces[i], pieces[j], a, b)
            if _reflex_corner(v[candidate], tol) is None:
                pieces = [p for k, p in enumerate(pieces) if k not in (i, j)] + [candidate]
                merged = True
                break
    return pieces


def split_outline(points: Any, field_name: str = "outline") -> list[np.ndarray]:
    """A simple polygon (convex or not, either orientation) as convex CCW pieces whose union is
    the polygon and which do not overlap: itself when convex, else ear clipping then
    Hertel-Mehlhorn merging. Refuses (one line naming ``field_name``) fewer than 3 points,
    non-finite or huge coordinates, zero area and a self-intersecting outline."""
    v = _simple_ccw(_points(points, field_name), field_name, "outline", "a simple polygon")
    tol = RELATIVE_TOLERANCE * _size(v)
    v = _drop_straight(v, tol)
    if _reflex_corner(v, tol) is None:
        return [v]
    pieces = _hertel_mehlhorn(v, _ear_clip(v, field_name), tol)
    return [v[p] for p in pieces]


def _points(points: Any, field_name: str) -> np.ndarray:
    """``points`` as an (N, 2) array of finite coordinates within +-MAX_COORDINATE, N >= 3."""
    try:
        v = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise CompositePartError(f"{field_name}: expected a list of [x, y] points") from None
    if v.ndim != 2 or v.shape[1] != 2 or len(v) < 3:
        raise CompositePartError(
            f"{field_name}: a polygon needs at least 3 points [x, y], got shape {v.shape}"
        )
    if len(v) > MAX_VERTICES:
        raise CompositePartError(
            f"{field_name}: {len(v)} points; at most {MAX_VERTICES} are allowed"
        )
    if not np.all(np.isfinite(v)) or np.max(np.abs(v)) > MAX_COORDINATE:
        raise CompositePartError(
            f"{field_name}: coordinates must be finite numbers within +-{MAX_COORDINATE:g}"
        )
    return v


def _simple_ccw(v: np.ndarray, field_name: str, what: str, allowed: str) -> np.ndarray:
    """``v`` counter-clockwise, if it encloses some area and its edges do not cross or touch."""
    size = _size(v)
    if shapely.MultiPoint(v).convex_hull.area <= RELATIVE_TOLERANCE * size * size:
        raise CompositePartError(
            f"{field_name}: the {what} has zero area (its points are on one line); "
            f"give {allowed} that encloses some"
        )
    if not shapely.LinearRing(v).is_simple:
        raise CompositePartError(
            f"{field_name}: the {what} intersects itself; give {allowed} "
            "(edges that do not cross or touch)"
        )
    return v if _signed_area(v) > 0 else v[::-1].copy()


def _polygon_moments(v: np.ndarray) -> tuple[float, np.ndarray, float]:
    """(area, centroid, polar second moment of area about the centroid) of CCW ``v``."""
    o = v.mean(axis=0)
    p = v - o  # about a point inside: no cancellation for a polygon far from the origin
    x, y = p[:, 0], p[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = 0.5 * float(cross.sum())
    cx = float(((x + xn) * cross).sum()) / (6.0 * area)
    cy = float(((y + yn) * cross).sum()) / (6.0 * area)
    polar = float(((x * x + x * xn + xn * xn + y * y + y * yn + yn * yn) * cross).sum()) / 12.0
    return area, o + np.array([cx, cy]), polar - area * (cx * cx + cy * cy)


@dataclass(frozen=True, eq=False)
class CompositePart:
    """A rigid planar part: convex polygons (``(K_i, 2)`` CCW, part frame) and discs
    (``(D, 3)``: cx, cy, radius), with their densities (mass per area) and ``labels`` naming
    each polygon then each disc in errors (``part.pieces[2]``). Two parts are equal when
    their pieces, densities and labels are (by value: so a device family that holds one
    compares equal to the same family read again).

    Computed: ``mass``, ``com`` (part frame), ``inertia`` about the centre of mass
    (mass x length^2) and ``area``. A polygon given clockwise is stored counter-clockwise.
    """

    polygons: tuple[np.ndarray, ...]
    polygon_densities: tuple[float, ...]
    discs: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    disc_densities: tuple[float, ...] = ()
    labels: tuple[str, ...] = ()
    mass: float = field(init=False)
    com: np.ndarray = field(init=False)
    inertia: float = field(init=False)
    area: float = field(init=False)

    def __post_init__(self) -> None:
        discs = np.asarray(self.discs, dtype=float).reshape(-1, 3)
        n_poly, n_disc = len(self.polygons), len(discs)
        labels = self.labels or tuple(
            [f"polygons[{i}]" for i in range(n_poly)] + [f"discs[{i}]" for i in range(n_disc)]
        )
        if len(labels) != n_poly + n_disc:
            raise CompositePartError(f"labels: {len(labels)} for {n_poly + n_disc} pieces")
        if not 1 <= n_poly + n_disc <= MAX_PIECES:
            raise CompositePartError(
                f"pieces: {n_poly + n_disc} given; a part has 1 to {MAX_PIECES} pieces"
            )
        if len(self.polygon_densities) != n_poly or len(self.disc_densities) != n_disc:
            raise CompositePartError("densities: one per polygon and one per disc")
        polygons = tuple(_convex_piece(p, labels[i]) for i, p in enumerate(self.polygons))
        for k, (cx, cy, r) in enumerate(discs):
            label = labels[n_poly + k]
            with field_errors_as(CompositePartError):
                for name, value in (("x", cx), ("y", cy)):
                    number_field(value, f"{label}.centre.{name}", -MAX_COORDINATE, MAX_COORDINATE)
                number_field(r, f"{label}.radius", *RADIUS_RANGE)
        densities = tuple(
            _density(d, labels[i])
            for i, d in enumerate(tuple(self.polygon_densities) + tuple(self.disc_densities))
        )
        object.__setattr__(self, "polygons", polygons)
        object.__setattr__(self, "discs", discs)
        object.__setattr__(self, "labels", labels)
        object.__setattr__(self, "polygon_densities", densities[:n_poly])
        object.__setattr__(self, "disc_densities", densities[n_poly:])
        _check_layout(polygons, discs, labels)
        masses, centres, own = [], [], []
        for v, rho in zip(polygons, densities[:n_poly], strict=True):
            a, c, j = _polygon_moments(v)
            masses.append(rho * a)
            centres.append(c)
            own.append(rho * j)
        for (cx, cy, r), rho in zip(discs, densities[n_poly:], strict=True):
            m = rho * math.pi * r * r
            masses.append(m)
            centres.append(np.array([cx, cy]))
            own.append(0.5 * m * r * r)
        m_all = np.array(masses)
        c_all = np.array(centres)
        mass = float(m_all.sum())
        com = (m_all[:, None] * c_all).sum(axis=0) / mass
        inertia = float(np.sum(own) + np.sum(m_all * np.sum((c_all - com) ** 2, axis=1)))
        area = sum(_signed_area(v) for v in polygons) + float(np.sum(math.pi * discs[:, 2] ** 2))
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "com", com)
        object.__setattr__(self, "inertia", inertia)
        object.__setattr__(self, "area", area)

    @classmethod
    def from_peg(cls, peg: Peg) -> CompositePart:
        """The two-density peg as two rectangles (light half x < 0, heavy half x > 0 of the
        peg's geometric centre), with the peg's mass, centre-of-mass offset and inertia. A peg
        whose inertia is not that of two uniform halves, or whose light half has no mass
        (heavy fraction 1), cannot be one."""
        length, width = peg.length, peg.width
        heavy_fraction = 0.5 + 2.0 * peg.com_offset / length  # offset = (2f - 1) L / 4
        _, inertia = two_density_moments(length, width, peg.mass, heavy_fraction)
        if not math.isclose(inertia, peg.inertia, rel_tol=1e-9):
            raise CompositePartError(
                f"peg: inertia {peg.inertia:g} is not that of two uniform halves ({inertia:g})"
            )
        half = length / 2.0 * width
        hx, hy = length / 2.0, width / 2.0
        light = np.array([[-hx, -hy], [0.0, -hy], [0.0, hy], [-hx, hy]])
        heavy = np.array([[0.0, -hy], [hx, -hy], [hx, hy], [0.0, hy]])
        return cls(
            (light, heavy),
            ((1.0 - heavy_fraction) * peg.mass / half, heavy_fraction * peg.mass / half),
            labels=("peg light half", "peg heavy half"),
        )

    def _key(self) -> tuple:
        return (
            tuple(v.tobytes() for v in self.polygons),
            tuple(v.shape for v in self.polygons),
            self.polygon_densities,
            self.discs.tobytes(),
            self.disc_densities,
            self.labels,
        )

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, CompositePart):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def body_polygons(self) -> tuple[np.ndarray, ...]:
        """The convex pieces in the body frame (origin at the centre of mass), CCW."""
        return tuple(v - self.com for v in self.polygons)

    def body_discs(self) -> np.ndarray:
        """The discs in the body frame, ``(D, 3)``: cx, cy, radius."""
        discs = self.discs.copy()
        discs[:, :2] -= self.com
        return discs

    def bounding_radius(self) -> float:
        """Largest distance from the centre of mass to a point of the part."""
        radii = [float(np.max(np.hypot(*v.T))) for v in self.body_polygons()]
        radii += [float(np.hypot(x, y) + r) for x, y, r in self.body_discs()]
        return max(radii)

    def convex_hull(self, disc_sides: int = 64) -> np.ndarray:
        """The convex hull in the body frame, CCW ``(H, 2)``: exact for polygons; each disc is
        replaced by the regular ``disc_sides``-gon around it (the hull then contains the part,
        and is at most ``r (1/cos(pi/disc_sides) - 1)`` larger)."""
        points = list(self.body_polygons())
        angles = 2.0 * math.pi * np.arange(disc_sides) / disc_sides
        ring = np.column_stack([np.cos(angles), np.sin(angles)]) / math.cos(math.pi / disc_sides)
        points += [np.array([x, y]) + r * ring for x, y, r in self.body_discs()]
        hull = shapely.MultiPoint(np.vstack(points)).convex_hull
        v = np.asarray(hull.exterior.coords)[:-1]
        return v if _signed_area(v) > 0 else v[::-1].copy()

    def seams(self) -> np.ndarray:
        """Internal seams in the body frame, ``(S, 2, 2)``: the parts of edges that two
        polygon pieces share (collinear, opposite directions, overlapping by more than the
        tolerance). They lie inside the part: a contact kernel must not treat them as surface."""
        tol = RELATIVE_TOLERANCE * self.bounding_radius()
        found = []
        body = self.body_polygons()
        for i in range(len(body)):
            for j in range(i + 1, len(body)):
                found += _shared_edges(body[i], body[j], tol)
        return np.array(found, dtype=float).reshape(-1, 2, 2)


def _density(value: Any, label: str) -> float:
    with field_errors_as(CompositePartError):
        return number_field(value, f"{label}.density", *DENSITY_RANGE)


def _convex_piece(points: Any, label: str) -> np.ndarray:
    """``points`` as a convex CCW polygon of positive area, else one line naming ``label``."""
    field_name = f"{label}.polygon"
    v = _simple_ccw(_points(points, field_name), field_name, "polygon", "a convex polygon")
    tol = RELATIVE_TOLERANCE * _size(v)
    corner = _reflex_corner(v, tol)
    if corner is not None:
        raise CompositePartError(
            f"{field_name}: not convex (reflex corner at point {corner}); give a convex polygon, "
            "or a non-convex one as 'outline' (split into convex pieces)"
        )
    return v


def _shared_edges(p: np.ndarray, q: np.ndarray, tol: float) -> list[np.ndarray]:
    """Segments where an edge of ``p`` and an edge of ``q`` lie on one line, run opposite ways
    and overlap by more than ``tol``."""
    out = []
    for a, b in zip(p, np.roll(p, -1, axis=0), strict=True):
        length = float(np.hypot(*(b - a)))
        t = (b - a) / length
        for c, d in zip(q, np.roll(q, -1, axis=0), strict=True):
            if abs(_cross(a, b, c)) > tol * length or abs(_cross(a, b, d)) > tol * length:
                continue
            if float(np.dot(d - c, t)) >= 0:
                continue
            s = sorted([float(np.dot(c - a, t)), float(np.dot(d - a, t))])
            lo, hi = max(0.0, s[0]), min(length, s[1])
            if hi - lo > tol:
                out.append(np.array([a + lo * t, a + hi * t]))
    return out


def _check_layout(
    polygons: tuple[np.ndarray, ...], discs: np.ndarray, labels: tuple[str, ...]
) -> None:
    """Refuse overlapping pieces and a part in several bodies (pieces may touch)."""
    shapes: list[Any] = [shapely.Polygon(v) for v in polygons]
    shapes += [shapely.Point(x, y) for x, y, _ in discs]
    radii = [0.0] * len(polygons) + [float(r) for r in discs[:, 2]]
    size = max(
        [_size(v) for v in polygons]
        + [float(np.max(np.abs(discs[:, :2]) + discs[:, 2:])) if len(discs) else 0.0]
    )
    tol = RELATIVE_TOLERANCE * size
    n = len(shapes)
    parent = list(range(n))

    def root(i: int) -> int:
        while parent[i] != i:
            i = parent[i]
        return i

    for i in range(n):
        for j in range(i):
            gap = float(shapes[i].distance(shapes[j])) - radii[i] - radii[j]
            if gap <= tol:
                parent[root(i)] = root(j)
            if _overlap(shapes[i], shapes[j], radii[i], radii[j], gap, tol):
                raise CompositePartError(
                    f"{labels[i]} overlaps {labels[j]}; pieces may touch but not overlap "
                    "(split them so each point of the part has one density)"
                )
    bodies = len({root(i) for i in range(n)})
    if bodies > 1:
        raise CompositePartError(
            f"pieces: they form {bodies} separate bodies; a part is one connected body "
            "(pieces must touch)"
        )


def _overlap(a: Any, b: Any, ra: float, rb: float, gap: float, tol: float) -> bool:
    if ra == 0.0 and rb == 0.0:  # two polygons
        return float(a.intersection(b).area) > tol * math.sqrt(min(a.area, b.area))
    if ra > 0.0 and rb > 0.0:  # two discs
        return gap < -tol
    polygon, centre = (a, b) if ra == 0.0 else (b, a)
    return bool(polygon.contains(centre)) or gap < -tol


# --- YAML ---------------------------------------------------------------------------------

_PIECE_KEYS = {"polygon", "outline", "circle", "disc", "density"}  # 'disc': 'circle' as before


def part_from_dict(data: Any, prefix: str = "part.") -> CompositePart:
    """The part described by a YAML-shaped mapping: ``pieces`` (a list of ``{polygon: [[x, y],
    ...], density: d}`` for a convex polygon, ``{outline: [...], density: d}`` for any simple
    polygon, split into convex pieces, or ``{circle: {centre: [x, y], radius: r}, density: d}``
    for a disc, written as a scene file's circles; ``disc:`` is taken for it too), or
    ``outline`` with ``density`` for a uniform simple polygon. Errors are one line naming the
    field with ``prefix`` before it (:class:`CompositePartError`)."""
    where = prefix.rstrip(".") or "part"
    with field_errors_as(CompositePartError):
        data = mapping_field(data, where, {"pieces", "outline", "density"})
        if ("pieces" in data) == ("outline" in data):
            raise CompositePartError(f"{where}: give exactly one of 'pieces' or 'outline'")
        if "outline" in data:
            if "density" not in data:
                raise CompositePartError(f"{prefix}density is required with {prefix}outline")
            items = [{"outline": data["outline"], "density": data["density"]}]
            names = [where]
        else:
            if "density" in data:
                raise CompositePartError(
                    f"{prefix}density: give each piece its density ({prefix}pieces[i].density)"
                )
            items = data["pieces"]
            if not isinstance(items, list) or not 1 <= len(items) <= MAX_PIECES:
                raise CompositePartError(
                    f"{prefix}pieces: expected a list of 1 to {MAX_PIECES} pieces"
                )
            names = [f"{prefix}pieces[{i}]" for i in range(len(items))]
        polygons, poly_rho, poly_labels, discs, disc_rho, disc_labels = [], [], [], [], [], []
        for item, name in zip(items, names, strict=True):
            item = mapping_field(item, name, _PIECE_KEYS)
            shapes = sorted({"polygon", "outline", "circle", "disc"} & set(item))
            if len(shapes) != 1:
                raise CompositePartError(
                    f"{name}: give exactly one of 'polygon', 'outline' or 'circle', and 'density'"
                )
            if "density" not in item:
                raise CompositePartError(f"{name}.density is required")
            rho = number_field(item["density"], f"{name}.density", *DENSITY_RANGE)
            if shapes[0] in ("circle", "disc"):
                key = f"{name}.{shapes[0]}"
                disc = mapping_field(item[shapes[0]], key, {"centre", "radius"})
                if "centre" not in disc or "radius" not in disc:
                    raise CompositePartError(f"{key}: needs 'centre' and 'radius'")
                cx, cy = numbers_field(disc["centre"], f"{key}.centre", 2)
                r = number_field(disc["radius"], f"{key}.radius", *RADIUS_RANGE)
                discs.append((cx, cy, r))
                disc_rho.append(rho)
                disc_labels.append(name)
                continue
            key = shapes[0]
            points = _yaml_points(item[key], f"{name}.{key}")
            pieces = split_outline(points, f"{name}.outline") if key == "outline" else [points]
            polygons += pieces
            poly_rho += [rho] * len(pieces)
            poly_labels += [name] * len(pieces)
        try:
            return CompositePart(
                tuple(polygons),
                tuple(poly_rho),
                np.array(discs, dtype=float).reshape(-1, 3),
                tuple(disc_rho),
                tuple(poly_labels + disc_labels),
            )
        except CompositePartError as exc:
            if str(exc).startswith("pieces:"):  # the whole part's fault: name its field
                raise CompositePartError(f"{prefix}{exc}") from None
            raise


def _yaml_points(value: Any, field_name: str) -> np.ndarray:
    if not isinstance(value, list) or not 3 <= len(value) <= MAX_VERTICES:
        raise CompositePartError(
            f"{field_name}: expected a list of 3 to {MAX_VERTICES} [x, y] points"
        )
    return np.array([numbers_field(p, f"{field_name}[{k}]", 2) for k, p in enumerate(value)])


# --- statics ------------------------------------------------------------------------------


class StablePose(NamedTuple):
    """A statically stable resting orientation on a horizontal floor (gravity along -y).

    ``yaw`` places the body frame (rad, in [-pi, pi)); ``face`` is the segment of the part on
    the floor, ``(2, 2)`` in the body frame (one point twice when a disc rests on it)."""

    yaw: float
    face: np.ndarray


def _yaw_putting_down(direction: np.ndarray) -> float:
    """The yaw that turns body ``direction`` to world (0, -1)."""
    yaw = -0.5 * math.pi - math.atan2(direction[1], direction[0])
    return (yaw + math.pi) % (2.0 * math.pi) - math.pi


def stable_poses(part: CompositePart) -> list[StablePose]:
    """The statically stable resting orientations of ``part`` on a horizontal floor.

    Resting on an edge of its convex hull is stable when the foot of the perpendicular from the
    centre of mass lies strictly inside that edge (the centre of mass is above the support, and
    tipping about either end raises it); resting on a disc's arc of the hull is stable when the
    centre of mass lies strictly between the disc's centre and the floor (rolling raises it). A
    centre of mass on a disc's centre (neutral: it rolls freely) and one above an end of an
    edge (tipping point) are not stable. The hull is exact here, discs included: its edges are
    the common tangents of its circles (a polygon vertex is a circle of radius 0).
    """
    centres = np.vstack([*part.body_polygons(), part.body_discs()[:, :2]])
    radii = np.concatenate([np.zeros(sum(len(v) for v in part.polygons)), part.discs[:, 2]])
    tol = RELATIVE_TOLERANCE * part.bounding_radius()
    poses: list[StablePose] = []
    seen: list[np.ndarray] = []
    for i in range(len(centres)):
        for j in range(len(centres)):
            d = centres[j] - centres[i]
            length = float(np.hypot(*d))
            if length <= abs(radii[j] - radii[i]) + tol:
                continue  # the same point, or one circle inside the other
            u = d / length
            alpha = (radii[i] - radii[j]) / length
            # the outward normal with the pair on its left going i -> j (each pair once a way)
            n = alpha * u + math.sqrt(1.0 - alpha * alpha) * np.array([u[1], -u[0]])
            support = centres @ n + radii
            if np.any(support > support[i] + tol) or any(np.dot(n, s) > 1 - 1e-12 for s in seen):
                continue
            seen.append(n)
            on = support >= support[i] - tol
            tangent = np.array([-n[1], n[0]])
            s = (centres[on] + radii[on, None] * n) @ tangent
            if s.min() + tol < 0.0 < s.max() - tol:  # the centre of mass (origin) projects inside
                foot = np.array([s.min(), s.max()])[:, None] * tangent + support[i] * n
                poses.append(StablePose(_yaw_putting_down(n), foot))
    n_vertices = len(centres) - len(part.discs)
    for k in range(n_vertices, len(centres)):
        c, r = centres[k], radii[k]
        distance = float(np.hypot(*c))
        if distance <= tol:
            continue  # neutral
        down = -c / distance  # the centre of mass between the disc's centre and the floor
        support = centres @ down + radii
        others = np.delete(support, k)
        if others.size and np.max(others) >= support[k] - tol:
            continue
        point = c + r * down
        poses.append(StablePose(_yaw_putting_down(down), np.array([point, point])))
    return sorted(poses, key=lambda pose: pose.yaw)
