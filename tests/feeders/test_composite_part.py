"""Specification of feeders.composite_part and feeders.cup: parts made of convex polygons and
discs of their own densities (issue 24).

References: mass properties worked by hand (rectangle, disc, L, the cup's U) and, independently
of the shoelace formulas, shapely's constrained Delaunay triangles of the shape (area,
centroid, and each triangle's polar moment m (a^2 + b^2 + c^2) / 36 about its centroid);
feeders.part.two_density_moments for the peg; shapely for the convex split (union, areas,
overlaps); for the stable poses, statics worked by hand and the local minima of the height of
the centre of mass above the floor sampled over yaw (a brute-force reference that knows nothing
of hulls or feet of perpendiculars).
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import shapely

from feeders.composite_part import (
    CompositePart,
    CompositePartError,
    part_from_dict,
    split_outline,
    stable_poses,
)
from feeders.cup import CUP_HEIGHT, CUP_WALL, CUP_WIDTH, cup_part
from feeders.fields import FieldError, parse_yaml
from feeders.part import DEFAULT_PEG, PartError, Peg, two_density_moments

RECT = [[0, 0], [2, 0], [2, 0.3], [0, 0.3]]
L_OUTLINE = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]
U_OUTLINE = [
    [0, 0],
    [1, 0],
    [1, 0.9],
    [0.85, 0.9],
    [0.85, 0.15],
    [0.15, 0.15],
    [0.15, 0.9],
    [0, 0.9],
]


def _shapely_moments(polygon: shapely.Polygon, density: float = 1.0):
    """(mass, centroid, inertia about it) of a uniform polygon from shapely's constrained
    Delaunay triangles: each triangle's polar moment about its centroid is m (a^2+b^2+c^2)/36."""
    triangles = shapely.get_parts(shapely.constrained_delaunay_triangles(polygon))
    masses, centres, own = [], [], []
    for t in triangles:
        p = np.asarray(t.exterior.coords)[:3]
        m = density * t.area
        sides = np.sum((p - np.roll(p, 1, axis=0)) ** 2)
        masses.append(m)
        centres.append(p.mean(axis=0))
        own.append(m * sides / 36.0)
    masses, centres = np.array(masses), np.array(centres)
    mass = masses.sum()
    com = (masses[:, None] * centres).sum(axis=0) / mass
    return mass, com, sum(own) + np.sum(masses * np.sum((centres - com) ** 2, axis=1))


# --- mass properties ------------------------------------------------------------------------


def test_rectangle_by_hand():
    """2 x 0.3 plate of density 2: m = 2 * 0.6 = 1.2, centre (1, 0.15),
    I = m (2^2 + 0.3^2) / 12 = 1.2 * 4.09 / 12 = 0.409."""
    part = part_from_dict({"pieces": [{"polygon": RECT, "density": 2.0}]})
    assert part.mass == pytest.approx(1.2, rel=1e-12)
    np.testing.assert_allclose(part.com, [1.0, 0.15], rtol=1e-12)
    assert part.inertia == pytest.approx(0.409, rel=1e-12)


def test_disc_by_hand():
    """Disc of radius 0.2 and density 3: m = 3 pi 0.04 = 0.12 pi, I = m r^2 / 2 = 0.0024 pi."""
    part = part_from_dict({"pieces": [{"disc": {"centre": [1, 1], "radius": 0.2}, "density": 3}]})
    assert part.mass == pytest.approx(0.12 * math.pi, rel=1e-12)
    np.testing.assert_allclose(part.com, [1.0, 1.0], rtol=1e-12)
    assert part.inertia == pytest.approx(0.0024 * math.pi, rel=1e-12)


def test_plate_with_a_disc_on_it_by_hand():
    """The 2 x 0.3 plate (density 1, m1 = 0.6 at (1, 0.15), own 0.6 * 4.09 / 12) with a disc of
    radius 0.2 and density 3 resting on it at (1, 0.5) (m2 = 0.12 pi, own m2 0.02): the centre
    of mass on x = 1 at y = (0.6 * 0.15 + m2 * 0.5) / (0.6 + m2); parallel axis for each."""
    part = part_from_dict(
        {
            "pieces": [
                {"polygon": RECT, "density": 1.0},
                {"disc": {"centre": [1, 0.5], "radius": 0.2}, "density": 3.0},
            ]
        }
    )
    m1, m2 = 0.6, 0.12 * math.pi
    y = (m1 * 0.15 + m2 * 0.5) / (m1 + m2)
    inertia = m1 * 4.09 / 12 + m1 * (0.15 - y) ** 2 + m2 * 0.02 + m2 * (0.5 - y) ** 2
    assert part.mass == pytest.approx(m1 + m2, rel=1e-12)
    np.testing.assert_allclose(part.com, [1.0, y], rtol=1e-12)
    assert part.inertia == pytest.approx(inertia, rel=1e-12)
    assert part.bounding_radius() == pytest.approx(math.hypot(1.0, y), rel=1e-12)
    assert len(part.seams()) == 0  # a disc touching a plate shares a point, not an edge


def test_l_shape_by_hand():
    """The L: a 2 x 1 plate (m 2, centre (1, 0.5)) under a 1 x 1 (m 1, centre (0.5, 1.5)), density
    1: area 3, centre (5/6, 5/6); I = 2*5/12 + 2*(1/36 + 4/36) + 1*2/12 + 1*(4/36 + 16/36)
    = 11/6."""
    part = part_from_dict({"outline": L_OUTLINE, "density": 1.0})
    assert part.mass == pytest.approx(3.0, rel=1e-12)
    np.testing.assert_allclose(part.com, [5 / 6, 5 / 6], rtol=1e-12)
    assert part.inertia == pytest.approx(11 / 6, rel=1e-12)


def test_cup_by_hand():
    """The U of 1.0 x 0.9, walls and base 0.15 thick, mass 1 (area 2*0.135 + 0.105 = 0.375,
    density 8/3): walls m 0.36 at 0.45 from the rim, base m 0.28 at 0.825, so the centre of
    mass is 0.555 from the rim along the axis; I = 2*(0.36*(0.81 + 0.0225)/12 + 0.36*(0.105^2
    + 0.425^2)) + 0.28*(0.0225 + 0.49)/12 + 0.28*0.27^2 = 0.22030833..."""
    cup = cup_part()
    assert (CUP_WIDTH, CUP_HEIGHT, CUP_WALL) == (1.0, 0.9, 0.15)
    assert cup.area == pytest.approx(0.375, rel=1e-12)
    assert cup.mass == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_allclose(cup.com, [0.555, 0.0], atol=1e-12)
    walls = 2 * (0.36 * 0.8325 / 12 + 0.36 * (0.105**2 + 0.425**2))
    base = 0.28 * 0.5125 / 12 + 0.28 * 0.27**2
    assert cup.inertia == pytest.approx(walls + base, rel=1e-12)
    assert cup.inertia == pytest.approx(0.2203083333, rel=1e-9)


@pytest.mark.parametrize(
    "outline",
    [
        RECT,
        L_OUTLINE,
        U_OUTLINE,
        [[0, 0], [3, 0], [3, 2], [2, 2], [2, 1], [1, 1], [1, 3], [0, 3]],  # an E-ish zigzag
        [
            [1e3, 1e3],
            [1e3 + 2, 1e3],
            [1e3 + 1, 1e3 + 0.2],
            [1e3 + 1, 1e3 + 2],
        ],  # an arrow, far away
    ],
)
def test_uniform_outline_matches_shapely_triangles(outline):
    part = part_from_dict({"outline": outline, "density": 1.7})
    mass, com, inertia = _shapely_moments(shapely.Polygon(outline), 1.7)
    assert part.mass == pytest.approx(mass, rel=1e-10)
    np.testing.assert_allclose(part.com, com, rtol=1e-10)
    assert part.inertia == pytest.approx(inertia, rel=1e-8)


def test_densities_weight_the_pieces_as_shapely_does():
    """The L as two plates of densities 1 and 5 against the sum of shapely's moments of each."""
    part = part_from_dict(
        {
            "pieces": [
                {"polygon": [[0, 0], [2, 0], [2, 1], [0, 1]], "density": 1.0},
                {"polygon": [[0, 1], [1, 1], [1, 2], [0, 2]], "density": 5.0},
            ]
        }
    )
    (m1, c1, i1), (m2, c2, i2) = (
        _shapely_moments(shapely.box(0, 0, 2, 1), 1.0),
        _shapely_moments(shapely.box(0, 1, 1, 2), 5.0),
    )
    com = (m1 * c1 + m2 * c2) / (m1 + m2)
    inertia = i1 + i2 + m1 * np.sum((c1 - com) ** 2) + m2 * np.sum((c2 - com) ** 2)
    assert part.mass == pytest.approx(m1 + m2, rel=1e-12)
    np.testing.assert_allclose(part.com, com, rtol=1e-12)
    assert part.inertia == pytest.approx(inertia, rel=1e-10)


# --- the peg as a composite part ------------------------------------------------------------


@pytest.mark.parametrize(
    "length, width, mass, heavy_fraction",
    [(2.2, 0.7, 1.0, 0.9), (1.6, 1.0, 1.0, 0.75), (2.0, 1.0, 1.0, 0.5), (3.0, 0.5, 2.5, 0.6)],
)
def test_peg_is_two_rectangles_with_its_moments(length, width, mass, heavy_fraction):
    peg = Peg.two_density(length, width, mass, heavy_fraction)
    part = CompositePart.from_peg(peg)
    offset, inertia = two_density_moments(length, width, mass, heavy_fraction)
    assert part.mass == pytest.approx(mass, rel=1e-12)
    np.testing.assert_allclose(part.com, [offset, 0.0], atol=1e-12 * length)
    assert part.inertia == pytest.approx(inertia, rel=1e-12)
    union = shapely.union_all([shapely.Polygon(p) for p in part.body_polygons()])
    assert union.symmetric_difference(shapely.Polygon(peg.body_vertices())).area < 1e-12
    assert part.bounding_radius() == pytest.approx(peg.bounding_radius(), rel=1e-12)


def test_peg_halves_meet_at_one_seam():
    """The light and heavy halves share the segment across the peg at its geometric centre,
    which is -offset from the centre of mass in the body frame."""
    seams = CompositePart.from_peg(DEFAULT_PEG).seams()
    assert seams.shape == (1, 2, 2)
    c, hy = DEFAULT_PEG.com_offset, DEFAULT_PEG.width / 2
    ends = seams[0][np.argsort(seams[0][:, 1])]
    np.testing.assert_allclose(ends, [[-c, -hy], [-c, hy]], atol=1e-12)


def test_peg_with_all_mass_in_one_half_cannot_be_two_densities():
    with pytest.raises(CompositePartError, match="density"):
        CompositePart.from_peg(Peg.two_density(heavy_fraction=1.0))


def test_peg_with_another_inertia_is_refused():
    with pytest.raises(CompositePartError, match="inertia"):
        CompositePart.from_peg(Peg(inertia=DEFAULT_PEG.inertia * 1.5))


# --- splitting outlines into convex pieces --------------------------------------------------


def _star(seed: int, n: int = 24) -> np.ndarray:
    """A random star-shaped polygon (simple by construction: one vertex per angle)."""
    rng = np.random.default_rng(seed)
    angles = np.sort(rng.uniform(0, 2 * math.pi, n))
    radii = rng.uniform(0.3, 2.0, n)
    return np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])


@pytest.mark.parametrize(
    "outline",
    [L_OUTLINE, U_OUTLINE, U_OUTLINE[::-1]] + [_star(seed) for seed in range(8)],
    ids=["L", "U", "U clockwise"] + [f"star {seed}" for seed in range(8)],
)
def test_outline_splits_into_convex_pieces_that_tile_it(outline):
    pieces = split_outline(outline)
    shape = shapely.Polygon(outline)
    polygons = [shapely.Polygon(p) for p in pieces]
    for p in pieces:  # convex and counter-clockwise
        assert shapely.Polygon(p).convex_hull.area == pytest.approx(shapely.Polygon(p).area)
        assert shapely.LinearRing(p).is_ccw
    assert sum(p.area for p in polygons) == pytest.approx(shape.area, rel=1e-12)
    assert shapely.union_all(polygons).symmetric_difference(shape).area < 1e-9 * shape.area
    for i in range(len(polygons)):
        for j in range(i):
            assert polygons[i].intersection(polygons[j]).area < 1e-12
    assert len(pieces) <= len(outline) - 2  # no more than the triangles of an ear clipping


def test_u_splits_into_three_pieces_and_convex_outline_is_kept_whole():
    """Hertel-Mehlhorn merges the U's six triangles into three convex pieces (the fewest a U
    can have); a convex outline is one piece."""
    assert len(split_outline(U_OUTLINE)) == 3
    assert len(split_outline(RECT)) == 1


def test_outline_and_its_seams():
    """The L split: its pieces meet along internal diagonals, each a seam inside the L."""
    part = part_from_dict({"outline": L_OUTLINE, "density": 1.0})
    seams = part.seams()
    assert len(seams) == len(part.polygons) - 1  # a tree of pieces joined by one edge each
    shape = shapely.Polygon(np.array(L_OUTLINE, dtype=float) - part.com)
    for a, b in seams:
        assert shape.contains(shapely.Point((a + b) / 2))  # inside, not on the boundary


def test_cup_from_outline_has_the_same_mass_properties():
    outline = part_from_dict({"outline": U_OUTLINE, "density": 8 / 3})
    # the cup's frame: axis along x, open end at x = 0 (the outline's y = 0.9)
    cup = cup_part()
    assert outline.mass == pytest.approx(cup.mass, rel=1e-12)
    assert outline.inertia == pytest.approx(cup.inertia, rel=1e-12)
    np.testing.assert_allclose(outline.com, [0.5, 0.9 - 0.555], rtol=1e-12)
    assert len(cup.seams()) == 2  # each wall meets the base along one edge


# --- YAML -----------------------------------------------------------------------------------


def test_yaml_text_to_part():
    doc = parse_yaml(
        """
part:
  pieces:
    - {polygon: [[0, 0], [2, 0], [2, 0.3], [0, 0.3]], density: 1.0}
    - {disc: {centre: [1, 0.5], radius: 0.2}, density: 3.0}
    - {outline: [[2, 0], [3, 0], [3, 1], [2.5, 0.5], [2, 1]], density: 0.5}
"""
    )
    part = part_from_dict(doc["part"])
    assert part.labels[0] == "part.pieces[0]" and part.labels[-1] == "part.pieces[1]"
    assert part.mass == pytest.approx(0.6 + 0.12 * math.pi + 0.5 * 0.75, rel=1e-12)


def _error(data) -> str:
    with pytest.raises(CompositePartError) as info:
        part_from_dict(data)
    message = str(info.value)
    assert "\n" not in message, f"not one line: {message!r}"
    assert isinstance(info.value, PartError) and isinstance(info.value, FieldError)
    return message


BOWTIE = [[0, 0], [1, 1], [1, 0], [0, 1]]


@pytest.mark.parametrize(
    "data, expected",
    [
        ({"outline": BOWTIE, "density": 1}, r"part\.outline: the outline intersects itself"),
        ({"pieces": [{"polygon": BOWTIE, "density": 1}]}, r"pieces\[0\]\.polygon: .*intersects"),
        ({"outline": [[0, 0], [1, 0], [2, 0]], "density": 1}, r"part\.outline: .*zero area"),
        ({"pieces": [{"polygon": RECT, "density": 0}]}, r"pieces\[0\]\.density = 0\.0 is outside"),
        ({"pieces": [{"polygon": RECT, "density": -1}]}, r"pieces\[0\]\.density = -1\.0"),
        ({"outline": RECT, "density": 0.0}, r"part\.density = 0\.0 is outside the allowed range"),
        ({"pieces": [{"polygon": L_OUTLINE, "density": 1}]}, r"pieces\[0\]\.polygon: not convex"),
        (
            {
                "pieces": [
                    {"polygon": RECT, "density": 1},
                    {"disc": {"centre": [1, 0.5], "radius": 0}, "density": 1},
                ]
            },
            r"pieces\[1\]\.disc\.radius = 0\.0 is outside the allowed range",
        ),
        (
            {"pieces": [{"polygon": [[0, 0], [1, 0], [1, float("nan")]], "density": 1}]},
            r"pieces\[0\]\.polygon\[2\]\[1\] = nan is outside",
        ),
        (
            {"pieces": [{"polygon": [[0, 0], [1, 0], [1, float("inf")]], "density": 1}]},
            r"pieces\[0\]\.polygon\[2\]\[1\] = inf is outside",
        ),
        (
            {
                "pieces": [
                    {"polygon": RECT, "density": 1},
                    {"polygon": [[1, 0], [3, 0], [3, 1]], "density": 1},
                ]
            },
            r"part\.pieces\[1\] overlaps part\.pieces\[0\]; pieces may touch but not overlap",
        ),
        (
            {
                "pieces": [
                    {"polygon": RECT, "density": 1},
                    {"disc": {"centre": [1, 0.4], "radius": 0.2}, "density": 1},
                ]
            },
            r"part\.pieces\[1\] overlaps part\.pieces\[0\]",
        ),
        (
            {
                "pieces": [
                    {"polygon": RECT, "density": 1},
                    {"disc": {"centre": [1, 1], "radius": 0.2}, "density": 1},
                ]
            },
            r"^part\.pieces: they form 2 separate bodies",
        ),
        (
            {"pieces": [{"polygon": RECT, "density": 1, "colour": "red"}]},
            r"pieces\[0\]: unknown key",
        ),
        ({"pieces": [], "outline": RECT}, r"part: give exactly one of 'pieces' or 'outline'"),
        ({"outline": RECT}, r"part\.density is required"),
        ({"pieces": [{"polygon": RECT}]}, r"pieces\[0\]\.density is required"),
        (
            {"pieces": [{"polygon": RECT, "disc": {}, "density": 1}]},
            r"pieces\[0\]: give exactly one",
        ),
        ({"shape": RECT}, r"part: unknown key\(s\) \['shape'\]"),
        ({"outline": [[0, 0], [1, 0]], "density": 1}, r"part\.outline: expected a list of 3 to"),
    ],
    ids=[
        "self-intersecting outline",
        "self-intersecting polygon",
        "zero-area outline",
        "zero density",
        "negative density",
        "zero outline density",
        "non-convex polygon",
        "zero radius",
        "nan coordinate",
        "infinite coordinate",
        "overlapping polygons",
        "disc overlapping polygon",
        "disconnected",
        "unknown piece key",
        "pieces and outline",
        "outline without density",
        "piece without density",
        "two shapes in a piece",
        "unknown part key",
        "two points",
    ],
)
def test_bad_input_is_one_line_naming_the_field(data, expected):
    message = _error(data)
    assert re.search(expected, message), message


def test_prefix_names_the_field_where_it_is():
    with pytest.raises(CompositePartError, match=r"^scene\.part\.pieces\[0\]\.density"):
        part_from_dict({"pieces": [{"polygon": RECT, "density": 0}]}, prefix="scene.part.")


def test_pieces_that_touch_along_an_edge_are_one_body():
    part = part_from_dict(
        {
            "pieces": [
                {"polygon": [[0, 0], [1, 0], [1, 1], [0, 1]], "density": 1},
                {"polygon": [[1, 0.5], [2, 0.5], [2, 1.5], [1, 1.5]], "density": 2},
            ]
        }
    )
    assert part.mass == pytest.approx(3.0)
    np.testing.assert_allclose(
        np.sort(part.seams()[0][:, 1] + part.com[1]), [0.5, 1.0], atol=1e-12
    )  # the shared part of x = 1: y from 0.5 to 1


# --- stable poses ---------------------------------------------------------------------------


def _height(part: CompositePart, yaw: np.ndarray) -> np.ndarray:
    """Height of the centre of mass above a floor the part rests on, at each yaw: the largest
    extent of the part (its vertices; each disc's centre plus its radius) along the body
    direction that ``yaw`` turns to world -y."""
    down = np.column_stack([-np.sin(yaw), -np.cos(yaw)])
    h = np.full(len(yaw), -np.inf)
    for points in part.body_polygons():
        h = np.maximum(h, np.max(down @ points.T, axis=1))
    for x, y, r in part.body_discs():
        h = np.maximum(h, down @ np.array([x, y]) + r)
    return h


def _sampled_minima(part: CompositePart, n: int = 72_000) -> np.ndarray:
    """Yaws of the strict local minima of the centre of mass's height, on a grid of n yaws."""
    yaw = -math.pi + 2 * math.pi * np.arange(n) / n
    h = _height(part, yaw)
    before, after = np.roll(h, 1), np.roll(h, -1)
    return yaw[(h < before - 1e-12) & (h <= after)]


def _assert_poses_are_the_sampled_minima(part: CompositePart) -> None:
    predicted = np.array([pose.yaw for pose in stable_poses(part)])
    sampled = _sampled_minima(part)
    assert len(predicted) == len(sampled), (predicted, sampled)
    gap = np.abs((predicted[:, None] - sampled[None, :] + math.pi) % (2 * math.pi) - math.pi)
    assert np.all(gap.min(axis=1) < 2e-4)


def test_cup_rests_in_four_poses():
    """Statics by hand: the cup's hull is its 0.9 x 1.0 outer rectangle and its centre of mass
    lies strictly inside it (0.345 from the base, on the axis), so the foot of the perpendicular
    on every side falls strictly inside that side and all four are stable: base down (open end
    up, yaw -pi/2: the body x axis, rim -> base, points down), open end down on its two rims
    (yaw pi/2, the face spans the opening, touching at the rims only) and on either wall (yaw 0,
    -pi). Any U whose hull is a rectangle has these four; which of them a feeder reaches is the
    dynamics' business."""
    cup = cup_part()
    poses = {round(pose.yaw, 12): pose.face for pose in stable_poses(cup)}
    assert sorted(poses) == pytest.approx([-math.pi, -math.pi / 2, 0.0, math.pi / 2])
    base_down, rims_down = poses[round(-math.pi / 2, 12)], poses[round(math.pi / 2, 12)]
    np.testing.assert_allclose(base_down[:, 0], [0.345, 0.345], atol=1e-12)  # the base's face
    np.testing.assert_allclose(rims_down[:, 0], [-0.555, -0.555], atol=1e-12)  # the rim's line
    np.testing.assert_allclose(sorted(rims_down[:, 1]), [-0.5, 0.5], atol=1e-12)
    _assert_poses_are_the_sampled_minima(cup)


def test_triangle_with_an_overhang_tips_off_one_side():
    """Triangle (0,0), (4,0), (5,1): centre of mass (3, 1/3). On the edge (4,0)-(5,1) the foot
    of the perpendicular from it is at -2/3/sqrt(2) from (4,0), outside the edge: it tips over.
    On (0,0)-(4,0) the foot is at x = 3, and on (5,1)-(0,0) at (3*5 + 1/3)/26 = 0.59 of the
    edge: both stable."""
    part = CompositePart((np.array([[0.0, 0.0], [4.0, 0.0], [5.0, 1.0]]),), (1.0,))
    poses = stable_poses(part)
    assert len(poses) == 2
    assert poses[0].yaw == pytest.approx(0.0, abs=1e-12)  # the bottom edge down
    # (5,1) -> (0,0) has the outward normal (-1, 5)/sqrt(26); turning it to -y: yaw
    # -pi/2 - atan2(5, -1), plus a turn to lie in [-pi, pi)
    assert poses[1].yaw == pytest.approx(-math.pi / 2 - math.atan2(5.0, -1.0) + 2 * math.pi)
    _assert_poses_are_the_sampled_minima(part)


def test_two_touching_discs_rest_on_their_common_tangents():
    """Discs of radius 1 at (0, 0) and 0.2 at (0, 1.2), density 1: the centre of mass is on the
    axis at y = 0.04 pi * 1.2 / (1.04 pi) = 0.0462, inside both discs' extent along it, so the
    part rests on either common tangent, whose outward normals n satisfy n . (0, 1.2) = 1 - 0.2,
    n_y = 2/3, n_x = +-sqrt(5)/3; it cannot rest on either disc alone (the centre of mass is
    above the big disc's centre and below the small one's)."""
    part = CompositePart((), (), np.array([[0.0, 0.0, 1.0], [0.0, 1.2, 0.2]]), (1.0, 1.0))
    assert part.com[1] == pytest.approx(0.048 / 1.04, rel=1e-12)
    yaws = sorted(pose.yaw for pose in stable_poses(part))
    expected = sorted(
        (-math.pi / 2 - math.atan2(2 / 3, s * math.sqrt(5) / 3) + math.pi) % (2 * math.pi) - math.pi
        for s in (1, -1)
    )
    assert yaws == pytest.approx(expected, abs=1e-12)
    _assert_poses_are_the_sampled_minima(part)


def test_disc_with_weights_rests_on_its_arc():
    """A disc of radius 1 with two dense 0.1-wide plates on its rim at 60 degrees either side of
    its bottom: the centre of mass is below the disc's centre, and straight down the disc reaches
    further (to -1) than the plates (about -0.55), so it rests on its arc with the plates
    low, yaw 0; the face is the single point below the centre of mass."""
    plates = []
    for side in (1, -1):
        angle = -math.pi / 2 + side * math.pi / 3
        n = np.array([math.cos(angle), math.sin(angle)])
        t = np.array([-n[1], n[0]])
        plates.append(
            np.array([n - 0.05 * t, n + 0.05 * t, 1.1 * n + 0.05 * t, 1.1 * n - 0.05 * t])
        )
    part = CompositePart(tuple(plates), (20.0, 20.0), np.array([[0.0, 0.0, 1.0]]), (1.0,))
    assert part.com[1] < 0 and part.com[0] == pytest.approx(0.0, abs=1e-12)
    poses = stable_poses(part)
    on_arc = [pose for pose in poses if np.allclose(pose.face[0], pose.face[1])]
    assert len(on_arc) == 1 and on_arc[0].yaw == pytest.approx(0.0, abs=1e-12)
    np.testing.assert_allclose(on_arc[0].face[0], [0.0, -1.0 - part.com[1]], atol=1e-12)
    _assert_poses_are_the_sampled_minima(part)


def test_random_parts_rest_where_the_height_is_least():
    for seed in range(4):
        part = part_from_dict({"outline": _star(seed, 12).tolist(), "density": 1.0})
        _assert_poses_are_the_sampled_minima(part)


# --- body frame, hull ----------------------------------------------------------------------


def test_body_frame_has_the_centre_of_mass_at_its_origin():
    part = part_from_dict({"outline": U_OUTLINE, "density": 1.0})
    _, com, _ = _shapely_moments(
        shapely.union_all([shapely.Polygon(p) for p in part.body_polygons()])
    )
    np.testing.assert_allclose(com, [0.0, 0.0], atol=1e-12)
    hull = part.convex_hull()
    assert shapely.Polygon(hull).area == pytest.approx(0.9, rel=1e-12)
    assert part.bounding_radius() == pytest.approx(math.hypot(0.5, 0.9 - 0.345), rel=1e-12)


def test_hull_contains_the_discs():
    part = CompositePart((), (), np.array([[0.0, 0.0, 1.0], [0.0, 1.2, 0.2]]), (1.0, 1.0))
    hull = shapely.Polygon(part.convex_hull())
    for x, y, r in part.body_discs():
        assert hull.buffer(1e-12).contains(shapely.Point(x, y).buffer(r, 256))


def test_a_pieces_disc_is_written_circle_as_in_a_scene_file():
    """``circle:`` (a scene file's word for a disc) and ``disc:`` read the same part; both at
    once are refused naming the piece."""
    plate = [[0, 0], [2, 0], [2, 0.3], [0, 0.3]]
    disc = {"centre": [1, 0.5], "radius": 0.2}
    a = part_from_dict(
        {"pieces": [{"polygon": plate, "density": 1}, {"circle": disc, "density": 3}]}
    )
    b = part_from_dict({"pieces": [{"polygon": plate, "density": 1}, {"disc": disc, "density": 3}]})
    assert (a.mass, a.inertia, tuple(a.com)) == (b.mass, b.inertia, tuple(b.com))
    with pytest.raises(CompositePartError, match=r"part\.pieces\[0\]: give exactly one of"):
        part_from_dict({"pieces": [{"circle": disc, "disc": disc, "density": 1}]})


def test_parts_compare_by_value_so_a_family_equals_itself_read_again():
    """Two cups built apart are equal (and hash alike); a cup of another wall is not; a
    device family holding the cup equals the same file read again (helper report: families
    with a composite part never compared equal)."""
    from feeders.device_family import load_family, packaged_family

    assert cup_part() == cup_part() and hash(cup_part()) == hash(cup_part())
    assert cup_part() != cup_part(wall=0.1)
    path = packaged_family("fig1-cup")
    assert path is not None and load_family(path) == load_family(path)
